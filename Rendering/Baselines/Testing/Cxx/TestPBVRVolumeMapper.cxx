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
void CheckParticles(vtkPBVRVolumeMapper* pointMapper, vtkPBVRVolumeMapper* cellMapper,
  const ShellInput& input, SPTTestChecks::FailureCount& failures)
{
  const vtkIdType particles = pointMapper->GetNumberOfParticles();
  std::cout << "Particles: " << particles << " (perspective, 64 sets), "
            << cellMapper->GetNumberOfParticles() << " (parallel, 2x2 subpixels, 32 sets); "
            << pointMapper->GetGPUMemorySize() << " bytes on the GPU; generated in "
            << pointMapper->GetGenerationTime() << " s\n";
  failures.Check(particles >= 64 * 1000 && pointMapper->GetNumberOfParticleSets() == 64 &&
      pointMapper->GetGPUMemorySize() >= 8 * particles && cellMapper->GetNumberOfParticles() > 0 &&
      pointMapper->GetGenerationCount() == 1 && cellMapper->GetGenerationCount() == 1,
    "the particle count, sets, memory and generation count");
  input.CheckInputAndSplit(pointMapper->GetNumberOfTetrahedra(), failures);
}

// Particles are kept while nothing that shapes them changes, and made anew when it does.
void CheckRegeneration(TwoViewports& scene, const std::vector<unsigned char>& first,
  vtkVolumeProperty* property, vtkPBVRVolumeMapper* pointMapper, vtkPBVRVolumeMapper* cellMapper,
  SPTTestChecks::FailureCount& failures)
{
  scene.Window->Render();
  failures.Check(Capture(scene.Window) == first && pointMapper->GetGenerationCount() == 1,
    "a second render draws the same image from the same particles");
  // About the data's centre the nearest point of its bounding sphere stays as near.
  scene.Left->GetActiveCamera()->Azimuth(40.0);
  scene.Window->Render();
  failures.Check(pointMapper->GetGenerationCount() == 1,
    "rotating the camera about the data keeps the particles");
  property->GetScalarOpacity()->AddPoint(0.5, 0.2);
  scene.Window->Render();
  failures.Check(pointMapper->GetGenerationCount() == 2 && cellMapper->GetGenerationCount() == 2,
    "a new opacity generates new particles");
}
}

int TestPBVRVolumeMapper(int argc, char* argv[])
{
  const ShellInput input;
  ShellVolumes<vtkPBVRVolumeMapper> volumes(input.Shell, input.Property);
  volumes.CellMapper->SetRepetitionLevel(32);
  volumes.CellMapper->SetSubpixelLevel(2);

  TwoViewports scene(256, 128, volumes.Point, volumes.Cell);
  SPTTestChecks::FailureCount failures;
  scene.Render(failures);
  const std::vector<unsigned char> first = Capture(scene.Window);
  scene.CheckCovered(first, 1500, failures);
  CheckParticles(volumes.PointMapper, volumes.CellMapper, input, failures);

  const int result = scene.CompareWithBaseline(argc, argv);

  CheckRegeneration(
    scene, first, input.Property, volumes.PointMapper, volumes.CellMapper, failures);
  return TwoViewports::ExitStatus(result, failures);
}
