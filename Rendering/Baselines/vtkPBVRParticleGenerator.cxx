#include "vtkPBVRParticleGenerator.h"
#include "vtkPBVRVolumeMapper.h"

#include "vtkObjectFactory.h"
#include "vtkSMPTools.h"

#include "vtkTetrahedralMesh.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <sstream>

namespace
{
// Cells per task of the parallel loop; blocks keep the output order independent of threads.
constexpr vtkIdType TetrahedraPerBlock = 4096;
// Poisson means above this are drawn from the normal approximation (relative error of the
// count's spread below 1e-3), below it exactly by inversion.
constexpr double LargePoissonMean = 1024.0;
// Generation gives up, as too slow to be useful, when it would have to try more candidates
// than this many per particle the memory could hold.
constexpr double MaximumCandidatesPerParticle = 64.0;
constexpr double TwoPi = 6.283185307179586;

uint64_t SplitMix64(uint64_t x)
{
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// PCG32 (O'Neill 2014): one independent stream per cell, keyed by (seed, cell).
class RandomStream
{
public:
  explicit RandomStream(uint64_t key)
    : State(SplitMix64(key))
  {
    this->Next();
  }

  uint32_t Next()
  {
    const uint64_t old = this->State;
    this->State = old * 6364136223846793005ull + 1442695040888963407ull;
    const uint32_t shifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    const uint32_t rotation = static_cast<uint32_t>(old >> 59u);
    return (shifted >> rotation) | (shifted << ((32u - rotation) & 31u));
  }

  /// Uniform in [0, 1), 24 bits.
  float Uniform() { return static_cast<float>(this->Next() >> 8) * (1.0f / 16777216.0f); }

  /// Uniform in (0, 1), 32 bits.
  double OpenUniform() { return (this->Next() + 0.5) * (1.0 / 4294967296.0); }

  /// Uniform integer in [0, n).
  uint32_t Below(uint32_t n)
  {
    return static_cast<uint32_t>((static_cast<uint64_t>(this->Next()) * n) >> 32);
  }

  uint64_t Poisson(double mean)
  {
    if (mean > LargePoissonMean)
    {
      const double normal =
        std::sqrt(-2.0 * std::log(this->OpenUniform())) * std::cos(TwoPi * this->OpenUniform());
      return static_cast<uint64_t>(
        std::max(0.0, std::floor(mean + std::sqrt(mean) * normal + 0.5)));
    }
    // A sum of Poisson variables is Poisson; pieces of mean 32 keep exp(-mean) far from
    // underflow and the inversion short.
    uint64_t count = 0;
    for (; mean > 32.0; mean -= 32.0)
    {
      count += this->SmallPoisson(32.0);
    }
    return count + this->SmallPoisson(mean);
  }

  /// Barycentric coordinates of a point uniform in a tetrahedron (Rocchini and Cignoni 2000).
  glm::vec4 UniformInTetrahedron()
  {
    float s = this->Uniform(), t = this->Uniform(), u = this->Uniform();
    if (s + t > 1.0f)
    {
      s = 1.0f - s;
      t = 1.0f - t;
    }
    if (t + u > 1.0f)
    {
      const float tmp = u;
      u = 1.0f - s - t;
      t = 1.0f - tmp;
    }
    else if (s + t + u > 1.0f)
    {
      const float tmp = u;
      u = s + t + u - 1.0f;
      s = 1.0f - t - tmp;
    }
    return glm::vec4(1.0f - s - t - u, s, t, u);
  }

private:
  uint64_t SmallPoisson(double mean)
  {
    const double u = this->OpenUniform();
    double probability = std::exp(-mean);
    double cumulative = probability;
    uint64_t k = 0;
    while (u > cumulative && k < 1024)
    {
      ++k;
      probability *= mean / static_cast<double>(k);
      cumulative += probability;
    }
    return k;
  }

  uint64_t State;
};

// The attenuation as a piecewise linear function of the transfer-function coordinate, with the
// exact maximum over any interval (a sparse table of the samples' maxima).
class AttenuationTable
{
public:
  explicit AttenuationTable(const std::vector<double>& samples)
    : Last(static_cast<int>(samples.size()) - 1)
  {
    this->Levels.push_back(samples);
    for (int width = 1; 2 * width <= this->Last + 1; width *= 2)
    {
      const std::vector<double>& previous = this->Levels.back();
      std::vector<double> level(previous.size() - width);
      for (size_t i = 0; i < level.size(); ++i)
      {
        level[i] = std::max(previous[i], previous[i + width]);
      }
      this->Levels.push_back(std::move(level));
    }
  }

  double At(float coordinate) const
  {
    const double x = std::min(std::max(double(coordinate), 0.0), 1.0) * this->Last;
    const int i = std::min(static_cast<int>(x), this->Last - 1);
    const double w = x - i;
    return (1.0 - w) * this->Levels[0][i] + w * this->Levels[0][i + 1];
  }

  /// The largest value over [low, high]: at an end, or at a sample in between.
  double Max(float low, float high) const
  {
    double result = std::max(this->At(low), this->At(high));
    const int first = static_cast<int>(std::ceil(std::max(double(low), 0.0) * this->Last));
    const int last = static_cast<int>(std::floor(std::min(double(high), 1.0) * this->Last));
    if (first <= last)
    {
      int level = 0;
      while ((2 << level) <= last - first + 1)
      {
        ++level;
      }
      const std::vector<double>& maxima = this->Levels[level];
      result = std::max({ result, maxima[first], maxima[last - (1 << level) + 1] });
    }
    return result;
  }

private:
  int Last;
  std::vector<std::vector<double>> Levels; // Levels[k][i]: max of samples i .. i + 2^k - 1
};

unsigned short Quantize(float unit)
{
  return static_cast<unsigned short>(std::min(std::max(unit, 0.0f), 1.0f) * 65535.0f + 0.5f);
}
}

// The particles of one block of cells, with the set of each.
struct vtkPBVRParticleGenerator::Block
{
  std::vector<unsigned short> Particles;
  std::vector<unsigned short> Sets;
  vtkIdType Candidates = 0;

  void Emit(const glm::vec3& position, float scalar, uint32_t set)
  {
    this->Particles.insert(this->Particles.end(),
      { Quantize(position.x + 0.5f), Quantize(position.y + 0.5f), Quantize(position.z + 0.5f),
        Quantize(scalar) });
    this->Sets.push_back(static_cast<unsigned short>(set));
  }
};

namespace
{
using Block = vtkPBVRParticleGenerator::Block;

// One tetrahedron's corners and scalars.
struct Cell
{
  glm::vec3 Points[4];
  glm::vec4 Scalars;
  double Volume;
  float MinScalar;
  float MaxScalar;

  glm::vec3 At(const glm::vec4& w) const
  {
    return w.x * Points[0] + w.y * Points[1] + w.z * Points[2] + w.w * Points[3];
  }
};

class CellSampler
{
public:
  CellSampler(const vtkTetrahedralMesh* mesh, const AttenuationTable& table,
    const vtkPBVRParticleGenerator::Settings& settings, std::vector<Block>& blocks)
    : Points(mesh->GetPoints())
    , Scalars(mesh->GetScalars())
    , Tetrahedra(mesh->GetTetrahedra())
    , CellScalars(mesh->GetCellScalars())
    , Table(table)
    , Options(settings)
    , Blocks(blocks)
  {
  }

  Cell Load(vtkIdType t) const
  {
    Cell cell;
    const unsigned int* ids = &this->Tetrahedra[4 * t];
    for (int v = 0; v < 4; ++v)
    {
      const float* p = &this->Points[3 * size_t(ids[v])];
      cell.Points[v] = glm::vec3(p[0], p[1], p[2]);
      cell.Scalars[v] = this->CellScalars ? this->Scalars[t] : this->Scalars[ids[v]];
    }
    const glm::dvec3 a(cell.Points[1] - cell.Points[0]);
    const glm::dvec3 b(cell.Points[2] - cell.Points[0]);
    const glm::dvec3 c(cell.Points[3] - cell.Points[0]);
    cell.Volume = std::abs(glm::dot(a, glm::cross(b, c))) / 6.0;
    cell.MinScalar = std::min({ cell.Scalars.x, cell.Scalars.y, cell.Scalars.z, cell.Scalars.w });
    cell.MaxScalar = std::max({ cell.Scalars.x, cell.Scalars.y, cell.Scalars.z, cell.Scalars.w });
    return cell;
  }

  /// Expected candidates of the cell over all sets.
  double CandidateMean(const Cell& cell) const
  {
    const double tau = this->Options.SamplingMode == vtkPBVRVolumeMapper::CELL_AVERAGE
      ? this->Table.At(0.25f * (cell.Scalars.x + cell.Scalars.y + cell.Scalars.z + cell.Scalars.w))
      : this->Table.Max(cell.MinScalar, cell.MaxScalar);
    return this->Options.Sets * tau * cell.Volume / this->Options.Footprint;
  }

  void operator()(vtkIdType begin, vtkIdType end)
  {
    for (vtkIdType b = begin; b < end && !this->Exceeded.load(std::memory_order_relaxed); ++b)
    {
      this->SampleBlock(b);
    }
  }

  std::atomic<vtkIdType> Accepted{ 0 };
  std::atomic<bool> Exceeded{ false };

private:
  void SampleBlock(vtkIdType b)
  {
    Block& block = this->Blocks[b];
    const vtkIdType numberOfCells = vtkIdType(this->Tetrahedra.size() / 4);
    const vtkIdType end = std::min(numberOfCells, (b + 1) * TetrahedraPerBlock);
    const vtkIdType limit = static_cast<vtkIdType>(this->Options.MaximumParticles);
    for (vtkIdType t = b * TetrahedraPerBlock; t < end; ++t)
    {
      const Cell cell = this->Load(t);
      RandomStream random((uint64_t(this->Options.Seed) << 32) | uint64_t(t));
      if (this->Options.SamplingMode == vtkPBVRVolumeMapper::CELL_AVERAGE)
      {
        this->SampleAverage(cell, random, block);
      }
      else
      {
        this->SampleRejection(cell, random, block);
      }
      const vtkIdType local = vtkIdType(block.Sets.size());
      if (this->Accepted.load(std::memory_order_relaxed) + local > limit)
      {
        this->Exceeded = true;
        break;
      }
    }
    this->Accepted += vtkIdType(block.Sets.size());
  }

  void SampleRejection(const Cell& cell, RandomStream& random, Block& block) const
  {
    const double tauMax = this->Table.Max(cell.MinScalar, cell.MaxScalar);
    if (!(tauMax > 0.0))
    {
      return;
    }
    const uint64_t candidates = random.Poisson(this->CandidateMean(cell));
    block.Candidates += vtkIdType(candidates);
    const uint32_t sets = static_cast<uint32_t>(this->Options.Sets);
    for (uint64_t k = 0; k < candidates; ++k)
    {
      const glm::vec4 w = random.UniformInTetrahedron();
      const float scalar = glm::dot(w, cell.Scalars);
      if (random.Uniform() * tauMax < this->Table.At(scalar))
      {
        block.Emit(cell.At(w), scalar, random.Below(sets));
      }
    }
  }

  void SampleAverage(const Cell& cell, RandomStream& random, Block& block) const
  {
    const double mean = this->CandidateMean(cell) / this->Options.Sets;
    if (!(mean > 0.0))
    {
      return;
    }
    const double whole = std::floor(mean);
    const float fraction = static_cast<float>(mean - whole);
    for (int set = 0; set < this->Options.Sets; ++set)
    {
      const uint64_t count = uint64_t(whole) + (random.Uniform() < fraction ? 1 : 0);
      block.Candidates += vtkIdType(count);
      for (uint64_t k = 0; k < count; ++k)
      {
        const glm::vec4 w = random.UniformInTetrahedron();
        block.Emit(cell.At(w), glm::dot(w, cell.Scalars), static_cast<uint32_t>(set));
      }
    }
  }

  const std::vector<float>& Points;
  const std::vector<float>& Scalars;
  const std::vector<unsigned int>& Tetrahedra;
  const bool CellScalars;
  const AttenuationTable& Table;
  const vtkPBVRParticleGenerator::Settings& Options;
  std::vector<Block>& Blocks;
};

// Why the settings or the attenuation cannot generate particles, or nothing.
std::string CheckSettings(
  const std::vector<double>& attenuation, const vtkPBVRParticleGenerator::Settings& settings)
{
  if (!(settings.Footprint > 0.0) || !std::isfinite(settings.Footprint))
  {
    return "The particle footprint must be a positive, finite area.";
  }
  if (settings.Sets < 1 || settings.Sets > 65536)
  {
    return "The number of particle sets must be 1 to 65536.";
  }
  if (attenuation.size() < 2)
  {
    return "The attenuation needs at least two samples.";
  }
  return std::string();
}
}

vtkStandardNewMacro(vtkPBVRParticleGenerator);

vtkPBVRParticleGenerator::vtkPBVRParticleGenerator() = default;

vtkPBVRParticleGenerator::~vtkPBVRParticleGenerator() = default;

bool vtkPBVRParticleGenerator::Fail(const std::string& reason)
{
  this->LastError = reason;
  this->ReleaseParticles();
  this->SetOffsets.assign(1, 0);
  this->NumberOfParticles = 0;
  return false;
}

void vtkPBVRParticleGenerator::ReleaseParticles()
{
  std::vector<unsigned short>().swap(this->Particles);
}

bool vtkPBVRParticleGenerator::Generate(
  const vtkTetrahedralMesh* mesh, const std::vector<double>& attenuation, const Settings& settings)
{
  const auto start = std::chrono::steady_clock::now();
  this->LastError.clear();
  this->NumberOfCandidates = 0;
  this->GenerationTime = 0.0;
  const std::string invalid = CheckSettings(attenuation, settings);
  if (!invalid.empty())
  {
    return this->Fail(invalid);
  }
  const AttenuationTable table(attenuation);
  const vtkIdType numberOfCells = mesh->GetNumberOfTetrahedra();
  const vtkIdType numberOfBlocks = (numberOfCells + TetrahedraPerBlock - 1) / TetrahedraPerBlock;
  std::vector<Block> blocks(numberOfBlocks);
  CellSampler sampler(mesh, table, settings, blocks);

  // The candidates to try are known in advance; the particles kept are not, for rejection.
  double candidates = 0.0;
  for (vtkIdType t = 0; t < numberOfCells; ++t)
  {
    candidates += sampler.CandidateMean(sampler.Load(t));
  }
  const double limit = static_cast<double>(settings.MaximumParticles);
  if (candidates > MaximumCandidatesPerParticle * limit + 1.0e6 ||
    (settings.SamplingMode == vtkPBVRVolumeMapper::CELL_AVERAGE &&
      candidates > limit * 1.01 + 100.0))
  {
    std::ostringstream reason;
    reason << "The particles would not fit: about " << std::llround(candidates)
           << (settings.SamplingMode == vtkPBVRVolumeMapper::CELL_AVERAGE ? " particles"
                                                                          : " candidate particles")
           << " for " << settings.Sets << " sets, and the memory holds at most "
           << settings.MaximumParticles << ".";
    return this->Fail(reason.str());
  }

  vtkSMPTools::For(0, numberOfBlocks, 1, sampler);
  // Each block checks against the blocks finished before it: blocks on other threads may
  // pass the limit together.
  if (sampler.Exceeded || static_cast<size_t>(sampler.Accepted.load()) > settings.MaximumParticles)
  {
    std::ostringstream reason;
    reason << "The particles would not fit: more than " << settings.MaximumParticles
           << " particles for " << settings.Sets << " sets (about " << std::llround(candidates)
           << " candidates).";
    return this->Fail(reason.str());
  }

  this->OrderBySet(blocks, settings.Sets);
  this->GenerationTime =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return true;
}

void vtkPBVRParticleGenerator::OrderBySet(std::vector<Block>& blocks, int sets)
{
  // A counting sort, which keeps the cell order within each set.
  this->SetOffsets.assign(sets + 1, 0);
  for (const Block& block : blocks)
  {
    for (unsigned short set : block.Sets)
    {
      ++this->SetOffsets[set + 1];
    }
    this->NumberOfCandidates += block.Candidates;
  }
  for (int set = 0; set < sets; ++set)
  {
    this->SetOffsets[set + 1] += this->SetOffsets[set];
  }
  this->NumberOfParticles = this->SetOffsets.back();
  this->Particles.resize(ComponentsPerParticle * size_t(this->NumberOfParticles));
  std::vector<vtkIdType> cursor(this->SetOffsets.begin(), this->SetOffsets.end() - 1);
  for (Block& block : blocks)
  {
    for (size_t i = 0; i < block.Sets.size(); ++i)
    {
      const size_t target = ComponentsPerParticle * size_t(cursor[block.Sets[i]]++);
      std::copy_n(&block.Particles[ComponentsPerParticle * i], ComponentsPerParticle,
        &this->Particles[target]);
    }
    block = Block(); // frees the block's memory as the particles move
  }
}

void vtkPBVRParticleGenerator::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfParticles: " << this->NumberOfParticles << "\n";
  os << indent << "NumberOfSets: " << this->GetNumberOfSets() << "\n";
  os << indent << "NumberOfCandidates: " << this->NumberOfCandidates << "\n";
  os << indent << "GenerationTime: " << this->GenerationTime << "\n";
}
