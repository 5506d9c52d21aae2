// Image test of vtkPBVRVolumeMapper: a hexahedral cylindrical shell (non-convex; the mapper
// splits the hexahedra itself) rendered in two 128x128 viewports:
// - left: perspective, point scalars, an opaque sphere inside the shell that hides part of it;
// - right: parallel projection, cell scalars, 2x2 subpixels, and a rotated, non-uniformly
//   scaled vtkVolume.
// Checks: the baseline image; that each viewport shows a volume (not the background); no
// OpenGL error; the input is not modified; the particle count and the memory are reported;
// a second render draws the same image from the same particles, a rotation of the camera about
// the data keeps them, and a change of the opacity makes new ones.

#include "vtkPBVRVolumeMapper.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkColorTransferFunction.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkStructuredGrid.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtkWindowToImageFilter.h"
#include "vtk_glew.h"

#include <cmath>
#include <iostream>
#include <vector>

namespace
{
// A thick cylindrical shell, 3/4 of a turn, as hexahedra with a point and a cell scalar.
vtkSmartPointer<vtkUnstructuredGrid> MakeShell()
{
  const int nr = 4, nt = 24, nz = 8;
  vtkNew<vtkStructuredGrid> grid;
  grid->SetDimensions(nr, nt, nz);
  vtkNew<vtkPoints> points;
  vtkNew<vtkFloatArray> field;
  field->SetName("pointField");
  for (int k = 0; k < nz; ++k)
  {
    for (int j = 0; j < nt; ++j)
    {
      for (int i = 0; i < nr; ++i)
      {
        const double radius = 1.0 + 0.6 * i / (nr - 1.0);
        const double angle = 1.5 * 3.14159265358979 * j / (nt - 1.0);
        const double z = 2.0 * k / (nz - 1.0) - 1.0;
        points->InsertNextPoint(radius * std::cos(angle), radius * std::sin(angle), z);
        field->InsertNextValue(static_cast<float>(0.5 + 0.5 * std::sin(3.0 * angle + 2.0 * z)));
      }
    }
  }
  grid->SetPoints(points);
  grid->GetPointData()->SetScalars(field);
  vtkNew<vtkFloatArray> cellField;
  cellField->SetName("cellField");
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
  {
    cellField->InsertNextValue(static_cast<float>((c * 7) % 11) / 10.0f);
  }
  grid->GetCellData()->AddArray(cellField);

  auto shell = vtkSmartPointer<vtkUnstructuredGrid>::New();
  shell->SetPoints(points);
  shell->Allocate(grid->GetNumberOfCells());
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
  {
    grid->GetCellPoints(c, ids);
    const vtkIdType hex[8] = { ids->GetId(0), ids->GetId(1), ids->GetId(3), ids->GetId(2),
      ids->GetId(4), ids->GetId(5), ids->GetId(7), ids->GetId(6) };
    shell->InsertNextCell(VTK_HEXAHEDRON, 8, hex);
  }
  shell->GetPointData()->ShallowCopy(grid->GetPointData());
  shell->GetCellData()->ShallowCopy(grid->GetCellData());
  return shell;
}

vtkSmartPointer<vtkVolumeProperty> MakeProperty()
{
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(0.0, 0.2, 0.3, 1.0);
  color->AddRGBPoint(0.5, 0.2, 1.0, 0.4);
  color->AddRGBPoint(1.0, 1.0, 0.4, 0.1);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.05);
  opacity->AddPoint(1.0, 0.9);
  auto property = vtkSmartPointer<vtkVolumeProperty>::New();
  property->SetColor(color);
  property->SetScalarOpacity(opacity);
  property->SetScalarOpacityUnitDistance(0.5);
  return property;
}

std::vector<unsigned char> Capture(vtkRenderWindow* window)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  grab->ShouldRerenderOff();
  grab->Update();
  vtkUnsignedCharArray* rgb =
    vtkUnsignedCharArray::SafeDownCast(grab->GetOutput()->GetPointData()->GetScalars());
  return std::vector<unsigned char>(rgb->GetPointer(0), rgb->GetPointer(0) + rgb->GetNumberOfValues());
}

// Pixels of columns [x0, x1) of a 3-component capture that differ from the black background.
int CountCovered(const std::vector<unsigned char>& rgb, int width, int x0, int x1)
{
  const int height = static_cast<int>(rgb.size() / (3 * size_t(width)));
  int covered = 0;
  for (int y = 0; y < height; ++y)
  {
    for (int x = x0; x < x1; ++x)
    {
      const size_t p = size_t(y) * width + x;
      covered += rgb[3 * p] + rgb[3 * p + 1] + rgb[3 * p + 2] > 24;
    }
  }
  return covered;
}
}

int TestPBVRVolumeMapper(int argc, char* argv[])
{
  vtkSmartPointer<vtkUnstructuredGrid> shell = MakeShell();
  const vtkMTimeType inputTime = shell->GetMTime();
  const vtkIdType inputCells = shell->GetNumberOfCells();
  vtkSmartPointer<vtkVolumeProperty> property = MakeProperty();

  vtkNew<vtkRenderWindow> window;
  window->SetSize(256, 128);
  window->SetMultiSamples(0);

  vtkNew<vtkPBVRVolumeMapper> pointMapper;
  pointMapper->SetInputData(shell);
  pointMapper->SetRepetitionLevel(64);
  pointMapper->SetSeed(1);
  vtkNew<vtkVolume> pointVolume;
  pointVolume->SetMapper(pointMapper);
  pointVolume->SetProperty(property);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(1.3, 0.0, 0.0);
  sphere->SetRadius(0.45);
  sphere->SetThetaResolution(32);
  sphere->SetPhiResolution(32);
  vtkNew<vtkPolyDataMapper> sphereMapper;
  sphereMapper->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkActor> sphereActor;
  sphereActor->SetMapper(sphereMapper);
  sphereActor->GetProperty()->SetColor(0.8, 0.8, 0.8);
  vtkNew<vtkRenderer> left;
  left->SetViewport(0.0, 0.0, 0.5, 1.0);
  left->AddVolume(pointVolume);
  left->AddActor(sphereActor);
  left->GetActiveCamera()->SetPosition(4.0, -5.0, 3.0);
  left->GetActiveCamera()->SetViewUp(0.0, 0.0, 1.0);
  left->ResetCamera();
  window->AddRenderer(left);

  vtkNew<vtkPBVRVolumeMapper> cellMapper;
  cellMapper->SetInputData(shell);
  cellMapper->SetScalarModeToUseCellFieldData();
  cellMapper->SelectScalarArray("cellField");
  cellMapper->SetRepetitionLevel(32);
  cellMapper->SetSubpixelLevel(2);
  cellMapper->SetSeed(2);
  vtkNew<vtkVolume> cellVolume;
  cellVolume->SetMapper(cellMapper);
  cellVolume->SetProperty(property);
  cellVolume->RotateZ(30.0);
  cellVolume->SetScale(1.0, 0.7, 1.3);
  vtkNew<vtkRenderer> right;
  right->SetViewport(0.5, 0.0, 1.0, 1.0);
  right->AddVolume(cellVolume);
  right->GetActiveCamera()->ParallelProjectionOn();
  right->GetActiveCamera()->SetPosition(0.0, -5.0, 4.0);
  right->GetActiveCamera()->SetViewUp(0.0, 0.0, 1.0);
  right->ResetCamera();
  window->AddRenderer(right);

  vtkNew<vtkRenderWindowInteractor> interactor;
  interactor->SetRenderWindow(window);
  window->Render();

  int failures = 0;
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
  {
    std::cerr << "OpenGL error " << error << " after rendering.\n";
    ++failures;
  }
  const std::vector<unsigned char> first = Capture(window);
  const int leftCovered = CountCovered(first, 256, 0, 128);
  const int rightCovered = CountCovered(first, 256, 128, 256);
  std::cout << "Covered pixels: " << leftCovered << " left, " << rightCovered << " right\n";
  if (leftCovered < 1500 || rightCovered < 1500)
  {
    std::cerr << "A viewport shows (almost) only the background.\n";
    ++failures;
  }
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
  const vtkIdType tetrahedra = pointMapper->GetNumberOfTetrahedra();
  if (shell->GetMTime() != inputTime || shell->GetNumberOfCells() != inputCells ||
    tetrahedra < 5 * inputCells || tetrahedra > 6 * inputCells)
  {
    std::cerr << "The input was modified, or its hexahedra not split into tetrahedra.\n";
    ++failures;
  }

  const int result = vtkRegressionTestImage(window);
  if (result == vtkRegressionTester::DO_INTERACTOR)
  {
    interactor->Start();
  }

  // The same particles again: the same image, no new generation.
  window->Render();
  if (Capture(window) != first || pointMapper->GetGenerationCount() != 1)
  {
    std::cerr << "A second render differs from the first or generated new particles.\n";
    ++failures;
  }
  // About the data's centre the nearest point of its bounding sphere stays as near.
  left->GetActiveCamera()->Azimuth(40.0);
  window->Render();
  if (pointMapper->GetGenerationCount() != 1)
  {
    std::cerr << "Rotating the camera about the data generated new particles.\n";
    ++failures;
  }
  property->GetScalarOpacity()->AddPoint(0.5, 0.2);
  window->Render();
  if (pointMapper->GetGenerationCount() != 2 || cellMapper->GetGenerationCount() != 2)
  {
    std::cerr << "A new opacity did not generate new particles.\n";
    ++failures;
  }
  return (result != vtkRegressionTester::FAILED && failures == 0) ? EXIT_SUCCESS : EXIT_FAILURE;
}
