#include "vtkSPTEGLRenderWindow.h"

#include "vtkObjectFactory.h"

vtkStandardNewMacro(vtkSPTEGLRenderWindow);

void vtkSPTEGLRenderWindow::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
