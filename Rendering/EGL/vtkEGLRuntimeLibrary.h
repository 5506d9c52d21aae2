/**
 * @file vtkEGLRuntimeLibrary.h
 * @brief The EGL functions this module calls, from libEGL.so.1 opened at run time.
 *
 * Built with SPT_EGL_RUNTIME_LIBRARY (the wheel): the module then links no libEGL, as PyPI's vtk
 * wheel links none (its glad loader opens libEGL when a window asks for it), so that a wheel of
 * the module needs no library outside the manylinux policy. The functions keep EGL's names and
 * signatures, hidden in this module: the window's code is the same either way. Without libEGL on
 * the machine each function fails as EGL does with no display (no extensions, no display, false,
 * EGL_NOT_INITIALIZED) and vtkEGLRuntimeLibraryError() says why.
 */
#ifndef vtkEGLRuntimeLibrary_h
#define vtkEGLRuntimeLibrary_h

#define EGL_EGL_PROTOTYPES 0
#include <EGL/egl.h>
#include <EGL/eglext.h>

#define SPT_EGL_HIDDEN __attribute__((visibility("hidden")))

extern "C"
{
  SPT_EGL_HIDDEN EGLint eglGetError(void);
  SPT_EGL_HIDDEN EGLBoolean eglInitialize(EGLDisplay display, EGLint* major, EGLint* minor);
  SPT_EGL_HIDDEN EGLBoolean eglTerminate(EGLDisplay display);
  SPT_EGL_HIDDEN const char* eglQueryString(EGLDisplay display, EGLint name);
  SPT_EGL_HIDDEN __eglMustCastToProperFunctionPointerType eglGetProcAddress(const char* name);
  SPT_EGL_HIDDEN EGLBoolean eglBindAPI(EGLenum api);
  SPT_EGL_HIDDEN EGLBoolean eglChooseConfig(
    EGLDisplay display, const EGLint* attributes, EGLConfig* configs, EGLint size, EGLint* count);
  SPT_EGL_HIDDEN EGLContext eglCreateContext(
    EGLDisplay display, EGLConfig config, EGLContext share, const EGLint* attributes);
  SPT_EGL_HIDDEN EGLBoolean eglDestroyContext(EGLDisplay display, EGLContext context);
  SPT_EGL_HIDDEN EGLBoolean eglMakeCurrent(
    EGLDisplay display, EGLSurface draw, EGLSurface read, EGLContext context);
  SPT_EGL_HIDDEN EGLContext eglGetCurrentContext(void);
}

/// Empty once libEGL.so.1 is open; otherwise why it could not be opened.
SPT_EGL_HIDDEN const char* vtkEGLRuntimeLibraryError();

#endif
