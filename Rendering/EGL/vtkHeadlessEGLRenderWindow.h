/**
 * @class   vtkHeadlessEGLRenderWindow
 * @brief   an OpenGL render window without X: an EGL context of its own, drawn offscreen
 *
 * vtkHeadlessEGLRenderWindow makes an OpenGL (core profile, 3.2 or later) context with libEGL and
 * hands it to VTK as a vtkGenericOpenGLRenderWindow, so that a VTK built for GLX only (as
 * Debian's) renders where there is no X server. The context has no surface: VTK renders into
 * its own offscreen framebuffers, and GetPixelData(), GetRGBACharPixelData() and
 * vtkWindowToImageFilter read the image from there.
 *
 * The EGL display comes from EGL_EXT_platform_device when a GPU is present (a device whose
 * driver is not a software rasterizer), whether or not a display is attached to it, and from
 * Mesa's surfaceless platform (EGL_MESA_platform_surfaceless, llvmpipe without a GPU)
 * otherwise. SetDeviceIndex() picks one device of EGL_EXT_device_enumeration's list instead.
 *
 * The context is made on the first Render(), MakeCurrent() or SupportsOpenGL() and released
 * with the window. Failures (no libEGL platform, no OpenGL 3.2 core context) are reported with
 * vtkErrorMacro, naming what is missing; the window then renders nothing.
 *
 * With VTK before 9.4, whose GLEW also loads GLX's functions and fails without an X display,
 * the window loads OpenGL's functions with GLEW's context part only, so that no spurious
 * "GLEW could not be initialized" is reported. From VTK 9.4 on, glad loads them through
 * eglGetProcAddress().
 */

#ifndef vtkHeadlessEGLRenderWindow_h
#define vtkHeadlessEGLRenderWindow_h

#include "SPTRenderingEGLModule.h" // For export macro
#include "vtkGenericOpenGLRenderWindow.h"

#include <memory> // For std::unique_ptr

class SPTRENDERINGEGL_EXPORT vtkHeadlessEGLRenderWindow : public vtkGenericOpenGLRenderWindow
{
public:
  static vtkHeadlessEGLRenderWindow* New();
  vtkTypeMacro(vtkHeadlessEGLRenderWindow, vtkGenericOpenGLRenderWindow);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The EGL device to render with, an index into EGL_EXT_device_enumeration's list (-1 to 63);
   * default -1: the first GPU device, else Mesa's surfaceless platform. Takes effect when the
   * context is made, that is before the first render.
   */
  vtkSetClampMacro(DeviceIndex, int, -1, 63);
  vtkGetMacro(DeviceIndex, int);
  ///@}

  /**
   * Make the EGL context if there is none yet. False, with an error naming what is missing,
   * when there is no EGL platform to make it on or it is not OpenGL 3.2 core or later.
   */
  bool InitializeContext();

  /**
   * The EGL platform the context was made on: "device", "surfaceless", or "" before the
   * context is made (or when it could not be made).
   */
  const char* GetPlatformName();

  /**
   * The OpenGL renderer and version strings of the context ("llvmpipe (LLVM 15.0.6, 256 bits)",
   * "4.5 (Core Profile) Mesa 22.3.6"), or "" when there is no context.
   */
  const char* GetRendererName();
  const char* GetOpenGLVersion();

  ///@{
  /**
   * The window's own EGL context, current on this thread with no surface.
   */
  void MakeCurrent() override;
  bool IsCurrent() override;
  void ReleaseCurrent() override;
  ///@}

  /**
   * 1 when the context can be made and is OpenGL 3.2 core or later, else 0, with the reason in
   * GetOpenGLSupportMessage().
   */
  int SupportsOpenGL() override;

  ///@{
  /**
   * The color and depth bits of the window: those of VTK's render framebuffer, which is what
   * the window draws into (the context has no default framebuffer, and querying it is an
   * OpenGL error); before VTK made it, 8 bits per color channel and 24 depth bits.
   */
  int GetColorBufferSizes(int* rgba) override;
  int GetDepthBufferSize() override;
  ///@}

  /**
   * Release VTK's graphics resources of this window, then its EGL context.
   */
  void Finalize() override;

  /**
   * Refuses an X interactor (vtkXRenderWindowInteractor, what vtkRenderWindowInteractor::New()
   * makes in a VTK built for X), which would need the X window this window does not have, with
   * an error; any other interactor (vtkGenericRenderWindowInteractor) is set.
   */
  void SetInteractor(vtkRenderWindowInteractor* interactor) override;

  /**
   * Make the context current before VTK initializes OpenGL in it.
   */
  void OpenGLInit() override;

protected:
  vtkHeadlessEGLRenderWindow();
  ~vtkHeadlessEGLRenderWindow() override;

  /**
   * Load OpenGL's functions for the EGL context (see the class description) and check its
   * version, then query its limits as vtkOpenGLRenderWindow does.
   */
  void OpenGLInitContext() override;

  int DeviceIndex = -1;

private:
  vtkHeadlessEGLRenderWindow(const vtkHeadlessEGLRenderWindow&) = delete;
  void operator=(const vtkHeadlessEGLRenderWindow&) = delete;

  void DestroyContext();
  /// Query `count` parameters (`names`) of an attachment of VTK's render framebuffer into
  /// `values`; false, leaving them, before that framebuffer exists or without the attachment.
  bool QueryRenderFramebuffer(
    unsigned int attachment, int count, const unsigned int* names, int* values);

  struct vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif
