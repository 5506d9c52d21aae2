// vtkTetGenMesher on a triangulated sphere:
// - the tetrahedra fill the polyhedron the triangles enclose, computed here independently by
//   the divergence theorem, and that polyhedron is close to the unit ball. TetGen adds Steiner
//   points on the surface, and treats neighbouring triangles within 0.1 degrees of coplanar as
//   one flat facet, so the volumes agree to 2e-9 relative here, tested to 1e-6;
// - every cell is a positively oriented VTK_TETRA, and the surface's points are kept;
// - TargetNumberOfCells is met within a factor of 1.5 at two sizes four times apart, and
//   MaximumVolume bounds the tetrahedra: TetGen 1.5.0 leaves about 2 in 10^4 of them (next to
//   the surface) up to 1.4 times larger, so at most 0.5 % may exceed it, none by 1.5 times;
// - the input is not modified, and a surface facing inwards gives the same mesh volume.

#include "vtkTetGenMesher.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellType.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkReverseSense.h"
#include "vtkSphereSource.h"
#include "vtkTetra.h"
#include "vtkUnstructuredGrid.h"

#include "SPTTestChecks.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

namespace
{
// The volume of the polyhedron, by the divergence theorem: the signed volumes of the
// tetrahedra from the origin to each triangle, summed.
double EnclosedVolume(vtkPolyData* surface)
{
  double origin[3] = { 0.0, 0.0, 0.0 };
  double sum = 0.0;
  auto polys = vtk::TakeSmartPointer(surface->GetPolys()->NewIterator());
  for (polys->GoToFirstCell(); !polys->IsDoneWithTraversal(); polys->GoToNextCell())
  {
    vtkIdType size;
    const vtkIdType* ids;
    polys->GetCurrentCell(size, ids);
    double a[3], b[3], c[3];
    surface->GetPoint(ids[0], a);
    surface->GetPoint(ids[1], b);
    surface->GetPoint(ids[2], c);
    sum += vtkTetra::ComputeVolume(origin, a, b, c);
  }
  return sum;
}

struct TetStatistics
{
  double Total = 0.0;
  double Smallest = VTK_DOUBLE_MAX;
  double Largest = 0.0;
  vtkIdType NotTetra = 0;
  vtkIdType OverBound = 0;
};

TetStatistics Measure(vtkUnstructuredGrid* grid, double bound = VTK_DOUBLE_MAX)
{
  TetStatistics statistics;
  for (vtkIdType cell = 0; cell < grid->GetNumberOfCells(); ++cell)
  {
    if (grid->GetCellType(cell) != VTK_TETRA)
    {
      ++statistics.NotTetra;
      continue;
    }
    vtkIdType size;
    const vtkIdType* ids;
    grid->GetCellPoints(cell, size, ids);
    double x[4][3];
    for (int corner = 0; corner < 4; ++corner)
    {
      grid->GetPoint(ids[corner], x[corner]);
    }
    const double volume = vtkTetra::ComputeVolume(x[0], x[1], x[2], x[3]);
    statistics.Total += volume;
    statistics.Smallest = std::min(statistics.Smallest, volume);
    statistics.Largest = std::max(statistics.Largest, volume);
    statistics.OverBound += volume > bound ? 1 : 0;
  }
  return statistics;
}

void TestVolumeAndOrientation(vtkPolyData* sphere, SPTTestChecks::FailureCount& failures)
{
  const double polyhedron = EnclosedVolume(sphere);
  const double ball = 4.0 / 3.0 * vtkMath::Pi();
  failures.Check(
    polyhedron > 0.97 * ball && polyhedron < ball, "the sphere's polyhedron is near a ball");

  const vtkMTimeType inputTime = sphere->GetMTime();
  const vtkIdType inputPoints = sphere->GetNumberOfPoints(),
                  inputPolys = sphere->GetNumberOfPolys();
  vtkNew<vtkTetGenMesher> mesher;
  mesher->SetInputData(sphere);
  mesher->Update();
  vtkUnstructuredGrid* grid = mesher->GetOutput();
  const TetStatistics tets = Measure(grid);
  std::cout << "default: " << grid->GetNumberOfCells() << " tets, volume " << tets.Total
            << " (polyhedron " << polyhedron << ", relative difference "
            << (tets.Total - polyhedron) / polyhedron << "), smallest " << tets.Smallest
            << ", switches " << mesher->GetTetGenSwitches() << "\n";
  failures.Check(grid->GetNumberOfCells() > 0, "the sphere gives tetrahedra");
  failures.Check(tets.NotTetra == 0, "every cell is a VTK_TETRA");
  failures.Check(tets.Smallest > 0.0, "every tetrahedron is positively oriented and not flat");
  failures.Check(std::abs(tets.Total - polyhedron) < 1e-6 * polyhedron,
    "the tetrahedra fill the enclosed polyhedron");
  failures.Check(std::abs(mesher->GetEnclosedVolume() - polyhedron) < 1e-12 * polyhedron,
    "EnclosedVolume is the polyhedron's volume");
  failures.Check(grid->GetNumberOfPoints() >= inputPoints, "the surface's points are kept");
  failures.Check(sphere->GetMTime() == inputTime && sphere->GetNumberOfPoints() == inputPoints &&
      sphere->GetNumberOfPolys() == inputPolys,
    "the input is not modified");

  vtkNew<vtkReverseSense> reverse;
  reverse->SetInputData(sphere);
  reverse->ReverseCellsOn();
  vtkNew<vtkTetGenMesher> inwards;
  inwards->SetInputConnection(reverse->GetOutputPort());
  inwards->Update();
  const TetStatistics reversed = Measure(inwards->GetOutput());
  failures.Check(
    reversed.Smallest > 0.0 && std::abs(reversed.Total - polyhedron) < 1e-6 * polyhedron,
    "a surface facing inwards gives the same positive tetrahedra");
}

void TestTargets(vtkPolyData* sphere, SPTTestChecks::FailureCount& failures)
{
  for (vtkIdType target : { vtkIdType(25000), vtkIdType(100000) })
  {
    vtkNew<vtkTetGenMesher> mesher;
    mesher->SetInputData(sphere);
    mesher->SetTargetNumberOfCells(target);
    mesher->Update();
    const vtkIdType count = mesher->GetOutput()->GetNumberOfCells();
    std::cout << "target " << target << ": " << count << " tets\n";
    failures.Check(count > target / 1.5 && count < target * 1.5,
      "TargetNumberOfCells " + std::to_string(target) + " gives " + std::to_string(count));
  }

  vtkNew<vtkTetGenMesher> mesher;
  mesher->SetInputData(sphere);
  const double bound = 1e-3;
  mesher->SetMaximumVolume(bound);
  mesher->Update();
  const vtkIdType count = mesher->GetOutput()->GetNumberOfCells();
  const TetStatistics tets = Measure(mesher->GetOutput(), bound);
  std::cout << "maximum volume " << bound << ": " << count << " tets, " << tets.OverBound
            << " larger, largest " << tets.Largest << "\n";
  failures.Check(tets.OverBound <= count / 200 && tets.Largest < 1.5 * bound,
    "MaximumVolume bounds the tetrahedra");
  failures.Check(mesher->GetAppliedMaximumVolume() == bound, "the bound applied is MaximumVolume");
}
} // namespace

int TestTetGenMesher(int, char*[])
{
  vtkNew<vtkSphereSource> source;
  source->SetRadius(1.0);
  source->SetThetaResolution(32);
  source->SetPhiResolution(24);
  source->Update();
  vtkPolyData* sphere = source->GetOutput();

  SPTTestChecks::FailureCount failures;
  TestVolumeAndOrientation(sphere, failures);
  TestTargets(sphere, failures);

  vtkNew<vtkTetGenMesher> printed;
  printed->Print(std::cout);
  return failures.ExitStatus();
}
