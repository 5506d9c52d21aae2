// The scene of the mappers' image tests (TestSPTVolumeMapper, TestHAVSVolumeMapper,
// TestPBVRVolumeMapper): a hexahedral cylindrical shell, 3/4 of a turn (non-convex; the
// mappers split the hexahedra themselves), with a point and a cell scalar, in two viewports:
// - left: perspective, with an opaque sphere inside the shell that hides part of it;
// - right: parallel projection, the volume rotated and scaled as the test chooses.
// Also the checks the three tests share (counted in an SPTTestChecks::FailureCount): the input
// unmodified and split into tetrahedra, OpenGL errors, covered pixels per viewport, and the
// baseline comparison.

#ifndef SPTTestScene_h
#define SPTTestScene_h

#include "vtkAbstractVolumeMapper.h"
#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkColorTransferFunction.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkOpenGLLoader.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkUnstructuredGrid.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include "SPTTestChecks.h"
#include "SPTTestWindow.h"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

namespace SPTTestScene
{
// A thick cylindrical shell, 3/4 of a turn, as hexahedra with a point and a cell scalar.
inline vtkSmartPointer<vtkUnstructuredGrid> MakeShell()
{
  const int nr = 4, nt = 24, nz = 8;
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
  auto shell = vtkSmartPointer<vtkUnstructuredGrid>::New();
  shell->SetPoints(points);
  shell->GetPointData()->SetScalars(field);
  vtkNew<vtkFloatArray> cellField;
  cellField->SetName("cellField");
  auto id = [&](int i, int j, int k) { return vtkIdType(i + nr * (j + nt * k)); };
  for (int k = 0; k + 1 < nz; ++k)
  {
    for (int j = 0; j + 1 < nt; ++j)
    {
      for (int i = 0; i + 1 < nr; ++i)
      {
        // The corners of each face in the order (i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1):
        // not VTK_HEXAHEDRON's, so each cell is a twisted hexahedron, split by the mappers as
        // given (the baselines are of this mesh).
        const vtkIdType hex[8] = { id(i, j, k), id(i + 1, j, k), id(i, j + 1, k),
          id(i + 1, j + 1, k), id(i, j, k + 1), id(i + 1, j, k + 1), id(i, j + 1, k + 1),
          id(i + 1, j + 1, k + 1) };
        const vtkIdType c = shell->InsertNextCell(VTK_HEXAHEDRON, 8, hex);
        cellField->InsertNextValue(static_cast<float>((c * 7) % 11) / 10.0f);
      }
    }
  }
  shell->GetCellData()->AddArray(cellField);
  return shell;
}

// A volume of the mapper with the property. A scaleY other than 0 transforms it as the right
// viewport shows it: rotated by 30 degrees about z and scaled by (1, scaleY, 1.3).
inline vtkSmartPointer<vtkVolume> MakeVolume(
  vtkAbstractVolumeMapper* mapper, vtkVolumeProperty* property, double scaleY = 0.0)
{
  auto volume = vtkSmartPointer<vtkVolume>::New();
  volume->SetMapper(mapper);
  volume->SetProperty(property);
  if (scaleY != 0.0)
  {
    volume->RotateZ(30.0);
    volume->SetScale(1.0, scaleY, 1.3);
  }
  return volume;
}

// The baseline scene's two volumes of one stochastic mapper class, at 64 repetitions: the
// shell by its point scalar (seed 1) and, transformed, by its cell scalar (seed 2).
template <class Mapper>
struct ShellVolumes
{
  vtkNew<Mapper> PointMapper;
  vtkNew<Mapper> CellMapper;
  vtkSmartPointer<vtkVolume> Point;
  vtkSmartPointer<vtkVolume> Cell;

  ShellVolumes(vtkUnstructuredGrid* shell, vtkVolumeProperty* property)
  {
    this->PointMapper->SetInputData(shell);
    this->PointMapper->SetRepetitionLevel(64);
    this->PointMapper->SetSeed(1);
    this->Point = MakeVolume(this->PointMapper, property);
    this->CellMapper->SetInputData(shell);
    this->CellMapper->SetScalarModeToUseCellFieldData();
    this->CellMapper->SelectScalarArray("cellField");
    this->CellMapper->SetRepetitionLevel(64);
    this->CellMapper->SetSeed(2);
    this->Cell = MakeVolume(this->CellMapper, property, 0.7);
  }
};

inline vtkSmartPointer<vtkVolumeProperty> MakeProperty()
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

// The shell and the property of a mapper's image test, with the shell's state before the
// test, for CheckInputAndSplit().
struct ShellInput
{
  vtkSmartPointer<vtkUnstructuredGrid> Shell = MakeShell();
  vtkMTimeType Time = this->Shell->GetMTime();
  vtkIdType Cells = this->Shell->GetNumberOfCells();
  vtkSmartPointer<vtkVolumeProperty> Property = MakeProperty();

  // The shell unmodified, and each hexahedron split into 5 or 6 by the mapper that made
  // `tetrahedra` of it.
  void CheckInputAndSplit(vtkIdType tetrahedra, SPTTestChecks::FailureCount& failures) const
  {
    failures.Check(this->Shell->GetMTime() == this->Time &&
        this->Shell->GetNumberOfCells() == this->Cells && tetrahedra >= 5 * this->Cells &&
        tetrahedra <= 6 * this->Cells,
      "the input unmodified, its hexahedra split into 5 or 6 tetrahedra each (" +
        std::to_string(tetrahedra) + " tetrahedra for " + std::to_string(this->Cells) +
        " hexahedra)");
  }
};

// The scene's image, RGB (SPTTestWindow.h).
using SPTTestWindow::Capture;

// Pixels of columns [x0, x1) of a capture that differ from the black background.
inline int CountCovered(const std::vector<unsigned char>& rgb, int width, int x0, int x1)
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

// The two viewports of the test, each with its volume; the left one with the sphere.
class TwoViewports
{
public:
  // The scene in `window`, by default the tests' window (SPTTestWindow.h: X, else EGL).
  TwoViewports(int width, int height, vtkVolume* leftVolume, vtkVolume* rightVolume,
    vtkRenderWindow* window = nullptr)
    : Window(window ? vtkSmartPointer<vtkRenderWindow>(window) : SPTTestWindow::New())
  {
    this->Window->SetSize(width, height);
    this->Window->SetMultiSamples(0);
    this->Sphere->SetCenter(1.3, 0.0, 0.0);
    this->Sphere->SetRadius(0.45);
    this->Sphere->SetThetaResolution(32);
    this->Sphere->SetPhiResolution(32);
    this->SphereMapper->SetInputConnection(this->Sphere->GetOutputPort());
    this->SphereActor->SetMapper(this->SphereMapper);
    this->SphereActor->GetProperty()->SetColor(0.8, 0.8, 0.8);
    this->Left->SetViewport(0.0, 0.0, 0.5, 1.0);
    this->Left->AddVolume(leftVolume);
    this->Left->AddActor(this->SphereActor);
    this->Left->GetActiveCamera()->SetPosition(4.0, -5.0, 3.0);
    this->Left->GetActiveCamera()->SetViewUp(0.0, 0.0, 1.0);
    this->Left->ResetCamera();
    this->Window->AddRenderer(this->Left);
    this->Right->SetViewport(0.5, 0.0, 1.0, 1.0);
    this->Right->AddVolume(rightVolume);
    this->Right->GetActiveCamera()->ParallelProjectionOn();
    this->Right->GetActiveCamera()->SetPosition(0.0, -5.0, 4.0);
    this->Right->GetActiveCamera()->SetViewUp(0.0, 0.0, 1.0);
    this->Right->ResetCamera();
    this->Window->AddRenderer(this->Right);
    if (!this->Window->IsA("vtkHeadlessEGLRenderWindow"))
    {
      // An X interactor (for -I): the EGL window has no X window for one.
      this->Interactor->SetRenderWindow(this->Window);
    }
  }

  // Render, without an OpenGL error.
  void Render(SPTTestChecks::FailureCount& failures)
  {
    this->Window->Render();
    const GLenum error = glGetError();
    failures.Check(error == GL_NO_ERROR, "no OpenGL error (" + std::to_string(error) + ")");
  }

  // Each viewport of `rgb` shows at least `minimum` covered pixels.
  void CheckCovered(
    const std::vector<unsigned char>& rgb, int minimum, SPTTestChecks::FailureCount& failures)
  {
    const int width = this->Window->GetSize()[0];
    const int leftCovered = CountCovered(rgb, width, 0, width / 2);
    const int rightCovered = CountCovered(rgb, width, width / 2, width);
    std::cout << "Covered pixels: " << leftCovered << " left, " << rightCovered << " right\n";
    failures.Check(leftCovered >= minimum && rightCovered >= minimum,
      "each viewport shows the volume, not (almost) only the background");
  }

  // The baseline comparison (or the interactor, with -I): vtkRegressionTester's result.
  int CompareWithBaseline(int argc, char* argv[])
  {
    const int result = vtkRegressionTestImage(this->Window);
    if (result == vtkRegressionTester::DO_INTERACTOR && this->Interactor->GetRenderWindow())
    {
      this->Interactor->Start();
    }
    return result;
  }

  static int ExitStatus(int result, const SPTTestChecks::FailureCount& failures)
  {
    return result == vtkRegressionTester::FAILED ? EXIT_FAILURE : failures.ExitStatus();
  }

  vtkSmartPointer<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> Left;
  vtkNew<vtkRenderer> Right;

private:
  vtkNew<vtkSphereSource> Sphere;
  vtkNew<vtkPolyDataMapper> SphereMapper;
  vtkNew<vtkActor> SphereActor;
  vtkNew<vtkRenderWindowInteractor> Interactor;
};
}

#endif
