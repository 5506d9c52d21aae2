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
  const ShellInput input;
  ShellVolumes<vtkSPTVolumeMapper> volumes(input.Shell, input.Property);

  TwoViewports scene(400, 200, volumes.Point, volumes.Cell);
  SPTTestChecks::FailureCount failures;
  scene.Render(failures);
  scene.CheckCovered(Capture(scene.Window), 4000, failures);
  const vtkIdType tetrahedra = volumes.PointMapper->GetNumberOfTetrahedra();
  input.CheckInputAndSplit(tetrahedra, failures);
  failures.Check(volumes.CellMapper->GetNumberOfTetrahedra() == tetrahedra,
    "the two mappers split the same shell into the same tetrahedra");
  return TwoViewports::ExitStatus(scene.CompareWithBaseline(argc, argv), failures);
}
