// Image test of vtkPBVRVolumeMapper in the scene of SPTTestScene.h, two 128x128 viewports:
// - left: perspective, point scalars, the opaque sphere inside the shell hides part of it;
// - right: parallel projection, cell scalars, 2x2 subpixels, and a rotated, non-uniformly
//   scaled vtkVolume.
// Checks: the baseline image; that each viewport shows a volume (not the background); no
// OpenGL error; the input is not modified; the particle count and the memory are reported;
// a second render draws the same image from the same particles, a rotation of the camera about
// the data keeps them, and a change of the opacity makes new ones.

#include "vtkPBVRVolumeMapper.h"

#include "SPTTestScene.h"

using namespace SPTTestScene;

namespace
{
// The particle count, sets, memory and generation count after the first render, and the input
// untouched with its hexahedra split into 5 or 6 tetrahedra each.
int CheckParticles(
  vtkPBVRVolumeMapper* pointMapper, vtkPBVRVolumeMapper* cellMapper, const ShellInput& input)
{
  int failures = 0;
  const vtkIdType particles = pointMapper->GetNumberOfParticles();
  std::cout << "Particles: " << particles << " (perspective, 64 sets), "
            << cellMapper->GetNumberOfParticles() << " (parallel, 2x2 subpixels, 32 sets); "
            << pointMapper->GetGPUMemorySize() << " bytes on the GPU; generated in "
            << pointMapper->GetGenerationTime() << " s\n";
  if (particles < 64 * 1000 || pointMapper->GetNumberOfParticleSets() != 64 ||
    pointMapper->GetGPUMemorySize() < 8 * particles || cellMapper->GetNumberOfParticles() <= 0 ||
    pointMapper->GetGenerationCount() != 1 || cellMapper->GetGenerationCount() != 1)
  {
    std::cerr << "The particle count, sets, memory or generation count are not as expected.\n";
    ++failures;
  }
  return failures + input.CheckInputAndSplit(pointMapper->GetNumberOfTetrahedra());
}

// Particles are kept while nothing that shapes them changes, and made anew when it does.
int CheckRegeneration(TwoViewports& scene, const std::vector<unsigned char>& first,
  vtkVolumeProperty* property, vtkPBVRVolumeMapper* pointMapper, vtkPBVRVolumeMapper* cellMapper)
{
  int failures = 0;
  // The same particles again: the same image, no new generation.
  scene.Window->Render();
  if (Capture(scene.Window) != first || pointMapper->GetGenerationCount() != 1)
  {
    std::cerr << "A second render differs from the first or generated new particles.\n";
    ++failures;
  }
  // About the data's centre the nearest point of its bounding sphere stays as near.
  scene.Left->GetActiveCamera()->Azimuth(40.0);
  scene.Window->Render();
  if (pointMapper->GetGenerationCount() != 1)
  {
    std::cerr << "Rotating the camera about the data generated new particles.\n";
    ++failures;
  }
  property->GetScalarOpacity()->AddPoint(0.5, 0.2);
  scene.Window->Render();
  if (pointMapper->GetGenerationCount() != 2 || cellMapper->GetGenerationCount() != 2)
  {
    std::cerr << "A new opacity did not generate new particles.\n";
    ++failures;
  }
  return failures;
}
}

int TestPBVRVolumeMapper(int argc, char* argv[])
{
  const ShellInput input;
  vtkNew<vtkPBVRVolumeMapper> pointMapper;
  pointMapper->SetInputData(input.Shell);
  pointMapper->SetRepetitionLevel(64);
  pointMapper->SetSeed(1);
  vtkSmartPointer<vtkVolume> pointVolume = MakeVolume(pointMapper, input.Property);

  vtkNew<vtkPBVRVolumeMapper> cellMapper;
  cellMapper->SetInputData(input.Shell);
  SelectCellField(cellMapper);
  cellMapper->SetRepetitionLevel(32);
  cellMapper->SetSubpixelLevel(2);
  cellMapper->SetSeed(2);
  vtkSmartPointer<vtkVolume> cellVolume = MakeVolume(cellMapper, input.Property, 0.7);

  TwoViewports scene(256, 128, pointVolume, cellVolume);
  int failures = scene.Render();
  const std::vector<unsigned char> first = Capture(scene.Window);
  failures += scene.CheckCovered(first, 1500);
  failures += CheckParticles(pointMapper, cellMapper, input);

  const int result = scene.CompareWithBaseline(argc, argv);

  failures += CheckRegeneration(scene, first, input.Property, pointMapper, cellMapper);
  return TwoViewports::ExitStatus(result, failures);
}
