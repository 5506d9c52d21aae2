// Unit test of the object-space half of HAVS (vtkHAVSFaceBuffers), without OpenGL:
// - unique faces and boundary marks: a cube split into 5 tetrahedra has 16 faces, 12 of them
//   on the boundary; two disjoint tetrahedra have 8, all on the boundary; a 3x3x3 block of
//   such cubes has the counts that Euler's formula gives;
// - every boundary face is wound to face out of its tetrahedron (inverted tetrahedra too),
//   and indexes vertex copies whose scalar carries the boundary offset;
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

glm::vec3 Vertex(const vtkHAVSFaceBuffers* faces, unsigned int id)
{
  return glm::make_vec3(&faces->GetVertices()[3 * size_t(id)]);
}

void CheckFaces(vtkUnstructuredGrid* grid, vtkIdType expectedFaces, vtkIdType expectedBoundary,
  const char* name, SPTTestChecks::FailureCount& failures)
{
  vtkNew<vtkTetrahedralMesh> mesh;
  vtkTetrahedralMesh::ScalarSelection selection;
  failures.Check(mesh->Update(grid, selection), "the mesh is accepted");
  vtkNew<vtkHAVSFaceBuffers> faces;
  faces->Update(mesh);
  std::cout << name << ": " << faces->GetNumberOfFaces() << " faces, "
            << faces->GetNumberOfBoundaryFaces() << " on the boundary\n";
  failures.Check(faces->GetNumberOfFaces() == expectedFaces, "number of unique faces");
  failures.Check(faces->GetNumberOfBoundaryFaces() == expectedBoundary, "number of boundary faces");

  // The mesh is a union of unit cubes or tetrahedra whose centroid is inside: a boundary
  // face's outward normal points away from the centroid of its own tetrahedron, checked here
  // through the face's distance to the mesh's center of mass along the normal for convex
  // meshes, and in general by the scalar offset and the winding test below.
  const std::vector<unsigned int>& ids = faces->GetFaces();
  const size_t numberOfPoints = mesh->GetPoints().size() / 3;
  int wrongOffsets = 0;
  for (vtkIdType f = 0; f < faces->GetNumberOfFaces(); ++f)
  {
    const bool boundary = faces->GetBoundary()[f] != 0;
    for (int v = 0; v < 3; ++v)
    {
      const unsigned int vertex = ids[3 * f + v];
      const float scalar = faces->GetVertexScalars()[vertex];
      const bool copy = vertex >= numberOfPoints;
      wrongOffsets += copy != boundary ||
        (copy && std::abs(scalar - vtkHAVSFaceBuffers::BoundaryScalarOffset) > 1.0f + 1e-6f) ||
        (!copy && (scalar < 0.0f || scalar > 1.0f));
    }
  }
  failures.Check(wrongOffsets == 0, "boundary faces (only they) use the offset vertex copies");
}

// Boundary faces of a convex mesh face away from its center.
void CheckOutwardWinding(
  vtkUnstructuredGrid* grid, const char* name, SPTTestChecks::FailureCount& failures)
{
  vtkNew<vtkTetrahedralMesh> mesh;
  vtkTetrahedralMesh::ScalarSelection selection;
  mesh->Update(grid, selection);
  vtkNew<vtkHAVSFaceBuffers> faces;
  faces->Update(mesh);
  glm::vec3 center(0.0f);
  for (size_t i = 0; i < mesh->GetPoints().size() / 3; ++i)
  {
    center += glm::make_vec3(&mesh->GetPoints()[3 * i]);
  }
  center /= float(mesh->GetPoints().size() / 3);
  int inward = 0;
  for (vtkIdType f = 0; f < faces->GetNumberOfFaces(); ++f)
  {
    if (!faces->GetBoundary()[f])
    {
      continue;
    }
    const unsigned int* v = &faces->GetFaces()[3 * f];
    const glm::vec3 a = Vertex(faces, v[0]);
    const glm::vec3 normal = glm::cross(Vertex(faces, v[1]) - a, Vertex(faces, v[2]) - a);
    const glm::vec3 centroid = (a + Vertex(faces, v[1]) + Vertex(faces, v[2])) / 3.0f;
    inward += glm::dot(normal, centroid - center) <= 0.0f;
  }
  std::cout << name << ": " << inward << " boundary faces wound inward\n";
  failures.Check(inward == 0, "boundary faces are wound to face out of the mesh");
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
  vtkSmartPointer<vtkUnstructuredGrid> grid = MakeBlock(4, 3, 2, false);
  vtkNew<vtkTetrahedralMesh> mesh;
  vtkTetrahedralMesh::ScalarSelection selection;
  mesh->Update(grid, selection);
  vtkNew<vtkHAVSFaceBuffers> faces;
  faces->Update(mesh);
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
    const unsigned int* v = &faces->GetFaces()[3 * size_t(face)];
    const glm::vec3 centroid =
      (Vertex(faces, v[0]) + Vertex(faces, v[1]) + Vertex(faces, v[2])) / 3.0f;
    const glm::vec3 centroidVC = glm::vec3(view * glm::vec4(centroid, 1.0f));
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
  CheckFaces(MakeBlock(1, 1, 1, false), 16, 12, "one cube", failures);
  CheckFaces(MakeBlock(1, 1, 1, true), 16, 12, "one cube, inverted tetrahedra", failures);
  // A 3x3x3 block: 27 cubes x 5 = 135 tetrahedra; boundary: 6 sides x 9 squares x 2 triangles;
  // unique faces = (4 x 135 + 108) / 2.
  CheckFaces(MakeBlock(3, 3, 3, false), (4 * 135 + 108) / 2, 108, "3x3x3 cubes", failures);
  CheckOutwardWinding(MakeBlock(3, 3, 3, false), "3x3x3 cubes", failures);
  CheckOutwardWinding(MakeBlock(3, 3, 3, true), "3x3x3 cubes, inverted tetrahedra", failures);

  // Two disjoint tetrahedra.
  vtkNew<vtkUnstructuredGrid> two;
  vtkNew<vtkPoints> points;
  for (double offset : { 0.0, 3.0 })
  {
    points->InsertNextPoint(offset, 0, 0);
    points->InsertNextPoint(offset + 1, 0, 0);
    points->InsertNextPoint(offset, 1, 0);
    points->InsertNextPoint(offset, 0, 1);
  }
  two->SetPoints(points);
  const vtkIdType first[4] = { 0, 1, 2, 3 }, second[4] = { 4, 6, 5, 7 };
  two->InsertNextCell(VTK_TETRA, 4, first);
  two->InsertNextCell(VTK_TETRA, 4, second);
  vtkNew<vtkFloatArray> scalars;
  for (int i = 0; i < 8; ++i)
  {
    scalars->InsertNextValue(float(i));
  }
  two->GetPointData()->SetScalars(scalars);
  CheckFaces(two, 8, 8, "two disjoint tetrahedra", failures);

  CheckKeysAndRadixSort(failures);
  CheckSortOrder(false, failures);
  CheckSortOrder(true, failures);
  return failures.ExitStatus();
}
