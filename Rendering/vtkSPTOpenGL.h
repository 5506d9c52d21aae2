/**
 * @file    vtkSPTOpenGL.h
 * @brief   the OpenGL loader header of the VTK this project is built against
 *
 * VTK 9.4 replaced GLEW (vtk_glew.h, modules VTK::glew and VTK::opengl) with glad (vtk_glad.h,
 * module VTK::glad). The project's sources include this header for the OpenGL declarations;
 * the CMake code links the matching modules (SPT_VTK_OPENGL_LOADER in the root CMakeLists.txt).
 *
 * Private header of the SPT module and its tests; not installed.
 */

#ifndef vtkSPTOpenGL_h
#define vtkSPTOpenGL_h

#include "vtkVersionMacros.h" // For VTK_VERSION_NUMBER

#if VTK_VERSION_NUMBER >= VTK_VERSION_CHECK(9, 4, 0)
#include "vtk_glad.h" // For the OpenGL declarations (glad)
#else
#include "vtk_glew.h" // For the OpenGL declarations (GLEW)
#endif

#endif
// VTK-HeaderTest-Exclude: vtkSPTOpenGL.h
