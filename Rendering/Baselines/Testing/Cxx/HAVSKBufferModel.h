// The k-buffer of vtkHAVSVolumeMapper's shaders on the CPU (Callahan et al. 2005): insertion
// of each fragment, the final flush and early termination, and compositing through the
// pre-integration table with trilinear filtering, in the shaders' single precision. The model
// against which TestHAVSKBufferOrdering checks the GPU's fragment order.

#ifndef HAVSKBufferModel_h
#define HAVSKBufferModel_h

#include "vtkPreIntegrationTable.h"

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
}

#endif
