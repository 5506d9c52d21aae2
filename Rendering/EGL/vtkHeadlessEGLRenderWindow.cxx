#include "vtkHeadlessEGLRenderWindow.h"

#include "vtkObjectFactory.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLLoader.h"
#include "vtkOpenGLState.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkVersionMacros.h"

#ifdef SPT_EGL_RUNTIME_LIBRARY
#include "vtkEGLRuntimeLibrary.h"
#else
#include <EGL/egl.h>
#include <EGL/eglext.h>
#endif

#include <algorithm>
#include <cstring>
#include <map>
#include <mutex>
#include <sstream>
#include <string>

vtkStandardNewMacro(vtkHeadlessEGLRenderWindow);

namespace
{
const int MaximumDevices = 64;

bool HasExtension(const char* extensions, const char* name)
{
  if (!extensions)
  {
    return false;
  }
  const std::size_t length = std::strlen(name);
  for (const char* found = std::strstr(extensions, name); found;
       found = std::strstr(found + length, name))
  {
    const bool startsWord = found == extensions || found[-1] == ' ';
    const bool endsWord = found[length] == '\0' || found[length] == ' ';
    if (startsWord && endsWord)
    {
      return true;
    }
  }
  return false;
}

std::string EGLErrorText()
{
  std::ostringstream text;
  text << "EGL error 0x" << std::hex << eglGetError();
  return text.str();
}

// eglInitialize() and eglTerminate() do not count: a display terminated by one window would be
// gone for every other window on it. The windows of a process share each display (`change`:
// +1 for a window that takes it, -1 for one that leaves it) and terminate it when the last goes.
void CountDisplayUser(EGLDisplay display, int change)
{
  static std::mutex mutex;
  static std::map<EGLDisplay, int> users;
  std::lock_guard<std::mutex> lock(mutex);
  if ((users[display] += change) <= 0)
  {
    users.erase(display);
    eglTerminate(display);
  }
}

/// An initialized display of EGL_EXT_platform_base's `platform`, or EGL_NO_DISPLAY.
EGLDisplay InitializePlatformDisplay(EGLenum platform, void* nativeDisplay)
{
  auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
    eglGetProcAddress("eglGetPlatformDisplayEXT"));
  EGLDisplay display =
    getPlatformDisplay ? getPlatformDisplay(platform, nativeDisplay, nullptr) : EGL_NO_DISPLAY;
  return display != EGL_NO_DISPLAY && eglInitialize(display, nullptr, nullptr) ? display
                                                                               : EGL_NO_DISPLAY;
}

#if VTK_VERSION_NUMBER >= VTK_VERSION_CHECK(9, 4, 0)
vtkOpenGLRenderWindow::VTKOpenGLAPIProc LoadEGLSymbol(void*, const char* name)
{
  return reinterpret_cast<vtkOpenGLRenderWindow::VTKOpenGLAPIProc>(eglGetProcAddress(name));
}
#endif
}

struct vtkHeadlessEGLRenderWindow::vtkInternals
{
  EGLDisplay Display = EGL_NO_DISPLAY;
  EGLContext Context = EGL_NO_CONTEXT;
  std::string Platform;
  std::string Renderer;
  std::string Version;
  std::string Error;

  /// An initialized display on EGL_EXT_platform_device, or EGL_NO_DISPLAY.
  EGLDisplay OpenDeviceDisplay(int deviceIndex)
  {
    const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!HasExtension(clientExtensions, "EGL_EXT_platform_device") ||
      !HasExtension(clientExtensions, "EGL_EXT_device_enumeration"))
    {
      return EGL_NO_DISPLAY;
    }
    auto queryDevices =
      reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    auto queryDeviceString = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(
      eglGetProcAddress("eglQueryDeviceStringEXT"));
    EGLDeviceEXT devices[MaximumDevices];
    EGLint count = 0;
    if (!queryDevices || !queryDeviceString || !queryDevices(MaximumDevices, devices, &count))
    {
      return EGL_NO_DISPLAY;
    }
    for (EGLint i = 0; i < count; ++i)
    {
      // By default a GPU only: Mesa lists its software rasterizer as a device too, which the
      // surfaceless platform serves as well.
      if (deviceIndex >= 0
          ? i != deviceIndex
          : HasExtension(queryDeviceString(devices[i], EGL_EXTENSIONS), "EGL_MESA_device_software"))
      {
        continue;
      }
      EGLDisplay display = InitializePlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i]);
      if (display != EGL_NO_DISPLAY)
      {
        return display;
      }
    }
    if (deviceIndex >= 0)
    {
      std::ostringstream text;
      text << "EGL device " << deviceIndex
           << (deviceIndex < count ? " could not be opened" : " does not exist")
           << " (libEGL lists " << count << " device(s), DeviceIndex 0 to " << count - 1 << ")";
      this->Error = text.str();
    }
    return EGL_NO_DISPLAY;
  }

  /// An initialized display on Mesa's surfaceless platform, or EGL_NO_DISPLAY.
  EGLDisplay OpenSurfacelessDisplay()
  {
    const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    return HasExtension(clientExtensions, "EGL_MESA_platform_surfaceless")
      ? InitializePlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY)
      : EGL_NO_DISPLAY;
  }

  bool CreateContext(EGLDisplay display)
  {
    if (!HasExtension(eglQueryString(display, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context"))
    {
      this->Error =
        "the EGL display lacks EGL_KHR_surfaceless_context (a context without a surface)";
      return false;
    }
    if (!eglBindAPI(EGL_OPENGL_API))
    {
      this->Error = "the EGL display has no desktop OpenGL (eglBindAPI(EGL_OPENGL_API) failed, " +
        EGLErrorText() + ")";
      return false;
    }
    // Any surface type: the context is only ever made current without a surface.
    const EGLint configAttributes[] = { EGL_SURFACE_TYPE, 0, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
      EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_NONE };
    EGLConfig config = nullptr;
    EGLint configs = 0;
    if (!eglChooseConfig(display, configAttributes, &config, 1, &configs) || configs < 1)
    {
      this->Error = "the EGL display has no configuration for desktop OpenGL with 8-bit RGB";
      return false;
    }
    // 3.2 core is what VTK's OpenGL2 back end needs; drivers return the newest version that is
    // compatible with it (4.5 with llvmpipe).
    const EGLint contextAttributes[] = { EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 2,
      EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE };
    this->Context = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttributes);
    if (this->Context == EGL_NO_CONTEXT)
    {
      this->Error = "the driver could not make an OpenGL 3.2 core profile context (" +
        EGLErrorText() +
        "); VTK needs OpenGL 3.2 or later. Use a driver that offers it (Mesa's llvmpipe offers "
        "4.5), and check that MESA_GL_VERSION_OVERRIDE, if set, does not ask for less";
      return false;
    }
    this->Display = display;
    return true;
  }

  /// Renderer and Version from the current context.
  void ReadRendererStrings()
  {
    // Through libGLdispatch, which GLX's and EGL's libraries share: glGetString is valid in an
    // EGL context before any loader ran.
    using GetStringFunction = const GLubyte* (*)(GLenum);
    auto getString = reinterpret_cast<GetStringFunction>(eglGetProcAddress("glGetString"));
    const GLubyte* renderer = getString ? getString(GL_RENDERER) : nullptr;
    const GLubyte* version = getString ? getString(GL_VERSION) : nullptr;
    this->Renderer = renderer ? reinterpret_cast<const char*>(renderer) : "";
    this->Version = version ? reinterpret_cast<const char*>(version) : "";
  }
};

vtkHeadlessEGLRenderWindow::vtkHeadlessEGLRenderWindow()
  : Internals(new vtkInternals)
{
  // The context is this window's own and has no surface: VTK draws into its offscreen
  // framebuffers and never blits to a default framebuffer.
  this->SetOwnContext(1);
  this->SetFrameBlitModeToNoBlit();
  this->ShowWindow = false;
  this->UseOffScreenBuffers = true;
#if VTK_VERSION_NUMBER >= VTK_VERSION_CHECK(9, 4, 0)
  this->SetOpenGLSymbolLoader(&LoadEGLSymbol, nullptr);
#endif
}

vtkHeadlessEGLRenderWindow::~vtkHeadlessEGLRenderWindow()
{
  this->Finalize();
}

bool vtkHeadlessEGLRenderWindow::InitializeContext()
{
  vtkInternals& internals = *this->Internals;
  if (internals.Context != EGL_NO_CONTEXT)
  {
    return true;
  }
  if (!internals.Error.empty())
  {
    return false; // Reported once, when it failed.
  }
  // Until there is a context, VTK neither renders nor reads pixels.
  this->SetReadyForRendering(false);
  EGLDisplay display = internals.OpenDeviceDisplay(this->DeviceIndex);
  std::string platform = "device";
  if (display == EGL_NO_DISPLAY && this->DeviceIndex < 0)
  {
    display = internals.OpenSurfacelessDisplay();
    platform = "surfaceless";
  }
  if (display == EGL_NO_DISPLAY)
  {
#ifdef SPT_EGL_RUNTIME_LIBRARY
    if (internals.Error.empty())
    {
      internals.Error = vtkEGLRuntimeLibraryError();
    }
#endif
    if (internals.Error.empty())
    {
      internals.Error = "libEGL offers neither a GPU through EGL_EXT_platform_device nor Mesa's "
                        "surfaceless platform (EGL_MESA_platform_surfaceless); install Mesa's "
                        "EGL driver (Debian: libegl-mesa0) or a GPU driver with EGL";
    }
    vtkErrorMacro("No EGL context: " << internals.Error << ".");
    return false;
  }
  CountDisplayUser(display, +1);
  if (!internals.CreateContext(display))
  {
    CountDisplayUser(display, -1);
    vtkErrorMacro("No EGL context on the " << platform << " platform: " << internals.Error << ".");
    return false;
  }
  internals.Platform = platform;
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, internals.Context))
  {
    internals.Error = "eglMakeCurrent failed (" + EGLErrorText() + ")";
    vtkErrorMacro("The EGL context cannot be made current: " << internals.Error << ".");
    this->DestroyContext();
    return false;
  }
  internals.ReadRendererStrings();
  this->SetIsCurrent(true);
  this->SetReadyForRendering(true);
  return true;
}

void vtkHeadlessEGLRenderWindow::DestroyContext()
{
  vtkInternals& internals = *this->Internals;
  if (internals.Context != EGL_NO_CONTEXT)
  {
    if (eglGetCurrentContext() == internals.Context)
    {
      eglMakeCurrent(internals.Display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    }
    eglDestroyContext(internals.Display, internals.Context);
    CountDisplayUser(internals.Display, -1);
  }
  internals.Context = EGL_NO_CONTEXT;
  internals.Display = EGL_NO_DISPLAY;
  this->SetIsCurrent(false);
}

const char* vtkHeadlessEGLRenderWindow::GetPlatformName()
{
  return this->Internals->Platform.c_str();
}

const char* vtkHeadlessEGLRenderWindow::GetRendererName()
{
  return this->Internals->Renderer.c_str();
}

const char* vtkHeadlessEGLRenderWindow::GetOpenGLVersion()
{
  return this->Internals->Version.c_str();
}

void vtkHeadlessEGLRenderWindow::MakeCurrent()
{
  if (!this->InitializeContext())
  {
    return;
  }
  const vtkInternals& internals = *this->Internals;
  if (eglGetCurrentContext() != internals.Context)
  {
    eglMakeCurrent(internals.Display, EGL_NO_SURFACE, EGL_NO_SURFACE, internals.Context);
  }
  this->SetIsCurrent(eglGetCurrentContext() == internals.Context);
}

bool vtkHeadlessEGLRenderWindow::IsCurrent()
{
  const bool current = this->Internals->Context != EGL_NO_CONTEXT &&
    eglGetCurrentContext() == this->Internals->Context;
  this->SetIsCurrent(current);
  return current;
}

void vtkHeadlessEGLRenderWindow::ReleaseCurrent()
{
  if (this->IsCurrent())
  {
    eglMakeCurrent(this->Internals->Display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    this->SetIsCurrent(false);
  }
}

int vtkHeadlessEGLRenderWindow::SupportsOpenGL()
{
  this->MakeCurrent();
  if (!this->IsCurrent())
  {
    this->OpenGLSupportMessage = "no EGL context: " + this->Internals->Error;
    this->SetSupportsOpenGL(0);
    return 0;
  }
  if (!this->Initialized)
  {
    this->OpenGLInit();
  }
  this->SetSupportsOpenGL(this->Initialized ? 1 : 0);
  this->OpenGLSupportMessage = this->Initialized
    ? "OpenGL " + this->Internals->Version + " through EGL (" + this->Internals->Platform + ")"
    : "the EGL context is not OpenGL 3.2 core or later";
  return this->Initialized ? 1 : 0;
}

void vtkHeadlessEGLRenderWindow::SetInteractor(vtkRenderWindowInteractor* interactor)
{
  if (interactor && interactor->IsA("vtkXRenderWindowInteractor"))
  {
    vtkErrorMacro("An X interactor (" << interactor->GetClassName()
                                      << ") cannot drive a window without X; use "
                                         "vtkGenericRenderWindowInteractor, or no interactor.");
    return;
  }
  this->Superclass::SetInteractor(interactor);
}

void vtkHeadlessEGLRenderWindow::OpenGLInit()
{
  this->MakeCurrent();
  if (this->IsCurrent())
  {
#if VTK_VERSION_NUMBER >= VTK_VERSION_CHECK(9, 4, 0)
    // vtkGenericOpenGLRenderWindow::OpenGLInit() resets VTK's OpenGL state (glClearColor, ...)
    // before vtkOpenGLRenderWindow::OpenGLInit() has glad load OpenGL's functions: load them
    // first, as VTK's own windows do once their context is made. The second call returns at
    // once.
    this->OpenGLInitContext();
#endif
    this->Superclass::OpenGLInit();
  }
}

void vtkHeadlessEGLRenderWindow::OpenGLInitContext()
{
#if VTK_VERSION_NUMBER < VTK_VERSION_CHECK(9, 4, 0)
  if (!this->Initialized)
  {
    // glewInit() loads OpenGL's functions (glewContextInit(), through libGLdispatch, which
    // EGL's contexts use too) and then GLX's, which need an X display: without one it returns
    // GLEW_ERROR_NO_GLX_DISPLAY (GLEW 2.0 on; VTK's own GLEW is 2.1 or later) after OpenGL's
    // functions are loaded. The rest is what vtkOpenGLRenderWindow::OpenGLInitContext() does.
    const GLenum result = glewInit();
    if (result != GLEW_OK && result != GLEW_ERROR_NO_GLX_DISPLAY)
    {
      vtkErrorMacro("GLEW could not load OpenGL's functions in the EGL context: "
        << reinterpret_cast<const char*>(glewGetErrorString(result)) << ".");
      return;
    }
    if (!GLEW_VERSION_3_2)
    {
      vtkErrorMacro("The EGL context is OpenGL " << this->Internals->Version
                                                 << "; VTK needs OpenGL 3.2 or later.");
      return;
    }
    this->GlewInitValid = true;
    this->Initialized = true;
    GLfloat lineWidthRange[2] = { 1.0f, 1.0f };
    glGetFloatv(this->LineSmoothing ? GL_SMOOTH_LINE_WIDTH_RANGE : GL_ALIASED_LINE_WIDTH_RANGE,
      lineWidthRange);
    this->MaximumHardwareLineWidth = glGetError() == GL_NO_ERROR ? lineWidthRange[1] : 1.0f;
  }
#endif
  this->Superclass::OpenGLInitContext();
}

bool vtkHeadlessEGLRenderWindow::QueryRenderFramebuffer(
  unsigned int attachment, int count, const unsigned int* names, int* values)
{
  if (!this->Initialized || !this->RenderFramebuffer ||
    this->RenderFramebuffer->GetFBOIndex() == 0 || !this->IsCurrent())
  {
    return false;
  }
  vtkOpenGLState* state = this->GetState();
  state->PushDrawFramebufferBinding();
  this->RenderFramebuffer->Bind(GL_DRAW_FRAMEBUFFER);
  GLint type = GL_NONE;
  glGetFramebufferAttachmentParameteriv(
    GL_DRAW_FRAMEBUFFER, attachment, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
  for (int i = 0; i < count && type != GL_NONE; ++i)
  {
    GLint value = 0;
    glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, attachment, names[i], &value);
    values[i] = value;
  }
  state->PopDrawFramebufferBinding();
  return type != GL_NONE;
}

int vtkHeadlessEGLRenderWindow::GetColorBufferSizes(int* rgba)
{
  if (!rgba)
  {
    return 0;
  }
  // What VTK's own framebuffers have, until the render framebuffer exists to tell.
  std::fill_n(rgba, 4, 8);
  const unsigned int names[4] = { GL_FRAMEBUFFER_ATTACHMENT_RED_SIZE,
    GL_FRAMEBUFFER_ATTACHMENT_GREEN_SIZE, GL_FRAMEBUFFER_ATTACHMENT_BLUE_SIZE,
    GL_FRAMEBUFFER_ATTACHMENT_ALPHA_SIZE };
  this->QueryRenderFramebuffer(GL_COLOR_ATTACHMENT0, 4, names, rgba);
  return rgba[0] + rgba[1] + rgba[2] + rgba[3];
}

int vtkHeadlessEGLRenderWindow::GetDepthBufferSize()
{
  int bits = 24; // As VTK answers before it has a context.
  const unsigned int name = GL_FRAMEBUFFER_ATTACHMENT_DEPTH_SIZE;
  this->QueryRenderFramebuffer(GL_DEPTH_ATTACHMENT, 1, &name, &bits);
  return bits;
}

void vtkHeadlessEGLRenderWindow::Finalize()
{
  if (this->Internals->Context != EGL_NO_CONTEXT)
  {
    this->MakeCurrent();
    this->Superclass::Finalize();
    this->Initialized = false;
    this->DestroyContext();
  }
}

void vtkHeadlessEGLRenderWindow::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "DeviceIndex: " << this->DeviceIndex << "\n";
  os << indent << "PlatformName: " << this->Internals->Platform << "\n";
  os << indent << "RendererName: " << this->Internals->Renderer << "\n";
  os << indent << "OpenGLVersion: " << this->Internals->Version << "\n";
}
