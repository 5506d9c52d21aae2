// A block of cubes, each split into 5 tetrahedra, for the C++ tests' meshes.
#ifndef SPTTestBlock_h
#define SPTTestBlock_h

#include "vtkCellType.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkSmartPointer.h"
#include "vtkUnstructuredGrid.h"

#include <utility>

namespace SPTTestBlock
{
// n[0] x n[1] x n[2] cubes, each split into 5 tetrahedra (alternating so that faces match):
// `point(i, j, k, points, scalars)` inserts lattice point (i, j, k) and its point scalar, the
// cubes where `keep(i, j, k)` is false are left out, and with `invert` every other tetrahedron
// is listed inverted.
template <class Point, class Keep>
vtkSmartPointer<vtkUnstructuredGrid> Make(const int n[3], Point point, Keep keep, bool invert)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkFloatArray> scalars;
  for (int k = 0; k <= n[2]; ++k)
  {
    for (int j = 0; j <= n[1]; ++j)
    {
      for (int i = 0; i <= n[0]; ++i)
      {
        point(i, j, k, points.Get(), scalars.Get());
      }
    }
  }
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->SetPoints(points);
  grid->GetPointData()->SetScalars(scalars);
  auto id = [&](int i, int j, int k) { return vtkIdType(i + (n[0] + 1) * (j + (n[1] + 1) * k)); };
  // Corners 0, 3, 5, 6 (or 1, 2, 4, 7 in odd cubes) form the central tetrahedron.
  const int tets[2][5][4] = { { { 0, 1, 3, 5 }, { 0, 2, 6, 3 }, { 0, 4, 5, 6 }, { 3, 5, 6, 7 },
                                { 0, 3, 6, 5 } },
    { { 1, 0, 2, 4 }, { 1, 3, 7, 2 }, { 1, 5, 4, 7 }, { 2, 4, 7, 6 }, { 1, 2, 7, 4 } } };
  int count = 0;
  for (int k = 0; k < n[2]; ++k)
  {
    for (int j = 0; j < n[1]; ++j)
    {
      for (int i = 0; i < n[0]; ++i)
      {
        if (!keep(i, j, k))
        {
          continue;
        }
        vtkIdType c[8];
        for (int corner = 0; corner < 8; ++corner)
        {
          c[corner] = id(i + (corner & 1), j + ((corner >> 1) & 1), k + ((corner >> 2) & 1));
        }
        for (const auto& tet : tets[(i + j + k) % 2])
        {
          vtkIdType ids[4] = { c[tet[0]], c[tet[1]], c[tet[2]], c[tet[3]] };
          if (invert && (count++ % 2 == 1))
          {
            std::swap(ids[0], ids[1]);
          }
          grid->InsertNextCell(VTK_TETRA, 4, ids);
        }
      }
    }
  }
  return grid;
}
}

#endif
