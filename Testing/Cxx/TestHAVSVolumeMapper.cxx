// Image test of vtkHAVSVolumeMapper: a hexahedral cylindrical shell (non-convex: rays cross
// two walls with a gap between them; the mapper splits the hexahedra itself) rendered in two
// viewports:
// - left: perspective, k = 6, an opaque sphere inside the shell that hides part of it;
// - right: parallel projection, k = 2, and a rotated vtkVolume scaled by a negative factor
//   (a mirror, which swaps which boundary faces the rays leave the mesh through).
// Checks: the baseline image, that each viewport shows a volume (not the background), that no
// OpenGL error was raised, that the input was not modified, the face counts, and that the
// mapper reports its time split.

#include "vtkHAVSVolumeMapper.h"

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
    // Structured hexahedra in VTK_HEXAHEDRON order.
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

// Pixels of a viewport that differ from the black background.
int CountCovered(vtkRenderWindow* window, int x0, int x1)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  grab->Update();
  vtkUnsignedCharArray* rgb =
    vtkUnsignedCharArray::SafeDownCast(grab->GetOutput()->GetPointData()->GetScalars());
  int dims[3];
  grab->GetOutput()->GetDimensions(dims);
  int covered = 0;
  for (int y = 0; y < dims[1]; ++y)
  {
    for (int x = x0; x < x1; ++x)
    {
      const vtkIdType p = vtkIdType(y) * dims[0] + x;
      covered += rgb->GetValue(3 * p) + rgb->GetValue(3 * p + 1) + rgb->GetValue(3 * p + 2) > 24;
    }
  }
  return covered;
}
}

int TestHAVSVolumeMapper(int argc, char* argv[])
{
  vtkSmartPointer<vtkUnstructuredGrid> shell = MakeShell();
  const vtkMTimeType inputTime = shell->GetMTime();
  const vtkIdType inputCells = shell->GetNumberOfCells();
  vtkSmartPointer<vtkVolumeProperty> property = MakeProperty();

  vtkNew<vtkRenderWindow> window;
  window->SetSize(400, 200);
  window->SetMultiSamples(0);

  vtkNew<vtkHAVSVolumeMapper> leftMapper;
  leftMapper->SetInputData(shell);
  leftMapper->SetKBufferSize(6);
  vtkNew<vtkVolume> leftVolume;
  leftVolume->SetMapper(leftMapper);
  leftVolume->SetProperty(property);
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
  left->AddVolume(leftVolume);
  left->AddActor(sphereActor);
  left->GetActiveCamera()->SetPosition(4.0, -5.0, 3.0);
  left->GetActiveCamera()->SetViewUp(0.0, 0.0, 1.0);
  left->ResetCamera();
  window->AddRenderer(left);

  vtkNew<vtkHAVSVolumeMapper> rightMapper;
  rightMapper->SetInputData(shell);
  rightMapper->SetKBufferSize(2);
  vtkNew<vtkVolume> rightVolume;
  rightVolume->SetMapper(rightMapper);
  rightVolume->SetProperty(property);
  rightVolume->RotateZ(30.0);
  rightVolume->SetScale(1.0, -0.7, 1.3);
  vtkNew<vtkRenderer> right;
  right->SetViewport(0.5, 0.0, 1.0, 1.0);
  right->AddVolume(rightVolume);
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
  if (leftMapper->GetKBufferSynchronizationInUse() < 0)
  {
    std::cout << "This context cannot synchronize the k-buffer; nothing to test.\n";
    return VTK_SKIP_RETURN_CODE;
  }
  const int leftCovered = CountCovered(window, 0, 200);
  const int rightCovered = CountCovered(window, 200, 400);
  std::cout << "Covered pixels: " << leftCovered << " left, " << rightCovered << " right\n";
  if (leftCovered < 4000 || rightCovered < 4000)
  {
    std::cerr << "A viewport shows (almost) only the background.\n";
    ++failures;
  }
  const vtkIdType tetrahedra = leftMapper->GetNumberOfTetrahedra();
  const vtkIdType faces = leftMapper->GetNumberOfFaces();
  const vtkIdType boundary = leftMapper->GetNumberOfBoundaryFaces();
  std::cout << tetrahedra << " tetrahedra, " << faces << " faces, " << boundary
            << " on the boundary; sort " << leftMapper->GetLastSortTime() << " s, GPU "
            << leftMapper->GetLastGPUTime() << " s; synchronization "
            << leftMapper->GetKBufferSynchronizationInUse() << "\n";
  if (shell->GetMTime() != inputTime || shell->GetNumberOfCells() != inputCells ||
    tetrahedra < 5 * inputCells || tetrahedra > 6 * inputCells ||
    2 * faces != 4 * tetrahedra + boundary || rightMapper->GetNumberOfFaces() != faces)
  {
    std::cerr << "The input was modified, or the faces do not match the tetrahedra.\n";
    ++failures;
  }
  if (!(leftMapper->GetLastSortTime() > 0.0) || !(rightMapper->GetLastGPUTime() > 0.0))
  {
    std::cerr << "The mapper does not report its sort and GPU times.\n";
    ++failures;
  }

  const int result = vtkRegressionTestImage(window);
  if (result == vtkRegressionTester::DO_INTERACTOR)
  {
    interactor->Start();
  }
  return (result != vtkRegressionTester::FAILED && failures == 0) ? EXIT_SUCCESS : EXIT_FAILURE;
}
