// Image test of vtkHAVSVolumeMapper in the scene of SPTTestScene.h (non-convex: rays cross
// two walls with a gap between them):
// - left: perspective, k = 6, the opaque sphere inside the shell hides part of it;
// - right: parallel projection, k = 2, and a rotated vtkVolume scaled by a negative factor
//   (a mirror, which swaps which boundary faces the rays leave the mesh through).
// Checks: the baseline image, that each viewport shows a volume (not the background), that no
// OpenGL error was raised, that the input was not modified, the face counts, and that the
// mapper reports its time split.

#include "vtkHAVSVolumeMapper.h"

#include "SPTTestScene.h"

using namespace SPTTestScene;

int TestHAVSVolumeMapper(int argc, char* argv[])
{
  const ShellInput input;
  vtkNew<vtkHAVSVolumeMapper> leftMapper;
  leftMapper->SetInputData(input.Shell);
  leftMapper->SetKBufferSize(6);
  vtkSmartPointer<vtkVolume> leftVolume = MakeVolume(leftMapper, input.Property);

  vtkNew<vtkHAVSVolumeMapper> rightMapper;
  rightMapper->SetInputData(input.Shell);
  rightMapper->SetKBufferSize(2);
  vtkSmartPointer<vtkVolume> rightVolume = MakeVolume(rightMapper, input.Property, -0.7);

  TwoViewports scene(400, 200, leftVolume, rightVolume);
  SPTTestChecks::FailureCount failures;
  scene.Render(failures);
  if (leftMapper->GetKBufferSynchronizationInUse() < 0)
  {
    std::cout << "This context cannot synchronize the k-buffer; nothing to test.\n";
    return VTK_SKIP_RETURN_CODE;
  }
  scene.CheckCovered(Capture(scene.Window), 4000, failures);
  const vtkIdType tetrahedra = leftMapper->GetNumberOfTetrahedra();
  const vtkIdType faces = leftMapper->GetNumberOfFaces();
  const vtkIdType boundary = leftMapper->GetNumberOfBoundaryFaces();
  std::cout << tetrahedra << " tetrahedra, " << faces << " faces, " << boundary
            << " on the boundary; sort " << leftMapper->GetLastSortTime() << " s, GPU "
            << leftMapper->GetLastGPUTime() << " s; synchronization "
            << leftMapper->GetKBufferSynchronizationInUse() << "\n";
  input.CheckInputAndSplit(tetrahedra, failures);
  failures.Check(2 * faces == 4 * tetrahedra + boundary && rightMapper->GetNumberOfFaces() == faces,
    "the faces match the tetrahedra");
  failures.Check(leftMapper->GetLastSortTime() > 0.0 && rightMapper->GetLastGPUTime() > 0.0,
    "the mapper reports its sort and GPU times");
  return TwoViewports::ExitStatus(scene.CompareWithBaseline(argc, argv), failures);
}
