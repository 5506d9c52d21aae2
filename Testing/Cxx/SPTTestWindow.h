// The render window of the C++ tests: VTK's own (X, GLX) when there is an X display, else
// vtkHeadlessEGLRenderWindow, so that the whole suite also runs without X. Also how the tests
// read a rendered image back.

#ifndef SPTTestWindow_h
#define SPTTestWindow_h

#include "vtkHeadlessEGLRenderWindow.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWindowToImageFilter.h"

#include <cstdlib>
#include <vector>

namespace SPTTestWindow
{
inline vtkSmartPointer<vtkRenderWindow> New()
{
  const char* display = std::getenv("DISPLAY");
  if (display && *display)
  {
    return vtkSmartPointer<vtkRenderWindow>::New();
  }
  return vtkSmartPointer<vtkHeadlessEGLRenderWindow>::New();
}

// The window's back buffer as it was last rendered: RGB bytes, or RGBA with `alpha`, one pixel
// after another from the bottom row up.
inline std::vector<unsigned char> Capture(vtkRenderWindow* window, bool alpha = false)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  if (alpha)
  {
    grab->SetInputBufferTypeToRGBA();
  }
  grab->ReadFrontBufferOff();
  grab->ShouldRerenderOff();
  grab->Update();
  vtkUnsignedCharArray* bytes =
    vtkUnsignedCharArray::SafeDownCast(grab->GetOutput()->GetPointData()->GetScalars());
  return std::vector<unsigned char>(
    bytes->GetPointer(0), bytes->GetPointer(0) + bytes->GetNumberOfValues());
}

// For tests that make OpenGL calls of their own: a rendered window's context, current, with
// VTK's render framebuffer bound. A window without X (EGL) has no complete default
// framebuffer: drawing there raises GL_INVALID_FRAMEBUFFER_OPERATION even with the
// rasterizer off. The previous bindings are restored when it goes. Context is null when the
// window is not an OpenGL one.
class RawContext
{
public:
  explicit RawContext(int size)
  {
    this->Window->SetOffScreenRendering(1);
    this->Window->SetSize(size, size);
    this->Window->AddRenderer(this->Renderer);
    this->Window->Render();
    this->Context = vtkOpenGLRenderWindow::SafeDownCast(this->Window);
    if (this->Context)
    {
      this->Context->MakeCurrent();
      this->Context->GetState()->PushFramebufferBindings();
      this->Context->GetRenderFramebuffer()->Bind();
    }
  }
  ~RawContext()
  {
    if (this->Context)
    {
      this->Context->GetState()->PopFramebufferBindings();
    }
  }
  RawContext(const RawContext&) = delete;
  RawContext& operator=(const RawContext&) = delete;

  vtkOpenGLRenderWindow* Context = nullptr;

private:
  vtkSmartPointer<vtkRenderWindow> Window = New();
  vtkNew<vtkRenderer> Renderer;
};
}

#endif
