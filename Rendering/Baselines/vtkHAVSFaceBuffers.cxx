#include "vtkHAVSFaceBuffers.h"

#include "vtkObjectFactory.h"
#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLLoader.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkShaderProgram.h"

#include "vtkTetrahedralMesh.h"

#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstring>

namespace
{
// Draw calls are split so that their index counts stay far below GLsizei's range.
constexpr vtkIdType MaxFacesPerDraw = vtkIdType(1) << 24;

// One face of one tetrahedron: its vertex ids in increasing order, and the fourth vertex.
struct FaceOfTetrahedron
{
  std::array<unsigned int, 3> Ids;
  unsigned int Opposite;
  bool operator<(const FaceOfTetrahedron& other) const { return this->Ids < other.Ids; }
};

glm::vec3 PointOf(const std::vector<float>& points, unsigned int id)
{
  return glm::make_vec3(&points[3 * size_t(id)]);
}

// Every face of every tetrahedron, sorted by vertex ids so that copies of a face are adjacent.
std::vector<FaceOfTetrahedron> FacesOfTetrahedra(const std::vector<unsigned int>& tetrahedra)
{
  const size_t numberOfTetrahedra = tetrahedra.size() / 4;
  std::vector<FaceOfTetrahedron> all(4 * numberOfTetrahedra);
  for (size_t t = 0; t < numberOfTetrahedra; ++t)
  {
    const unsigned int* v = &tetrahedra[4 * t];
    for (int opposite = 0; opposite < 4; ++opposite)
    {
      FaceOfTetrahedron& face = all[4 * t + opposite];
      int n = 0;
      for (int corner = 0; corner < 4; ++corner)
      {
        if (corner != opposite)
        {
          face.Ids[n++] = v[corner];
        }
      }
      std::sort(face.Ids.begin(), face.Ids.end());
      face.Opposite = v[opposite];
    }
  }
  std::sort(all.begin(), all.end());
  return all;
}

// Order a boundary face's vertices so that its normal (right-hand rule) points away from its
// tetrahedron's fourth vertex: out of the mesh.
void WindOutward(
  const std::vector<float>& points, unsigned int opposite, std::array<unsigned int, 3>& ids)
{
  const glm::vec3 a = PointOf(points, ids[0]);
  const glm::vec3 normal = glm::cross(PointOf(points, ids[1]) - a, PointOf(points, ids[2]) - a);
  if (glm::dot(normal, PointOf(points, opposite) - a) > 0.0f)
  {
    std::swap(ids[1], ids[2]);
  }
}
}

vtkStandardNewMacro(vtkHAVSFaceBuffers);

vtkHAVSFaceBuffers::vtkHAVSFaceBuffers() = default;

vtkHAVSFaceBuffers::~vtkHAVSFaceBuffers() = default;

void vtkHAVSFaceBuffers::Update(const vtkTetrahedralMesh* mesh)
{
  if (mesh->GetBuildTime() == this->MeshBuildTime && this->BuildTime.GetMTime() > 0)
  {
    return;
  }
  this->MeshBuildTime = mesh->GetBuildTime();
  const std::vector<float>& points = mesh->GetPoints();
  const std::vector<FaceOfTetrahedron> all = FacesOfTetrahedra(mesh->GetTetrahedra());
  const size_t numberOfPoints = points.size() / 3;
  std::vector<unsigned int> boundaryCopy(numberOfPoints, ~0u);
  unsigned int numberOfCopies = 0;
  this->Faces.clear();
  this->Boundary.clear();
  this->Centroids.clear();
  this->NumberOfBoundaryFaces = 0;
  for (size_t begin = 0, end = 0; begin < all.size(); begin = end)
  {
    // A face that occurs once is on the boundary, one that occurs twice (or more, in a
    // non-manifold mesh) inside.
    for (end = begin + 1; end < all.size() && all[end].Ids == all[begin].Ids; ++end)
    {
    }
    std::array<unsigned int, 3> ids = all[begin].Ids;
    const bool boundary = end - begin == 1;
    if (boundary)
    {
      WindOutward(points, all[begin].Opposite, ids);
      for (unsigned int id : ids)
      {
        if (boundaryCopy[id] == ~0u)
        {
          boundaryCopy[id] = numberOfCopies++;
        }
      }
      ++this->NumberOfBoundaryFaces;
    }
    const glm::vec3 centroid =
      (PointOf(points, ids[0]) + PointOf(points, ids[1]) + PointOf(points, ids[2])) / 3.0f;
    for (unsigned int id : ids)
    {
      this->Faces.push_back(boundary ? unsigned(numberOfPoints) + boundaryCopy[id] : id);
    }
    this->Boundary.push_back(boundary ? 1 : 0);
    this->Centroids.insert(this->Centroids.end(), { centroid.x, centroid.y, centroid.z });
  }
  this->BuildVertices(mesh, boundaryCopy, numberOfCopies);
  this->Order.clear();
  this->SortedTriangles.clear();
  this->BuildTime.Modified();
}

void vtkHAVSFaceBuffers::BuildVertices(const vtkTetrahedralMesh* mesh,
  const std::vector<unsigned int>& boundaryCopy, unsigned int numberOfCopies)
{
  const std::vector<float>& points = mesh->GetPoints();
  const std::vector<float>& scalars = mesh->GetScalars();
  const size_t numberOfPoints = points.size() / 3;
  this->Vertices.assign(points.begin(), points.end());
  this->VertexScalars.assign(scalars.begin(), scalars.end());
  this->VertexScalars.resize(numberOfPoints, 0.0f);
  this->Vertices.resize(3 * (numberOfPoints + numberOfCopies));
  this->VertexScalars.resize(numberOfPoints + numberOfCopies);
  for (size_t id = 0; id < numberOfPoints; ++id)
  {
    if (boundaryCopy[id] != ~0u)
    {
      const size_t copy = numberOfPoints + boundaryCopy[id];
      std::copy_n(&points[3 * id], 3, &this->Vertices[3 * copy]);
      this->VertexScalars[copy] = this->VertexScalars[id] + BoundaryScalarOffset;
    }
  }
}

uint32_t vtkHAVSFaceBuffers::SortableKey(float value)
{
  // IEEE 754: flipping the sign bit orders positive floats after negative ones, and flipping
  // every bit of a negative float reverses the order of the magnitudes.
  uint32_t bits;
  std::memcpy(&bits, &value, sizeof(bits));
  return (bits & 0x80000000u) ? ~bits : (bits | 0x80000000u);
}

void vtkHAVSFaceBuffers::RadixSort(std::vector<uint32_t>& keys, std::vector<unsigned int>& values,
  std::vector<uint32_t>& scratchKeys, std::vector<unsigned int>& scratchValues)
{
  const size_t n = keys.size();
  scratchKeys.resize(n);
  scratchValues.resize(n);
  for (int shift = 0; shift < 32; shift += 8)
  {
    std::array<size_t, 257> offsets{};
    for (uint32_t key : keys)
    {
      ++offsets[((key >> shift) & 0xFFu) + 1];
    }
    if (std::any_of(offsets.begin() + 1, offsets.end(), [n](size_t count) { return count == n; }))
    {
      continue; // every key has the same digit here
    }
    for (size_t digit = 1; digit < offsets.size(); ++digit)
    {
      offsets[digit] += offsets[digit - 1];
    }
    for (size_t i = 0; i < n; ++i)
    {
      const size_t at = offsets[(keys[i] >> shift) & 0xFFu]++;
      scratchKeys[at] = keys[i];
      scratchValues[at] = values[i];
    }
    keys.swap(scratchKeys);
    values.swap(scratchValues);
  }
}

void vtkHAVSFaceBuffers::Sort(const float modelToView[16], bool parallelProjection)
{
  const auto start = std::chrono::steady_clock::now();
  const glm::mat4 matrix = glm::make_mat4(modelToView);
  const size_t numberOfFaces = this->Boundary.size();
  this->Keys.resize(numberOfFaces);
  this->Order.resize(numberOfFaces);
  for (size_t face = 0; face < numberOfFaces; ++face)
  {
    const glm::vec3 centroidVC =
      glm::vec3(matrix * glm::vec4(glm::make_vec3(&this->Centroids[3 * face]), 1.0f));
    // The camera looks down -z; in perspective the squared distance orders as the distance.
    const float distance = parallelProjection ? -centroidVC.z : glm::dot(centroidVC, centroidVC);
    this->Keys[face] = SortableKey(distance);
    this->Order[face] = static_cast<unsigned int>(face);
  }
  RadixSort(this->Keys, this->Order, this->ScratchKeys, this->ScratchOrder);
  this->SortedTriangles.resize(3 * numberOfFaces);
  for (size_t i = 0; i < numberOfFaces; ++i)
  {
    std::copy_n(&this->Faces[3 * size_t(this->Order[i])], 3, &this->SortedTriangles[3 * i]);
  }
  this->LastSortTime =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

bool vtkHAVSFaceBuffers::Upload(vtkOpenGLRenderWindow* renWin)
{
  if (this->Context && this->Context != renWin)
  {
    this->ReleaseGraphicsResources(this->Context);
  }
  if (this->Context != renWin || this->UploadTime < this->BuildTime)
  {
    this->Context = renWin;
    this->VertexArray.ForgetLayout();
    this->VertexBytes = 0;
    if (!this->PointBuffer->Upload(this->Vertices, vtkOpenGLBufferObject::ArrayBuffer) ||
      !this->ScalarBuffer->Upload(this->VertexScalars, vtkOpenGLBufferObject::ArrayBuffer))
    {
      vtkErrorMacro("Could not upload the " << this->Vertices.size() / 3
                                            << " vertices of the faces (out of GPU memory?).");
      this->ReleaseGraphicsResources(renWin);
      return false;
    }
    this->VertexBytes = sizeof(float) * (this->Vertices.size() + this->VertexScalars.size());
    this->UploadTime.Modified();
  }
  if (!this->IndexBuffer->Upload(this->SortedTriangles, vtkOpenGLBufferObject::ElementArrayBuffer))
  {
    vtkErrorMacro(
      "Could not upload the " << this->Boundary.size() << " sorted faces (out of GPU memory?).");
    this->ReleaseGraphicsResources(renWin);
    return false;
  }
  this->IndexBytes = sizeof(unsigned int) * this->SortedTriangles.size();
  return true;
}

void vtkHAVSFaceBuffers::Draw(vtkShaderProgram* program)
{
  this->VertexArray.Bind(program,
    { { "vertexMC", this->PointBuffer, 3 * sizeof(float), VTK_FLOAT, 3, false },
      { "scalarTF", this->ScalarBuffer, sizeof(float), VTK_FLOAT, 1, false } },
    this->IndexBuffer);
  const vtkIdType numberOfFaces = static_cast<vtkIdType>(this->SortedTriangles.size() / 3);
  vtkBatchedVertexArray::DrawElements(GL_TRIANGLES, 3, 0, numberOfFaces, MaxFacesPerDraw);
  this->VertexArray.Release();
}

size_t vtkHAVSFaceBuffers::GetGPUMemorySize() const
{
  return this->VertexBytes + this->IndexBytes;
}

void vtkHAVSFaceBuffers::ReleaseGraphicsResources(vtkWindow*)
{
  this->PointBuffer->ReleaseGraphicsResources();
  this->ScalarBuffer->ReleaseGraphicsResources();
  this->IndexBuffer->ReleaseGraphicsResources();
  this->VertexArray.ReleaseGraphicsResources();
  this->Context = nullptr;
  this->VertexBytes = 0;
  this->IndexBytes = 0;
}

void vtkHAVSFaceBuffers::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfFaces: " << this->GetNumberOfFaces() << "\n";
  os << indent << "NumberOfBoundaryFaces: " << this->NumberOfBoundaryFaces << "\n";
  os << indent << "NumberOfVertices: " << this->Vertices.size() / 3 << "\n";
  os << indent << "LastSortTime: " << this->LastSortTime << "\n";
  os << indent << "GPUMemorySize: " << this->GetGPUMemorySize() << "\n";
}
