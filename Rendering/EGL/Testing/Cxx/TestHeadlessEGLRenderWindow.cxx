// vtkHeadlessEGLRenderWindow renders vtkSPTVolumeMapper without X: the scene of
// TestSPTVolumeMapper (SPTTestScene.h), with the same settings and seeds, drawn in an EGL
// window. Run with no DISPLAY (see CMakeLists.txt). Checks: the window made an OpenGL 3.2+
// context on an EGL platform, each viewport shows a volume, no OpenGL error was raised, and the
// image matches TestSPTVolumeMapper's baseline, which was rendered through X (GLX).

#include "vtkHeadlessEGLRenderWindow.h"
#include "vtkSPTVolumeMapper.h"

#include "SPTTestScene.h"

#include <string>

using namespace SPTTestScene;

namespace
{
// The window made its context, on the EGL platform asked for: SPT_EGL_DEVICE_INDEX=i asks for
// device i of EGL_EXT_device_enumeration (with Mesa, device 0 is its software rasterizer, which
// makes the device platform testable without a GPU).
void CheckContext(
  vtkHeadlessEGLRenderWindow* window, bool deviceAsked, SPTTestChecks::FailureCount& failures)
{
  const std::string platform = window->GetPlatformName();
  std::cout << "EGL platform: " << platform << ", renderer: " << window->GetRendererName()
            << ", OpenGL: " << window->GetOpenGLVersion() << "\n";
  failures.Check(window->SupportsOpenGL(),
    std::string("OpenGL through EGL: ") + window->GetOpenGLSupportMessage());
  failures.Check(platform == "device" || (!deviceAsked && platform == "surfaceless"),
    "the EGL platform asked for, not '" + platform + "'");
}
}

int TestHeadlessEGLRenderWindow(int argc, char* argv[])
{
  const ShellInput input;
  ShellVolumes<vtkSPTVolumeMapper> volumes(input.Shell, input.Property);

  vtkNew<vtkHeadlessEGLRenderWindow> window;
  const char* device = std::getenv("SPT_EGL_DEVICE_INDEX");
  if (device)
  {
    window->SetDeviceIndex(std::atoi(device));
  }
  TwoViewports scene(400, 200, volumes.Point, volumes.Cell, window);
  SPTTestChecks::FailureCount failures;
  scene.Render(failures);
  CheckContext(window, device != nullptr, failures);
  scene.CheckCovered(Capture(scene.Window), 4000, failures);
  return TwoViewports::ExitStatus(scene.CompareWithBaseline(argc, argv), failures);
}
