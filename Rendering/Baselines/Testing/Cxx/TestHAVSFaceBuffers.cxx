// Unit test of the object-space half of HAVS (vtkHAVSFaceBuffers), without OpenGL:
// - unique faces and boundary marks: a cube split into 5 tetrahedra has 16 faces, 12 of them
//   on the boundary; two disjoint tetrahedra have 8, all on the boundary; a 3x3x3 block of
//   such cubes has the counts that Euler's formula gives;
// - every boundary face of a convex block is wound to face out of it (inverted tetrahedra
//   too), and indexes vertex copies whose scalar carries the boundary offset;
// - the float-to-key map keeps the order of floats, negative ones included;
// - the radix sort agrees with std::stable_sort, and Sort() orders faces by the distance of
//   their centroids from the eye (perspective) or by depth (parallel).

#include "vtkHAVSFaceBuffers.h"
#include "vtkTetrahedralMesh.h"

#include "vtkCellArray.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkUnstructuredGrid.h"

#include "SPTTestBlock.h"
#include "SPTTestChecks.h"

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numeric>
#include <random>
#include <vector>

namespace
{
// A block of nx x ny x nz unit cubes of 5 tetrahedra each, with a point scalar. With
// `invert`, every other tetrahedron is listed inverted.
vtkSmartPointer<vtkUnstructuredGrid> MakeBlock(int nx, int ny, int nz, bool invert)
{
  const int n[3] = { nx, ny, nz };
  auto grid = SPTTestBlock::Make(
    n,
    [](int i, int j, int k, vtkPoints* points, vtkFloatArray* scalars)
    {
      points->InsertNextPoint(i, j, k);
      scalars->InsertNextValue(static_cast<float>(i + 2 * j + 3 * k));
    },
    [](int, int, int) { return true; }, invert);
  grid->GetPointData()->GetScalars()->SetName("s");
  return grid;
}

// The mapper's faces of a grid, and the mesh they index.
struct MeshFaces
{
  explicit MeshFaces(vtkUnstructuredGrid* grid)
    : Accepted(this->Mesh->Update(grid, vtkTetrahedralMesh::ScalarSelection()))
  {
    this->Faces->Update(this->Mesh);
  }

  glm::vec3 Vertex(unsigned int id) const
  {
    return glm::make_vec3(&this->Faces->GetVertices()[3 * size_t(id)]);
  }

  glm::vec3 Centroid(unsigned int face) const
  {
    const unsigned int* v = &this->Faces->GetFaces()[3 * size_t(face)];
    return (this->Vertex(v[0]) + this->Vertex(v[1]) + this->Vertex(v[2])) / 3.0f;
  }

  vtkNew<vtkTetrahedralMesh> Mesh;
  vtkNew<vtkHAVSFaceBuffers> Faces;
  bool Accepted;
};

// The face counts; boundary faces (and only they) index the vertex copies whose scalar carries
// the boundary offset; and, on a convex mesh, boundary faces face away from its center.
void CheckFaces(vtkUnstructuredGrid* grid, vtkIdType expectedFaces, vtkIdType expectedBoundary,
  bool convex, const char* name, SPTTestChecks::FailureCount& failures)
{
  const MeshFaces m(grid);
  vtkHAVSFaceBuffers* faces = m.Faces;
  failures.Check(m.Accepted, "the mesh is accepted");
  std::cout << name << ": " << faces->GetNumberOfFaces() << " faces, "
            << faces->GetNumberOfBoundaryFaces() << " on the boundary\n";
  failures.Check(faces->GetNumberOfFaces() == expectedFaces, "number of unique faces");
  failures.Check(faces->GetNumberOfBoundaryFaces() == expectedBoundary, "number of boundary faces");

  const size_t numberOfPoints = m.Mesh->GetPoints().size() / 3;
  glm::vec3 center(0.0f);
  for (size_t i = 0; i < numberOfPoints; ++i)
  {
    center += glm::make_vec3(&m.Mesh->GetPoints()[3 * i]);
  }
  center /= float(numberOfPoints);
  int wrongOffsets = 0, inward = 0;
  for (vtkIdType f = 0; f < faces->GetNumberOfFaces(); ++f)
  {
    const bool boundary = faces->GetBoundary()[f] != 0;
    const unsigned int* v = &faces->GetFaces()[3 * f];
    for (int corner = 0; corner < 3; ++corner)
    {
      const float scalar = faces->GetVertexScalars()[v[corner]];
      const bool copy = v[corner] >= numberOfPoints;
      wrongOffsets += copy != boundary ||
        (copy && std::abs(scalar - vtkHAVSFaceBuffers::BoundaryScalarOffset) > 1.0f + 1e-6f) ||
        (!copy && (scalar < 0.0f || scalar > 1.0f));
    }
    const glm::vec3 a = m.Vertex(v[0]);
    const glm::vec3 normal = glm::cross(m.Vertex(v[1]) - a, m.Vertex(v[2]) - a);
    inward += boundary && glm::dot(normal, m.Centroid(unsigned(f)) - center) <= 0.0f;
  }
  failures.Check(wrongOffsets == 0, "boundary faces (only they) use the offset vertex copies");
  if (convex)
  {
    std::cout << name << ": " << inward << " boundary faces wound inward\n";
    failures.Check(inward == 0, "boundary faces are wound to face out of the mesh");
  }
}

void CheckKeysAndRadixSort(SPTTestChecks::FailureCount& failures)
{
  std::mt19937 random(7);
  std::uniform_real_distribution<float> uniform(-1000.0f, 1000.0f);
  std::vector<float> values = { -0.0f, 0.0f, -1e-30f, 1e-30f, -3.0e38f, 3.0e38f, 1.0f, -1.0f };
  for (int i = 0; i < 20000; ++i)
  {
    values.push_back(uniform(random) * (i % 3 == 0 ? 1e-6f : 1.0f));
  }
  for (int i = 0; i < 2000; ++i)
  {
    values.push_back(std::round(uniform(random) * 0.01f)); // many equal keys
  }
  int misordered = 0;
  for (size_t i = 0; i + 1 < values.size(); ++i)
  {
    const float a = values[i], b = values[i + 1];
    const uint32_t ka = vtkHAVSFaceBuffers::SortableKey(a);
    const uint32_t kb = vtkHAVSFaceBuffers::SortableKey(b);
    misordered += (a < b && !(ka < kb)) || (a > b && !(ka > kb));
  }
  failures.Check(misordered == 0, "SortableKey keeps the order of floats");

  std::vector<uint32_t> keys(values.size()), scratchKeys;
  std::vector<unsigned int> order(values.size()), scratchOrder;
  for (size_t i = 0; i < values.size(); ++i)
  {
    keys[i] = vtkHAVSFaceBuffers::SortableKey(values[i]);
    order[i] = static_cast<unsigned int>(i);
  }
  vtkHAVSFaceBuffers::RadixSort(keys, order, scratchKeys, scratchOrder);
  std::vector<unsigned int> expected(values.size());
  std::iota(expected.begin(), expected.end(), 0u);
  std::stable_sort(expected.begin(), expected.end(),
    [&](unsigned int a, unsigned int b)
    {
      return vtkHAVSFaceBuffers::SortableKey(values[a]) <
        vtkHAVSFaceBuffers::SortableKey(values[b]);
    });
  failures.Check(order == expected, "the radix sort is the stable sort by key");
  failures.Check(std::is_sorted(keys.begin(), keys.end()), "the sorted keys are in order");
}

void CheckSortOrder(bool parallel, SPTTestChecks::FailureCount& failures)
{
  const MeshFaces m(MakeBlock(4, 3, 2, false));
  vtkHAVSFaceBuffers* faces = m.Faces;
  const glm::mat4 view =
    glm::lookAt(glm::vec3(1.3f, -2.0f, 1.7f), glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 1.0f));
  faces->Sort(glm::value_ptr(view), parallel);
  const std::vector<unsigned int>& order = faces->GetOrder();
  failures.Check(order.size() == size_t(faces->GetNumberOfFaces()), "every face is sorted");
  double previous = -1e30;
  int misordered = 0;
  std::vector<char> seen(order.size(), 0);
  for (unsigned int face : order)
  {
    seen[face] = 1;
    const glm::vec3 centroidVC = glm::vec3(view * glm::vec4(m.Centroid(face), 1.0f));
    const double key = parallel ? -centroidVC.z : glm::length(centroidVC);
    misordered += key < previous - 1e-5;
    previous = std::max(previous, key);
  }
  failures.Check(
    misordered == 0, parallel ? "faces sorted by depth" : "faces sorted by eye distance");
  failures.Check(
    std::count(seen.begin(), seen.end(), 1) == long(seen.size()), "the order is a permutation");
  failures.Check(faces->GetLastSortTime() >= 0.0, "the sort time is measured");
}
}

int TestHAVSFaceBuffers(int, char*[])
{
  SPTTestChecks::FailureCount failures;
  // One cube: 5 tetrahedra, 4 faces shared by the central one: 20 - 4 = 16 unique, 12 outside.
  CheckFaces(MakeBlock(1, 1, 1, false), 16, 12, true, "one cube", failures);
  CheckFaces(MakeBlock(1, 1, 1, true), 16, 12, true, "one cube, inverted tetrahedra", failures);
  // A 3x3x3 block: 27 cubes x 5 = 135 tetrahedra; boundary: 6 sides x 9 squares x 2 triangles;
  // unique faces = (4 x 135 + 108) / 2.
  for (bool invert : { false, true })
  {
    CheckFaces(MakeBlock(3, 3, 3, invert), (4 * 135 + 108) / 2, 108, true,
      invert ? "3x3x3 cubes, inverted tetrahedra" : "3x3x3 cubes", failures);
  }

  // Two disjoint tetrahedra, the second listed inverted.
  vtkNew<vtkUnstructuredGrid> two;
  vtkNew<vtkPoints> points;
  vtkNew<vtkFloatArray> scalars;
  for (int i = 0; i < 8; ++i)
  {
    const int corner = i % 4;
    points->InsertNextPoint((i < 4 ? 0.0 : 3.0) + (corner == 1), corner == 2, corner == 3);
    scalars->InsertNextValue(float(i));
  }
  two->SetPoints(points);
  two->GetPointData()->SetScalars(scalars);
  const vtkIdType first[4] = { 0, 1, 2, 3 }, second[4] = { 4, 6, 5, 7 };
  two->InsertNextCell(VTK_TETRA, 4, first);
  two->InsertNextCell(VTK_TETRA, 4, second);
  CheckFaces(two, 8, 8, false, "two disjoint tetrahedra", failures);

  CheckKeysAndRadixSort(failures);
  CheckSortOrder(false, failures);
  CheckSortOrder(true, failures);
  return failures.ExitStatus();
}
