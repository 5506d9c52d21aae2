#include "vtkHAVSNearCap.h"

#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLLoader.h"
#include "vtkShaderProgram.h"
#include "vtkTetrahedralMesh.h"

#include <algorithm>
#include <utility>

namespace
{
// Triangles per draw call, far below GLsizei's range.
constexpr vtkIdType MaxTrianglesPerDraw = 1 << 22;

// Distance in front of the near plane, in clip units: z + w, zero on the plane.
double NearDistance(const double m[4][4], const float* p)
{
  double d = m[2][3] + m[3][3];
  for (int i = 0; i < 3; ++i)
  {
    d += (m[2][i] + m[3][i]) * p[i];
  }
  return d;
}

// Twice the signed area of a polygon on the screen (normalized device coordinates).
double ScreenArea(const double m[4][4], const float (*polygon)[4], int count)
{
  double x[4], y[4];
  for (int k = 0; k < count; ++k)
  {
    double clip[4];
    for (int r = 0; r < 4; ++r)
    {
      clip[r] =
        m[r][0] * polygon[k][0] + m[r][1] * polygon[k][1] + m[r][2] * polygon[k][2] + m[r][3];
    }
    x[k] = clip[0] / clip[3];
    y[k] = clip[1] / clip[3];
  }
  double area = 0.0;
  for (int k = 0; k < count; ++k)
  {
    const int next = (k + 1) % count;
    area += x[k] * y[next] - x[next] * y[k];
  }
  return area;
}
}

vtkHAVSNearCap::vtkHAVSNearCap() = default;
vtkHAVSNearCap::~vtkHAVSNearCap() = default;

vtkIdType vtkHAVSNearCap::Build(const vtkTetrahedralMesh* mesh, const std::vector<float>& points,
  const std::vector<float>& scalars, const double modelToClip[4][4], float boundaryOffset,
  bool counterClockwise)
{
  this->Vertices.clear();
  this->Scalars.clear();
  this->Points = &points;
  this->PointScalars = &scalars;
  this->BoundaryOffset = boundaryOffset;
  this->ModelToClip = modelToClip;
  const std::vector<unsigned int>& tetrahedra = mesh->GetTetrahedra();
  for (size_t first = 0; first + 4 <= tetrahedra.size(); first += 4)
  {
    const unsigned int* ids = &tetrahedra[first];
    double distance[4];
    bool front = false, behind = false;
    for (int k = 0; k < 4; ++k)
    {
      distance[k] = NearDistance(modelToClip, &points[3 * size_t(ids[k])]);
      (distance[k] > 0.0 ? front : behind) = true;
    }
    if (front && behind)
    {
      this->CutTetrahedron(ids, distance, counterClockwise);
    }
  }
  return this->GetNumberOfTriangles();
}

void vtkHAVSNearCap::AddCutPoint(
  unsigned int a, unsigned int b, double da, double db, float cut[4]) const
{
  // The same edge gives the same point in every tetrahedron that has it.
  if (a > b)
  {
    std::swap(a, b);
    std::swap(da, db);
  }
  const double t = da / (da - db);
  const float* pa = &(*this->Points)[3 * size_t(a)];
  const float* pb = &(*this->Points)[3 * size_t(b)];
  for (int i = 0; i < 3; ++i)
  {
    cut[i] = float(pa[i] + t * (double(pb[i]) - pa[i]));
  }
  const double sa = (*this->PointScalars)[a];
  cut[3] = float(sa + t * ((*this->PointScalars)[b] - sa));
}

void vtkHAVSNearCap::CutTetrahedron(
  const unsigned int ids[4], const double distance[4], bool counterClockwise)
{
  // The vertices behind the near plane (or on it) first, then those in front.
  int order[4] = { 0, 1, 2, 3 };
  std::stable_partition(order, order + 4, [&](int k) { return distance[k] <= 0.0; });
  const int behind = int(std::count_if(distance, distance + 4, [](double d) { return d <= 0.0; }));
  // The cut edges in order around the section: each two consecutive ones share a face.
  int edges[4][2];
  int count = 0;
  if (behind == 2)
  {
    const int a = order[0], b = order[1], c = order[2], d = order[3];
    const int cycle[4][2] = { { a, c }, { a, d }, { b, d }, { b, c } };
    std::copy(&cycle[0][0], &cycle[0][0] + 8, &edges[0][0]);
    count = 4;
  }
  else
  {
    const int lone = behind == 1 ? order[0] : order[3];
    for (int k = 0; k < 4; ++k)
    {
      if (order[k] != lone)
      {
        edges[count][0] = lone;
        edges[count++][1] = order[k];
      }
    }
  }
  float polygon[4][4];
  for (int k = 0; k < count; ++k)
  {
    const int i = edges[k][0], j = edges[k][1];
    this->AddCutPoint(ids[i], ids[j], distance[i], distance[j], polygon[k]);
  }
  const double area = ScreenArea(this->ModelToClip, polygon, count);
  if (area == 0.0)
  {
    return; // seen edge on: it covers no pixel
  }
  const bool reverse = (area > 0.0) != counterClockwise;
  for (int triangle = 0; triangle + 2 < count; ++triangle)
  {
    const int corners[3] = { 0, triangle + 1, triangle + 2 };
    for (int k = 0; k < 3; ++k)
    {
      const float* p = polygon[corners[reverse ? 2 - k : k]];
      this->Vertices.insert(this->Vertices.end(), p, p + 3);
      this->Scalars.push_back(p[3] + this->BoundaryOffset);
    }
  }
}

bool vtkHAVSNearCap::Draw(vtkShaderProgram* program)
{
  if (this->Scalars.empty())
  {
    return true;
  }
  if (!this->VertexBuffer->Upload(this->Vertices, vtkOpenGLBufferObject::ArrayBuffer) ||
    !this->ScalarBuffer->Upload(this->Scalars, vtkOpenGLBufferObject::ArrayBuffer))
  {
    this->UploadedBytes = 0;
    return false;
  }
  this->UploadedBytes = sizeof(float) * (this->Vertices.size() + this->Scalars.size());
  this->VertexArray.ForgetLayout(); // the buffers were uploaded anew
  this->VertexArray.Bind(program,
    { { "vertexMC", this->VertexBuffer, 3 * sizeof(float), VTK_FLOAT, 3, false },
      { "scalarTF", this->ScalarBuffer, sizeof(float), VTK_FLOAT, 1, false } });
  vtkBatchedVertexArray::DrawArrays(
    GL_TRIANGLES, 0, vtkIdType(this->Scalars.size()), 3 * MaxTrianglesPerDraw);
  this->VertexArray.Release();
  return true;
}

void vtkHAVSNearCap::ReleaseGraphicsResources()
{
  this->VertexArray.ReleaseGraphicsResources();
  this->VertexBuffer->ReleaseGraphicsResources();
  this->ScalarBuffer->ReleaseGraphicsResources();
  this->UploadedBytes = 0;
}
