#include "vtkSPTMeshBuffers.h"

#include "vtkObjectFactory.h"
#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLLoader.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

#include "vtkBatchedVertexArray.h"
#include "vtkTetrahedralMesh.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <numeric>

namespace
{
// Draw calls are split so that their index counts stay far below GLsizei's range.
constexpr vtkIdType MaxTetrahedraPerDraw = vtkIdType(1) << 22;

// The most texels a buffer texture of this context holds.
size_t MaxBufferTexels()
{
  GLint texels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &texels);
  return static_cast<size_t>(std::max(texels, 0));
}

// A point's square is about the square of the cell's longest edge; the cell covers on average
// a quarter of its surface area (Cauchy's formula for the mean projection of a convex body).
// Cells that cover less than this share of their square on average (needles and slivers) are
// drawn as triangles whatever their size: their squares would waste more samples than a point
// saves. A regular tetrahedron covers sqrt(3) / 4 = 0.43, a TetGen mesh's cells 0.2 to 0.3.
constexpr float SmallestPointFill = 0.15f;

// The longest edge of each tetrahedron (normalized units), and whether its mean projection
// fills enough of the square of that edge for it to be drawn as a point.
void CellShapes(
  const vtkTetrahedralMesh* mesh, std::vector<float>& longest, std::vector<bool>& pointShaped)
{
  const std::vector<float>& points = mesh->GetPoints();
  const std::vector<unsigned int>& tetrahedra = mesh->GetTetrahedra();
  longest.resize(tetrahedra.size() / 4);
  pointShaped.resize(longest.size());
  constexpr int faces[4][3] = { { 1, 2, 3 }, { 0, 2, 3 }, { 0, 1, 3 }, { 0, 1, 2 } };
  for (size_t t = 0; t < longest.size(); ++t)
  {
    const unsigned int* ids = &tetrahedra[4 * t];
    auto point = [&](int i) { return &points[3 * ids[i]]; };
    float squared = 0.0f;
    for (int i = 0; i < 4; ++i)
    {
      for (int j = i + 1; j < 4; ++j)
      {
        const float* a = point(i);
        const float* b = point(j);
        const float d[3] = { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
        squared = std::max(squared, d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      }
    }
    float surface = 0.0f;
    for (const auto& face : faces)
    {
      const float* a = point(face[0]);
      const float* b = point(face[1]);
      const float* c = point(face[2]);
      const float u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
      const float v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
      const float n[3] = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0] };
      surface += 0.5f * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    }
    longest[t] = std::sqrt(squared);
    pointShaped[t] = squared > 0.0f && 0.25f * surface >= SmallestPointFill * squared;
  }
}

// The size class of a longest edge `length` above the mesh's smallest edge `smallest`: classes
// are a factor of sqrt(2) apart, so that a threshold in pixels lands within that factor.
int SizeClass(float length, float smallest)
{
  constexpr int classes = 64;
  const double ratio = double(length) / smallest;
  const int c = ratio > 1.0 ? static_cast<int>(2.0 * std::log2(ratio)) : 0;
  return std::min(c, classes - 1);
}

// A buffer texture of `texels` texels of `components` values over `buffer`.
bool MakeBufferTexture(vtkSmartPointer<vtkTextureObject>& texture, vtkOpenGLRenderWindow* renWin,
  vtkOpenGLBufferObject* buffer, size_t texels, int components, int dataType,
  unsigned int internalFormat)
{
  if (!texture)
  {
    texture = vtkSmartPointer<vtkTextureObject>::New();
  }
  texture->SetContext(renWin);
  texture->SetInternalFormat(internalFormat);
  return texture->CreateTextureBuffer(
    static_cast<unsigned int>(texels), components, dataType, buffer);
}
}

vtkStandardNewMacro(vtkSPTMeshBuffers);

vtkSPTMeshBuffers::vtkSPTMeshBuffers() = default;

vtkSPTMeshBuffers::~vtkSPTMeshBuffers() = default;

bool vtkSPTMeshBuffers::Upload(vtkOpenGLRenderWindow* renWin, vtkTetrahedralMesh* mesh)
{
  if (this->Context == renWin && this->Mesh == mesh && this->UploadedBuild == mesh->GetBuildTime())
  {
    return true;
  }
  if (this->Context && this->Context != renWin)
  {
    this->ReleaseGraphicsResources(this->Context);
  }
  this->Context = renWin;
  this->Mesh = mesh;
  this->UploadedBuild = mesh->GetBuildTime();
  this->UploadedBytes = 0;
  this->VertexArray.ForgetLayout(); // the buffers are uploaded anew
  this->PointVertexArray.ForgetLayout();
  const std::vector<float>& points = mesh->GetPoints();
  const std::vector<float>& scalars = mesh->GetScalars();
  const std::vector<unsigned int>& tetrahedra = mesh->GetTetrahedra();
  if (tetrahedra.empty())
  {
    return true;
  }
  const size_t texels = std::max(scalars.size(), tetrahedra.size() / 4);
  const size_t maxTexels = MaxBufferTexels();
  if (texels > maxTexels)
  {
    vtkErrorMacro("The mesh has " << texels
                                  << " tetrahedra or points; this OpenGL context holds at most "
                                  << maxTexels << " in a buffer texture.");
    this->ReleaseGraphicsResources(renWin);
    return false;
  }
  const std::vector<unsigned int> order = this->ClassifyBySize(mesh);
  bool ok = this->PointBuffer->Upload(points, vtkOpenGLBufferObject::ArrayBuffer) &&
    MakeBufferTexture(
      this->PointTexture, renWin, this->PointBuffer, points.size() / 3, 3, VTK_FLOAT, GL_RGB32F);
  ok = ok && this->UploadTetrahedra(renWin, order) && this->UploadRandomIds(renWin, order);
  if (!ok)
  {
    vtkErrorMacro("Could not upload " << mesh->GetNumberOfTetrahedra()
                                      << " tetrahedra to the GPU (out of GPU memory?).");
    this->ReleaseGraphicsResources(renWin);
    return false;
  }
  this->UploadedBytes = sizeof(float) * (points.size() + scalars.size()) +
    sizeof(unsigned int) * (tetrahedra.size() + order.size() + mesh->GetRandomIds().size());
  return true;
}

std::vector<unsigned int> vtkSPTMeshBuffers::ClassifyBySize(const vtkTetrahedralMesh* mesh)
{
  // A stable counting sort by class: each class keeps the mesh's order. The cells shaped for
  // points come first, by size, then the others, by size.
  std::vector<float> longest;
  std::vector<bool> pointShaped;
  CellShapes(mesh, longest, pointShaped);
  float smallest = FLT_MAX; // the smallest positive
  for (float length : longest)
  {
    smallest = length > 0.0f ? std::min(smallest, length) : smallest;
  }
  const int sizeClasses = SizeClass(FLT_MAX, smallest) + 1;
  auto classOf = [&](size_t t)
  { return SizeClass(longest[t], smallest) + (pointShaped[t] ? 0 : sizeClasses); };
  std::vector<vtkIdType> starts(2 * sizeClasses + 1, 0);
  std::vector<float> classLongest(starts.size() - 1, -1.0f);
  for (size_t t = 0; t < longest.size(); ++t)
  {
    const int c = classOf(t);
    ++starts[c + 1];
    classLongest[c] = std::max(classLongest[c], longest[t]);
  }
  std::partial_sum(starts.begin(), starts.end(), starts.begin());
  this->ClassLongestEdges.clear();
  this->ClassEnds.clear();
  for (int c = 0; c < sizeClasses; ++c)
  {
    if (starts[c + 1] > starts[c])
    {
      this->ClassLongestEdges.push_back(classLongest[c]);
      this->ClassEnds.push_back(starts[c + 1]);
    }
  }
  std::vector<unsigned int> order(longest.size());
  for (size_t t = 0; t < longest.size(); ++t)
  {
    order[starts[classOf(t)]++] = static_cast<unsigned int>(t);
  }
  return order;
}

bool vtkSPTMeshBuffers::UploadTetrahedra(
  vtkOpenGLRenderWindow* renWin, const std::vector<unsigned int>& order)
{
  const std::vector<unsigned int>& tetrahedra = this->Mesh->GetTetrahedra();
  std::vector<unsigned int> sorted(tetrahedra.size());
  for (size_t t = 0; t < order.size(); ++t)
  {
    std::copy_n(&tetrahedra[4 * size_t(order[t])], 4, &sorted[4 * t]);
  }
  // The scalars are a vertex attribute for point scalars; every buffer is also a buffer
  // texture, for the cells that the fragment stage reads whole.
  const bool cellScalars = this->Mesh->GetCellScalars();
  std::vector<float> sortedCellScalars(cellScalars ? order.size() : 0);
  for (size_t t = 0; t < sortedCellScalars.size(); ++t)
  {
    sortedCellScalars[t] = this->Mesh->GetScalars()[order[t]];
  }
  const std::vector<float>& scalars = cellScalars ? sortedCellScalars : this->Mesh->GetScalars();
  return this->IndexBuffer->Upload(sorted, vtkOpenGLBufferObject::ElementArrayBuffer) &&
    this->ScalarBuffer->Upload(scalars,
      cellScalars ? vtkOpenGLBufferObject::TextureBuffer : vtkOpenGLBufferObject::ArrayBuffer) &&
    this->MeshIndexBuffer->Upload(order, vtkOpenGLBufferObject::TextureBuffer) &&
    MakeBufferTexture(
      this->ScalarTexture, renWin, this->ScalarBuffer, scalars.size(), 1, VTK_FLOAT, GL_R32F) &&
    MakeBufferTexture(this->TetrahedronTexture, renWin, this->IndexBuffer, order.size(), 4,
      VTK_UNSIGNED_INT, GL_RGBA32UI) &&
    MakeBufferTexture(this->MeshIndexTexture, renWin, this->MeshIndexBuffer, order.size(), 1,
      VTK_UNSIGNED_INT, GL_R32UI);
}

bool vtkSPTMeshBuffers::UploadRandomIds(
  vtkOpenGLRenderWindow* renWin, const std::vector<unsigned int>& order)
{
  const std::vector<unsigned int>& randomIds = this->Mesh->GetRandomIds();
  if (randomIds.empty())
  {
    if (this->RandomIdTexture)
    {
      this->RandomIdTexture->ReleaseGraphicsResources(renWin);
      this->RandomIdTexture = nullptr;
    }
    return true;
  }
  std::vector<unsigned int> sorted(order.size());
  for (size_t t = 0; t < order.size(); ++t)
  {
    sorted[t] = randomIds[order[t]];
  }
  return this->RandomIdBuffer->Upload(sorted, vtkOpenGLBufferObject::TextureBuffer) &&
    MakeBufferTexture(this->RandomIdTexture, renWin, this->RandomIdBuffer, sorted.size(), 1,
      VTK_UNSIGNED_INT, GL_R32UI);
}

void vtkSPTMeshBuffers::Bind(vtkShaderProgram* program)
{
  using Attribute = vtkBatchedVertexArray::Attribute;
  const Attribute points{ "vertexMC", this->PointBuffer, 3 * sizeof(float), VTK_FLOAT, 3, false };
  const Attribute scalars{ "scalarTF", this->ScalarBuffer, sizeof(float), VTK_FLOAT, 1, false };
  if (this->Mesh && this->Mesh->GetCellScalars())
  {
    this->VertexArray.Bind(program, { points }, this->IndexBuffer);
  }
  else
  {
    this->VertexArray.Bind(program, { points, scalars }, this->IndexBuffer);
  }
}

void vtkSPTMeshBuffers::Unbind()
{
  this->VertexArray.Release();
}

void vtkSPTMeshBuffers::Draw(vtkShaderProgram* program, vtkIdType first, vtkIdType count)
{
  const vtkIdType end =
    std::min(first + count, this->Mesh ? this->Mesh->GetNumberOfTetrahedra() : 0);
  vtkBatchedVertexArray::DrawElements(GL_LINES_ADJACENCY, 4, first, end - first,
    MaxTetrahedraPerDraw,
    [program](vtkIdType begin)
    { program->SetUniformi("primitiveOffset", static_cast<int>(begin)); });
}

vtkIdType vtkSPTMeshBuffers::CountSmallCells(double length) const
{
  const size_t classes =
    std::upper_bound(this->ClassLongestEdges.begin(), this->ClassLongestEdges.end(), length) -
    this->ClassLongestEdges.begin();
  return classes > 0 ? this->ClassEnds[classes - 1] : 0;
}

void vtkSPTMeshBuffers::DrawPoints(vtkShaderProgram* program, vtkIdType first, vtkIdType count)
{
  const vtkIdType end =
    std::min(first + count, this->Mesh ? this->Mesh->GetNumberOfTetrahedra() : 0);
  this->PointVertexArray.Bind(program, {});
  vtkBatchedVertexArray::DrawArrays(GL_POINTS, first, end - first, MaxTetrahedraPerDraw);
  this->PointVertexArray.Release();
}

void vtkSPTMeshBuffers::ReleaseGraphicsResources(vtkWindow* window)
{
  this->PointBuffer->ReleaseGraphicsResources();
  this->ScalarBuffer->ReleaseGraphicsResources();
  this->IndexBuffer->ReleaseGraphicsResources();
  this->RandomIdBuffer->ReleaseGraphicsResources();
  this->MeshIndexBuffer->ReleaseGraphicsResources();
  this->VertexArray.ReleaseGraphicsResources();
  this->PointVertexArray.ReleaseGraphicsResources();
  for (vtkSmartPointer<vtkTextureObject>* texture : { &this->ScalarTexture, &this->PointTexture,
         &this->TetrahedronTexture, &this->RandomIdTexture, &this->MeshIndexTexture })
  {
    if (*texture)
    {
      (*texture)->ReleaseGraphicsResources(window);
      *texture = nullptr;
    }
  }
  this->Context = nullptr;
  this->Mesh = nullptr;
  this->ClassLongestEdges.clear();
  this->ClassEnds.clear();
  this->UploadedBuild = 0;
  this->UploadedBytes = 0;
}

void vtkSPTMeshBuffers::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Mesh: " << this->Mesh.Get() << "\n";
  os << indent << "GPUMemorySize: " << this->UploadedBytes << "\n";
}
