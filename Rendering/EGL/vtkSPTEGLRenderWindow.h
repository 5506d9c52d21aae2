/**
 * @class   vtkSPTEGLRenderWindow
 * @brief   deprecated name of vtkHeadlessEGLRenderWindow
 *
 * The headless EGL window is not specific to SPT: it is vtkHeadlessEGLRenderWindow. This
 * subclass keeps the former name working for one release; it adds nothing.
 */

#ifndef vtkSPTEGLRenderWindow_h
#define vtkSPTEGLRenderWindow_h

#include "SPTRenderingEGLModule.h" // For export macro
#include "vtkHeadlessEGLRenderWindow.h"

class SPTRENDERINGEGL_EXPORT vtkSPTEGLRenderWindow : public vtkHeadlessEGLRenderWindow
{
public:
  static vtkSPTEGLRenderWindow* New();
  vtkTypeMacro(vtkSPTEGLRenderWindow, vtkHeadlessEGLRenderWindow);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkSPTEGLRenderWindow() = default;
  ~vtkSPTEGLRenderWindow() override = default;

private:
  vtkSPTEGLRenderWindow(const vtkSPTEGLRenderWindow&) = delete;
  void operator=(const vtkSPTEGLRenderWindow&) = delete;
};

#endif
