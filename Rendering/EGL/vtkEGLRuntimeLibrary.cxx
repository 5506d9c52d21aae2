#include "vtkEGLRuntimeLibrary.h"

#include <dlfcn.h>

#include <string>

namespace
{
/// libEGL.so.1, opened on the first call of any function (thread-safe: a static's initializer).
struct Library
{
  void* Handle = nullptr;
  std::string Error;

  Library()
  {
    this->Handle = dlopen("libEGL.so.1", RTLD_NOW | RTLD_LOCAL);
    if (!this->Handle)
    {
      const char* reason = dlerror();
      this->Error = std::string("libEGL.so.1 could not be loaded (") +
        (reason ? reason : "no reason given") +
        "): install the system's EGL (Debian: libegl1, with Mesa's libegl-mesa0 or a GPU driver)";
    }
  }
};

Library& TheLibrary()
{
  static Library library;
  return library;
}

/// The function `name` of libEGL, or nullptr without the library.
template <typename Function>
Function Find(const char* name)
{
  void* handle = TheLibrary().Handle;
  return handle ? reinterpret_cast<Function>(dlsym(handle, name)) : nullptr;
}
}

// Each function: libEGL's, looked up once, or EGL's failure without it.
#define SPT_EGL_FORWARD(name, failure, ...)                                                        \
  static const auto function = Find<decltype(&name)>(#name);                                       \
  return function ? function(__VA_ARGS__) : failure

extern "C"
{
  EGLint eglGetError(void)
  {
    SPT_EGL_FORWARD(eglGetError, EGL_NOT_INITIALIZED);
  }
  EGLBoolean eglInitialize(EGLDisplay display, EGLint* major, EGLint* minor)
  {
    SPT_EGL_FORWARD(eglInitialize, EGL_FALSE, display, major, minor);
  }
  EGLBoolean eglTerminate(EGLDisplay display)
  {
    SPT_EGL_FORWARD(eglTerminate, EGL_FALSE, display);
  }
  const char* eglQueryString(EGLDisplay display, EGLint name)
  {
    SPT_EGL_FORWARD(eglQueryString, nullptr, display, name);
  }
  __eglMustCastToProperFunctionPointerType eglGetProcAddress(const char* name)
  {
    SPT_EGL_FORWARD(eglGetProcAddress, nullptr, name);
  }
  EGLBoolean eglBindAPI(EGLenum api)
  {
    SPT_EGL_FORWARD(eglBindAPI, EGL_FALSE, api);
  }
  EGLBoolean eglChooseConfig(
    EGLDisplay display, const EGLint* attributes, EGLConfig* configs, EGLint size, EGLint* count)
  {
    SPT_EGL_FORWARD(eglChooseConfig, EGL_FALSE, display, attributes, configs, size, count);
  }
  EGLContext eglCreateContext(
    EGLDisplay display, EGLConfig config, EGLContext share, const EGLint* attributes)
  {
    SPT_EGL_FORWARD(eglCreateContext, EGL_NO_CONTEXT, display, config, share, attributes);
  }
  EGLBoolean eglDestroyContext(EGLDisplay display, EGLContext context)
  {
    SPT_EGL_FORWARD(eglDestroyContext, EGL_FALSE, display, context);
  }
  EGLBoolean eglMakeCurrent(
    EGLDisplay display, EGLSurface draw, EGLSurface read, EGLContext context)
  {
    SPT_EGL_FORWARD(eglMakeCurrent, EGL_FALSE, display, draw, read, context);
  }
  EGLContext eglGetCurrentContext(void)
  {
    SPT_EGL_FORWARD(eglGetCurrentContext, EGL_NO_CONTEXT);
  }
}

const char* vtkEGLRuntimeLibraryError()
{
  return TheLibrary().Error.c_str();
}
