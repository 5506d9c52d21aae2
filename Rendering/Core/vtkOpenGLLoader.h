/**
 * @file    vtkOpenGLLoader.h
 * @brief   the OpenGL loader header of the VTK this project is built against
 *
 * VTK 9.4 replaced GLEW (vtk_glew.h, modules VTK::glew and VTK::opengl) with glad (vtk_glad.h,
 * module VTK::glad). The project's sources include this header for the OpenGL declarations;
 * the CMake code links the matching modules (SPT_VTK_OPENGL_LOADER in the root CMakeLists.txt).
 * The capability queries below ask the current context itself, so they read the same with
 * either loader (GLEW's GLEW_VERSION_x_y and glad's GLAD_GL_VERSION_x_y differ).
 *
 * Private header of SPT::RenderingCore, used by the project's modules and tests; not installed.
 */

#ifndef vtkOpenGLLoader_h
#define vtkOpenGLLoader_h

#include "vtkVersionMacros.h" // For VTK_VERSION_NUMBER

#if VTK_VERSION_NUMBER >= VTK_VERSION_CHECK(9, 4, 0)
#include "vtk_glad.h" // For the OpenGL declarations (glad)
#else
#include "vtk_glew.h" // For the OpenGL declarations (GLEW)
#endif

#include <cstddef> // For size_t
#include <cstring> // For std::strcmp

namespace vtkOpenGLLoader
{
/// The current context's OpenGL version (GL_MAJOR_VERSION and GL_MINOR_VERSION), as major and
/// minor; 0.0 when the context does not tell (OpenGL 2 and older).
inline void GetVersion(int& major, int& minor)
{
  GLint values[2] = { 0, 0 };
  glGetIntegerv(GL_MAJOR_VERSION, &values[0]);
  glGetIntegerv(GL_MINOR_VERSION, &values[1]);
  if (glGetError() != GL_NO_ERROR)
  {
    values[0] = values[1] = 0;
  }
  major = values[0];
  minor = values[1];
}

/// Whether the current context is OpenGL major.minor or later.
inline bool HasVersion(int major, int minor)
{
  int contextMajor = 0, contextMinor = 0;
  GetVersion(contextMajor, contextMinor);
  return contextMajor > major || (contextMajor == major && contextMinor >= minor);
}

/// The most texels a side of a 3D texture may have in the current context
/// (GL_MAX_3D_TEXTURE_SIZE: 2048 on Mesa's llvmpipe and many GPUs).
inline int Max3DTextureSize()
{
  GLint size = 0;
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &size);
  return size;
}

/// Whether the current context lists the extension (GL_EXTENSIONS, one by one: core profile).
inline bool HasExtension(const char* name)
{
  GLint count = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &count);
  for (GLint i = 0; i < count; ++i)
  {
    const char* extension = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, i));
    if (extension && std::strcmp(extension, name) == 0)
    {
      return true;
    }
  }
  return false;
}

/// The free memory of the current context's device in bytes, where its driver says
/// (GL_NVX_gpu_memory_info, GL_ATI_meminfo: both in KiB); 0 where it does not.
inline size_t FreeDeviceMemoryBytes()
{
  GLint kib[4] = { 0, 0, 0, 0 };
  if (HasExtension("GL_NVX_gpu_memory_info"))
  {
    glGetIntegerv(0x9049, kib); // GL_GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX
  }
  else if (HasExtension("GL_ATI_meminfo"))
  {
    glGetIntegerv(0x87FC, kib); // GL_TEXTURE_FREE_MEMORY_ATI: the pool's free memory first
  }
  return glGetError() == GL_NO_ERROR && kib[0] > 0 ? size_t(kib[0]) * 1024 : 0;
}

/// The bits per channel of the color buffer that the bound draw framebuffer draws into first
/// (its draw buffer 0): 8 for RGBA8; 0 for floating-point channels, which round nothing that
/// matters. 8 when the context does not tell.
inline int DrawColorBits()
{
  GLint framebuffer = 0;
  GLint buffer = GL_NONE;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
  glGetIntegerv(GL_DRAW_BUFFER0, &buffer);
  // The default framebuffer names its attachments by side: a double-buffered window draws
  // into GL_BACK, whose channels are GL_BACK_LEFT's.
  if (framebuffer == 0 && (buffer == GL_BACK || buffer == GL_FRONT))
  {
    buffer = buffer == GL_BACK ? GL_BACK_LEFT : GL_FRONT_LEFT;
  }
  GLint bits = 0;
  GLint type = GL_NONE;
  if (glGetError() == GL_NO_ERROR && buffer != GL_NONE)
  {
    glGetFramebufferAttachmentParameteriv(
      GL_DRAW_FRAMEBUFFER, static_cast<GLenum>(buffer), GL_FRAMEBUFFER_ATTACHMENT_RED_SIZE, &bits);
    glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, static_cast<GLenum>(buffer),
      GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE, &type);
  }
  if (glGetError() != GL_NO_ERROR || bits <= 0)
  {
    return 8;
  }
  return type == GL_FLOAT ? 0 : bits;
}
}

#endif
// VTK-HeaderTest-Exclude: vtkOpenGLLoader.h
