// The render window of the C++ tests: VTK's own (X, GLX) when there is an X display, else
// vtkSPTEGLRenderWindow, so that the whole suite also runs without X.

#ifndef SPTTestWindow_h
#define SPTTestWindow_h

#include "vtkRenderWindow.h"
#include "vtkSPTEGLRenderWindow.h"
#include "vtkSmartPointer.h"

#include <cstdlib>

namespace SPTTestWindow
{
inline bool HasXDisplay()
{
  const char* display = std::getenv("DISPLAY");
  return display && *display;
}

inline vtkSmartPointer<vtkRenderWindow> New()
{
  if (HasXDisplay())
  {
    return vtkSmartPointer<vtkRenderWindow>::New();
  }
  return vtkSmartPointer<vtkSPTEGLRenderWindow>::New();
}
}

#endif
