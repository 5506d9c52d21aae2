// Image test of vtkSPTVolumeMapper in the scene of SPTTestScene.h:
// - left: perspective, point scalars, the opaque sphere inside the shell hides part of it;
// - right: parallel projection, cell scalars, and a rotated, non-uniformly scaled vtkVolume.
// Checks: the baseline image, that each viewport shows a volume (not the background), that no
// OpenGL error was raised, and that the input data set was not modified.

#include "vtkSPTVolumeMapper.h"

#include "SPTTestScene.h"

using namespace SPTTestScene;

int TestSPTVolumeMapper(int argc, char* argv[])
{
  vtkSmartPointer<vtkUnstructuredGrid> shell = MakeShell();
  const vtkMTimeType inputTime = shell->GetMTime();
  const vtkIdType inputCells = shell->GetNumberOfCells();
  vtkSmartPointer<vtkVolumeProperty> property = MakeProperty();

  ShellVolumes<vtkSPTVolumeMapper> volumes(shell, property);

  TwoViewports scene(400, 200, volumes.Point, volumes.Cell);
  int failures = scene.Render();
  failures += scene.CheckCovered(Capture(scene.Window), 4000);
  const vtkIdType tetrahedra = volumes.PointMapper->GetNumberOfTetrahedra();
  if (shell->GetMTime() != inputTime || shell->GetNumberOfCells() != inputCells ||
    tetrahedra < 5 * inputCells || tetrahedra > 6 * inputCells ||
    volumes.CellMapper->GetNumberOfTetrahedra() != tetrahedra)
  {
    std::cerr << "The input was modified, or its hexahedra not split into 5 or 6 tetrahedra each ("
              << tetrahedra << " tetrahedra for " << inputCells << " hexahedra).\n";
    ++failures;
  }
  return TwoViewports::ExitStatus(scene.CompareWithBaseline(argc, argv), failures);
}
