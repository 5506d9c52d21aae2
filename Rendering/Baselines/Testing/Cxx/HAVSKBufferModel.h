// vtkHAVSVolumeMapper on the CPU, the model against which TestHAVSKBufferOrdering checks the
// GPU's fragment order:
// - the fragments of the mapper's faces as the GPU makes them: the faces (vtkHAVSFaceBuffers,
//   in the mapper's draw order) rasterized at the pixel centers, with the scalar and the eye
//   distance interpolated perspective-correct. Pixels whose center lies within EdgeMargin
//   pixels of a triangle edge, where coverage is a matter of rasterizer precision, are marked
//   ambiguous;
// - the k-buffer of the mapper's shaders (Callahan et al. 2005): insertion of each fragment,
//   the final flush and early termination, and compositing through the pre-integration table
//   with trilinear filtering, in the shaders' single precision.

#ifndef HAVSKBufferModel_h
#define HAVSKBufferModel_h

#include "vtkHAVSFaceBuffers.h"
#include "vtkPreIntegrationTable.h"
#include "vtkVolumeViewMatrices.h"

#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace HAVSKBufferModel
{
constexpr float EmptyDistance = 1.0e30f;
constexpr float OpaqueAlpha = 0.998046875f;

struct Entry
{
  float Scalar; // plus 2 where the ray leaves the mesh, plus 4 where it enters it
  float Distance;
};

// Trilinear lookup of the table at (front, back, sqrt(thickness)) in [0, 1]^3, texel centers
// at the ends, as the GPU's texture() with the mapper's scale and offset does.
inline glm::vec4 LookUp(const vtkPreIntegrationTable* table, float front, float back, float length)
{
  const int ns = table->GetScalarResolution();
  const int nl = table->GetLengthResolution();
  const float coordinate[3] = { front * (ns - 1), back * (ns - 1), length * (nl - 1) };
  const int sizes[3] = { ns, ns, nl };
  int lower[3];
  float weight[3];
  for (int a = 0; a < 3; ++a)
  {
    lower[a] = std::min(static_cast<int>(std::floor(coordinate[a])), sizes[a] - 2);
    weight[a] = coordinate[a] - lower[a];
  }
  glm::vec4 result(0.0f);
  for (int corner = 0; corner < 8; ++corner)
  {
    const int i = lower[0] + (corner & 1), j = lower[1] + ((corner >> 1) & 1),
              k = lower[2] + ((corner >> 2) & 1);
    const float w = ((corner & 1) ? weight[0] : 1.0f - weight[0]) *
      (((corner >> 1) & 1) ? weight[1] : 1.0f - weight[1]) *
      (((corner >> 2) & 1) ? weight[2] : 1.0f - weight[2]);
    result += w * glm::make_vec4(&table->GetTable()[4 * ((size_t(k) * ns + j) * ns + i)]);
  }
  return result;
}

// The k-buffer of the mapper's shaders, on the CPU.
class KBuffer
{
public:
  KBuffer(int size, const vtkPreIntegrationTable* table, float thicknessToTable, float lengthScale)
    : Entries(size - 1, Entry{ 0.0f, EmptyDistance })
    , Table(table)
    , ThicknessToTable(thicknessToTable)
    , LengthScale(lengthScale)
  {
  }

  void Insert(Entry fragment)
  {
    if (this->Color.a >= OpaqueAlpha)
    {
      return;
    }
    for (Entry& entry : this->Entries)
    {
      if (entry.Distance >= EmptyDistance)
      {
        entry = fragment;
        return;
      }
    }
    auto nearest = std::min_element(this->Entries.begin(), this->Entries.end(),
      [](const Entry& a, const Entry& b) { return a.Distance < b.Distance; });
    if (fragment.Distance <= nearest->Distance)
    {
      this->Composite(fragment, *nearest);
      return;
    }
    // Ties go to the stored entries, as in the shader.
    Entry next{ 0.0f, EmptyDistance };
    for (auto entry = this->Entries.begin(); entry != this->Entries.end(); ++entry)
    {
      if (entry != nearest && entry->Distance < next.Distance)
      {
        next = *entry;
      }
    }
    if (fragment.Distance < next.Distance)
    {
      next = fragment;
    }
    this->Composite(*nearest, next);
    *nearest = fragment;
  }

  glm::vec4 Flush()
  {
    if (this->Color.a < OpaqueAlpha)
    {
      std::stable_sort(this->Entries.begin(), this->Entries.end(),
        [](const Entry& a, const Entry& b) { return a.Distance < b.Distance; });
      for (size_t i = 0; i + 1 < this->Entries.size(); ++i)
      {
        this->Composite(this->Entries[i], this->Entries[i + 1]);
      }
    }
    return this->Color;
  }

private:
  void Composite(const Entry& front, const Entry& back)
  {
    const float frontCrossing = std::floor(front.Scalar * 0.5f);
    const float backCrossing = std::floor(back.Scalar * 0.5f);
    if (back.Distance >= EmptyDistance || (frontCrossing == 1.0f && backCrossing == 2.0f))
    {
      return;
    }
    const float frontScalar = front.Scalar - 2.0f * frontCrossing;
    const float backScalar = back.Scalar - 2.0f * backCrossing;
    const float thickness = std::max(back.Distance - front.Distance, 0.0f) * this->LengthScale;
    const float length = std::sqrt(std::min(thickness * this->ThicknessToTable, 1.0f));
    const glm::vec4 segment = LookUp(
      this->Table, glm::clamp(frontScalar, 0.0f, 1.0f), glm::clamp(backScalar, 0.0f, 1.0f), length);
    this->Color += (1.0f - this->Color.a) * segment;
  }

  std::vector<Entry> Entries;
  glm::vec4 Color{ 0.0f };
  const vtkPreIntegrationTable* Table;
  float ThicknessToTable;
  float LengthScale;
};

constexpr double EdgeMargin = 0.01; // pixels (llvmpipe snaps vertices to 1/256 pixel)

// What the CPU rasterizer found for one pixel: its fragments in draw order.
struct PixelFragments
{
  std::vector<Entry> Fragments;
  bool Ambiguous = false;
  float LengthScale = 0.0f;
};

// A face of the mapper in view and window coordinates, with its clip w and scalars.
struct ProjectedFace
{
  glm::dvec3 VC[3];
  glm::dvec2 Window[3];
  double W[3];
  double Scalar[3];
  double Area; // twice the signed window area: positive counter-clockwise
};

inline ProjectedFace ProjectFace(vtkHAVSFaceBuffers* faces, unsigned int face,
  const glm::mat4& modelToView, const glm::mat4& viewToClip, int size)
{
  ProjectedFace f;
  for (int v = 0; v < 3; ++v)
  {
    const unsigned int id = faces->GetFaces()[3 * size_t(face) + v];
    f.VC[v] = glm::dvec3(
      modelToView * glm::vec4(glm::make_vec3(&faces->GetVertices()[3 * size_t(id)]), 1.0f));
    const glm::dvec4 clip = glm::dmat4(viewToClip) * glm::dvec4(f.VC[v], 1.0);
    f.W[v] = clip.w;
    f.Window[v] = (glm::dvec2(clip) / clip.w + 1.0) * 0.5 * double(size);
    f.Scalar[v] = faces->GetVertexScalars()[id];
  }
  const glm::dvec2 e01 = f.Window[1] - f.Window[0], e02 = f.Window[2] - f.Window[0];
  f.Area = e01.x * e02.y - e01.y * e02.x;
  return f;
}

// The pixels with their length scale from view to model distance along their rays.
inline std::vector<PixelFragments> MakePixels(const vtkVolumeViewMatrices& m, int size)
{
  const glm::mat4 clipToView = glm::make_mat4(m.DCVC);
  const glm::mat3 viewToModel = glm::make_mat3(m.VCMCLinear);
  std::vector<PixelFragments> pixels(size_t(size) * size);
  for (int y = 0; y < size; ++y)
  {
    for (int x = 0; x < size; ++x)
    {
      const glm::vec2 ndc((x + 0.5f) / size * 2.0f - 1.0f, (y + 0.5f) / size * 2.0f - 1.0f);
      const glm::vec4 nearVC = clipToView * glm::vec4(ndc, -1.0f, 1.0f);
      const glm::vec4 farVC = clipToView * glm::vec4(ndc, 1.0f, 1.0f);
      const glm::vec3 ray = m.ParallelProjection
        ? glm::vec3(0.0f, 0.0f, -1.0f)
        : glm::normalize(glm::vec3(farVC) / farVC.w - glm::vec3(nearVC) / nearVC.w);
      pixels[y * size + x].LengthScale = glm::length(viewToModel * ray);
    }
  }
  return pixels;
}

// Barycentric weights of the window point p in the face. Returns whether p is covered (within
// EdgeMargin pixels of the inside); onEdge tells whether it is that close to an edge.
inline bool Cover(const ProjectedFace& f, glm::dvec2 p, double barycentric[3], bool& onEdge)
{
  double nearest = 1e30;
  bool inside = true;
  for (int v = 0; v < 3; ++v)
  {
    const glm::dvec2 a = f.Window[(v + 1) % 3], b = f.Window[(v + 2) % 3];
    const double edge = ((b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x)) / f.Area;
    barycentric[v] = edge;
    const double pixelsFromEdge = edge * std::abs(f.Area) / glm::length(b - a);
    nearest = std::min(nearest, std::abs(pixelsFromEdge));
    inside = inside && pixelsFromEdge > -EdgeMargin;
  }
  onEdge = nearest < EdgeMargin;
  return inside;
}

// The fragment at the barycentric weights: scalar (with the crossing code of a boundary face)
// and eye distance, interpolated perspective-correct, as the GPU does.
inline Entry Interpolate(const ProjectedFace& f, const double barycentric[3], bool parallel)
{
  const bool boundary = f.Scalar[0] > 1.5;
  // Counter-clockwise is front-facing: an outward face seen from behind is an exit.
  const float crossing = boundary ? (f.Area < 0.0 ? 2.0f : 4.0f) : 0.0f;
  double sum = 0.0, weights[3];
  for (int v = 0; v < 3; ++v)
  {
    weights[v] = barycentric[v] / f.W[v];
    sum += weights[v];
  }
  glm::dvec3 positionVC(0.0);
  double s = 0.0;
  for (int v = 0; v < 3; ++v)
  {
    positionVC += weights[v] / sum * f.VC[v];
    s += weights[v] / sum * f.Scalar[v];
  }
  const double distance = parallel ? -positionVC.z : glm::length(positionVC);
  const float code = float(glm::clamp(boundary ? s - 2.0 : s, 0.0, 1.0)) + crossing;
  return Entry{ code, float(distance) };
}

inline void RasterizeFace(
  const ProjectedFace& f, bool parallel, int size, std::vector<PixelFragments>& pixels)
{
  const glm::dvec2 lo = glm::min(f.Window[0], glm::min(f.Window[1], f.Window[2]));
  const glm::dvec2 hi = glm::max(f.Window[0], glm::max(f.Window[1], f.Window[2]));
  for (int y = std::max(0, int(lo.y) - 1); y <= std::min(size - 1, int(hi.y) + 1); ++y)
  {
    for (int x = std::max(0, int(lo.x) - 1); x <= std::min(size - 1, int(hi.x) + 1); ++x)
    {
      double barycentric[3];
      bool onEdge = false;
      if (!Cover(f, glm::dvec2(x + 0.5, y + 0.5), barycentric, onEdge))
      {
        continue;
      }
      PixelFragments& pixel = pixels[y * size + x];
      if (onEdge)
      {
        pixel.Ambiguous = true;
        continue;
      }
      pixel.Fragments.push_back(Interpolate(f, barycentric, parallel));
    }
  }
}

// The fragments of the mapper's faces, in its draw order, at every pixel center of a size x
// size image.
inline std::vector<PixelFragments> Rasterize(
  vtkHAVSFaceBuffers* faces, const vtkVolumeViewMatrices& m, int size)
{
  const glm::mat4 modelToView = glm::make_mat4(m.MCVC);
  const glm::mat4 viewToClip = glm::make_mat4(m.VCDC);
  std::vector<PixelFragments> pixels = MakePixels(m, size);
  for (unsigned int face : faces->GetOrder())
  {
    const ProjectedFace f = ProjectFace(faces, face, modelToView, viewToClip, size);
    if (f.Area != 0.0)
    {
      RasterizeFace(f, m.ParallelProjection, size, pixels);
    }
  }
  return pixels;
}
}

#endif
