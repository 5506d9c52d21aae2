// vtkTetGenMesher on bad input: each case reports an error that names the problem (observed,
// not printed), leaves an empty output, and does not crash or end the process. Cases: no
// input, an empty surface, quadrilaterals, a degenerate triangle, an open surface (one triangle
// of a sphere removed: 3 boundary edges), a non-manifold edge, inconsistent orientation, a flat
// closed surface, and two overlapping spheres (self-intersecting; found by TetGen itself).
// Afterwards the same mesher meshes a good sphere.

#include "vtkTetGenMesher.h"

#include "vtkAppendPolyData.h"
#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkTestErrorObserver.h"
#include "vtkUnstructuredGrid.h"

#include "SPTTestChecks.h"

#include <initializer_list>
#include <iostream>
#include <string>
#include <vector>

namespace
{
vtkSmartPointer<vtkPolyData> Sphere(double centerX)
{
  vtkNew<vtkSphereSource> source;
  source->SetCenter(centerX, 0.0, 0.0);
  source->SetThetaResolution(16);
  source->SetPhiResolution(12);
  source->Update();
  return source->GetOutput();
}

/// A surface from explicit points and cells (triangles or any polygon).
vtkSmartPointer<vtkPolyData> Surface(
  const std::vector<double>& coordinates, std::initializer_list<std::vector<vtkIdType>> cells)
{
  auto surface = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  for (std::size_t i = 0; i + 2 < coordinates.size(); i += 3)
  {
    points->InsertNextPoint(coordinates[i], coordinates[i + 1], coordinates[i + 2]);
  }
  vtkNew<vtkCellArray> polys;
  for (const auto& cell : cells)
  {
    polys->InsertNextCell(static_cast<vtkIdType>(cell.size()), cell.data());
  }
  surface->SetPoints(points);
  surface->SetPolys(polys);
  return surface;
}

/// The sphere with some triangles reversed or removed (the rest copied).
vtkSmartPointer<vtkPolyData> Edited(vtkPolyData* sphere, bool reverseFirst, bool dropFirst)
{
  auto surface = vtkSmartPointer<vtkPolyData>::New();
  surface->SetPoints(sphere->GetPoints());
  vtkNew<vtkCellArray> polys;
  for (vtkIdType cell = 0; cell < sphere->GetNumberOfPolys(); ++cell)
  {
    vtkIdType size;
    const vtkIdType* ids;
    sphere->GetCellPoints(cell, size, ids);
    if (cell == 0 && dropFirst)
    {
      continue;
    }
    const vtkIdType reversed[3] = { ids[0], ids[2], ids[1] };
    polys->InsertNextCell(3, cell == 0 && reverseFirst ? reversed : ids);
  }
  surface->SetPolys(polys);
  return surface;
}

// A new mesher of `input`, which must report an error with `expected` and give no cells.
vtkSmartPointer<vtkTetGenMesher> Expect(vtkPolyData* input, const std::string& expected,
  const std::string& name, SPTTestChecks::FailureCount& failures)
{
  auto mesher = vtkSmartPointer<vtkTetGenMesher>::New();
  vtkNew<vtkTest::ErrorObserver> errors;
  vtkNew<vtkTest::ErrorObserver> executiveErrors;
  mesher->AddObserver(vtkCommand::ErrorEvent, errors);
  mesher->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, executiveErrors);
  if (input)
  {
    mesher->SetInputData(input);
  }
  mesher->Update();
  const vtkIdType cells = mesher->GetOutput()->GetNumberOfCells();
  const std::string message = errors->GetErrorMessage() + executiveErrors->GetErrorMessage();
  // The message after the object's name and address, up to the end of its line.
  const std::size_t object = message.find("): ");
  const std::size_t start = object == std::string::npos ? 0 : object + 3;
  std::cout << name << ": " << message.substr(start, message.find('\n', start) - start) << "\n";
  failures.Check(message.find(expected) != std::string::npos,
    name + ": expected an error with \"" + expected + "\", got \"" + message + "\"");
  failures.Check(cells == 0, name + ": the output has " + std::to_string(cells) + " cells");
  return mesher;
}
} // namespace

int TestTetGenMesherErrors(int, char*[])
{
  SPTTestChecks::FailureCount failures;
  auto sphere = Sphere(0.0);
  const std::vector<double> cube = { 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1,
    0, 1, 1 };
  const std::vector<double> twoTetrahedra = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, -1, 0, 0, 0,
    -1 };

  Expect(nullptr, "connections", "no input", failures);
  Expect(vtkNew<vtkPolyData>(), "no triangles", "empty surface", failures);
  Expect(Surface(cube,
           { { 0, 3, 2, 1 }, { 4, 5, 6, 7 }, { 0, 1, 5, 4 }, { 1, 2, 6, 5 }, { 2, 3, 7, 6 },
             { 3, 0, 4, 7 } }),
    "6 polygons that are not triangles", "quadrilaterals", failures);
  Expect(Surface(twoTetrahedra, { { 0, 2, 1 }, { 0, 1, 3 }, { 0, 3, 2 }, { 1, 1, 3 } }),
    "1 degenerate triangle", "degenerate triangle", failures);
  vtkSmartPointer<vtkTetGenMesher> open =
    Expect(Edited(sphere, false, true), "open: 3 boundary edges", "open sphere", failures);
  // Two tetrahedra sharing the edge 0-1: that edge has four triangles.
  Expect(Surface(twoTetrahedra,
           { { 0, 2, 1 }, { 0, 1, 3 }, { 0, 3, 2 }, { 1, 2, 3 }, { 0, 1, 4 }, { 0, 5, 1 },
             { 0, 4, 5 }, { 1, 5, 4 } }),
    "not manifold: 1 edge", "non-manifold edge", failures);
  Expect(
    Edited(sphere, true, false), "not consistently oriented: 3 edges", "one flipped", failures);
  Expect(
    Surface(cube, { { 0, 1, 2 }, { 0, 2, 1 } }), "encloses no volume", "flat surface", failures);

  vtkNew<vtkAppendPolyData> overlapping;
  overlapping->AddInputData(sphere);
  overlapping->AddInputData(Sphere(0.5));
  overlapping->Update();
  Expect(overlapping->GetOutput(), "intersect", "two overlapping spheres", failures);

  // The mesher that reported the open sphere meshes a good one.
  open->SetInputData(sphere);
  open->Update();
  failures.Check(
    open->GetOutput()->GetNumberOfCells() != 0, "after an error, a good sphere gives tetrahedra");
  return failures.ExitStatus();
}
