#include "vtkSPTParallelReduction.h"

#include "vtkCommunicator.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLLoader.h"
#include "vtkTextureObject.h"

#include "vtkPreIntegrationTable.h"
#include "vtkSPTDepthKeyBuffer.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>

namespace
{
// The fields of a rank's record, before its settings.
enum Field
{
  Ready,
  EmptyImage,
  HasCells,
  Components,
  CellScalars,
  GlobalIds,
  OpaqueScene,
  Bounds,
  ScalarRange = Bounds + 6,
  MaxEdgeLength = ScalarRange + 2,
  Tetrahedra,
  FirstSetting
};

// The array names are exchanged cut to this length.
constexpr int NameLength = 128;

std::vector<double> Record(
  const vtkSPTParallelReduction::Settings& settings, const vtkSPTParallelReduction::Piece& piece)
{
  std::vector<double> record(FirstSetting + settings.size());
  record[Ready] = piece.Ready;
  record[EmptyImage] = piece.EmptyImage;
  record[HasCells] = piece.HasCells;
  record[Components] = piece.Components;
  record[CellScalars] = piece.CellScalars;
  record[GlobalIds] = piece.GlobalIds;
  record[OpaqueScene] = piece.OpaqueScene;
  std::copy(piece.Bounds, piece.Bounds + 6, &record[Bounds]);
  std::copy(piece.ScalarRange, piece.ScalarRange + 2, &record[ScalarRange]);
  record[MaxEdgeLength] = piece.MaxEdgeLength;
  record[Tetrahedra] = piece.Tetrahedra;
  for (size_t i = 0; i < settings.size(); ++i)
  {
    record[FirstSetting + i] = settings[i].second;
  }
  return record;
}

// The union of the pieces of the agreed records.
vtkSPTParallelReduction::Agreement Union(const std::vector<double>& records, size_t size, int ranks)
{
  vtkSPTParallelReduction::Agreement agreement;
  bool first = true;
  agreement.GlobalIds = true;
  for (int r = 0; r < ranks; ++r)
  {
    const double* record = &records[r * size];
    agreement.OpaqueScene = agreement.OpaqueScene || record[OpaqueScene] != 0.0;
    if (record[HasCells] == 0.0)
    {
      continue;
    }
    agreement.AnyCells = true;
    agreement.Tetrahedra += record[Tetrahedra];
    agreement.GlobalIds = agreement.GlobalIds && record[GlobalIds] != 0.0;
    agreement.MaxEdgeLength = std::max(agreement.MaxEdgeLength, record[MaxEdgeLength]);
    for (int i = 0; i < 8; ++i)
    {
      const double value = record[Bounds + i]; // the bounds, then the range: min, max pairs
      double& target = i < 6 ? agreement.Bounds[i] : agreement.ScalarRange[i - 6];
      target = first ? value : (i % 2 == 0 ? std::min(target, value) : std::max(target, value));
    }
    first = false;
  }
  agreement.GlobalIds = agreement.GlobalIds && agreement.AnyCells;
  return agreement;
}

std::vector<float> ReadTexture(vtkTextureObject* texture, unsigned int format, int components)
{
  std::vector<float> values(
    size_t(texture->GetWidth()) * size_t(texture->GetHeight()) * size_t(components));
  texture->Activate();
  glGetTexImage(texture->GetTarget(), 0, format, GL_FLOAT, values.data());
  texture->Deactivate();
  return values;
}

void WriteTexture(vtkTextureObject* texture, unsigned int format, const std::vector<float>& values)
{
  texture->Activate();
  glTexSubImage2D(texture->GetTarget(), 0, 0, 0, static_cast<GLsizei>(texture->GetWidth()),
    static_cast<GLsizei>(texture->GetHeight()), format, GL_FLOAT, values.data());
  texture->Deactivate();
}
}

vtkStandardNewMacro(vtkSPTParallelReduction);

vtkSPTParallelReduction::vtkSPTParallelReduction() = default;

vtkSPTParallelReduction::~vtkSPTParallelReduction()
{
  this->SetController(nullptr);
}

void vtkSPTParallelReduction::SetController(vtkMultiProcessController* controller)
{
  if (controller != this->Controller)
  {
    vtkMultiProcessController* old = this->Controller;
    this->Controller = controller;
    if (controller)
    {
      controller->Register(this);
    }
    if (old)
    {
      old->UnRegister(this);
    }
    this->Modified();
  }
}

bool vtkSPTParallelReduction::Agree(
  const Settings& settings, const Piece& piece, Agreement& agreement, std::string& error)
{
  vtkMultiProcessController* controller = this->Controller;
  const int ranks = controller->GetNumberOfProcesses();
  const std::vector<double> record = Record(settings, piece);
  std::vector<double> records(record.size() * ranks);
  std::vector<char> name(NameLength, '\0');
  std::strncpy(name.data(), piece.ArrayName.c_str(), NameLength - 1);
  std::vector<char> names(name.size() * ranks);
  if (!controller->AllGather(record.data(), records.data(), vtkIdType(record.size())) ||
    !controller->AllGather(name.data(), names.data(), vtkIdType(name.size())))
  {
    error = "The ranks could not exchange their settings.";
    return false;
  }
  this->Bytes += (record.size() * sizeof(double) + name.size()) * size_t(ranks);
  error = Compare(settings, records, names, ranks);
  if (!error.empty() || records[EmptyImage] != 0.0)
  {
    return false;
  }
  agreement = Union(records, record.size(), ranks);
  return true;
}

std::string vtkSPTParallelReduction::Compare(const Settings& settings,
  const std::vector<double>& records, const std::vector<char>& names, int ranks)
{
  const size_t size = FirstSetting + settings.size();
  std::ostringstream reason;
  // The settings first: a rank that cannot prepare may do so because its settings differ
  // (an image of another size).
  for (int r = 1; r < ranks; ++r)
  {
    const double* record = &records[r * size];
    for (size_t i = 0; i < settings.size(); ++i)
    {
      if (record[FirstSetting + i] != records[FirstSetting + i])
      {
        reason << "Rank " << r << " has " << settings[i].first << " " << record[FirstSetting + i]
               << " but rank 0 has " << records[FirstSetting + i];
        return reason.str();
      }
    }
  }
  int reference = -1; // the first rank with cells: the others' scalars must be its
  for (int r = 0; r < ranks; ++r)
  {
    const double* record = &records[r * size];
    if (record[EmptyImage] != 0.0)
    {
      return std::string(); // the same image size on every rank: none has pixels to draw
    }
    if (record[Ready] == 0.0)
    {
      reason << "Rank " << r << " could not prepare its piece (see its own error)";
      return reason.str();
    }
    if (record[HasCells] == 0.0)
    {
      continue;
    }
    if (reference < 0)
    {
      reference = r;
      continue;
    }
    const double* first = &records[reference * size];
    const std::string name(&names[r * NameLength]);
    const std::string firstName(&names[reference * NameLength]);
    if (name != firstName || record[Components] != first[Components] ||
      record[CellScalars] != first[CellScalars])
    {
      reason << "Rank " << r << " renders the " << (record[CellScalars] ? "cell" : "point")
             << " array '" << name << "' of " << record[Components] << " component(s), but rank "
             << reference << " renders the " << (first[CellScalars] ? "cell" : "point")
             << " array '" << firstName << "' of " << first[Components] << " component(s)";
      return reason.str();
    }
  }
  return std::string();
}

bool vtkSPTParallelReduction::CompositeScene(
  vtkTextureObject* depth, std::vector<unsigned char>& color)
{
  // One key per pixel: the depth's bits above the rank. Depths are not negative, so their
  // bits order as their values do, and the minimum key names the nearest rank.
  std::vector<float> local = ReadTexture(depth, GL_DEPTH_COMPONENT, 1);
  const int rank = this->Controller->GetLocalProcessId();
  std::vector<unsigned long long> keys(local.size());
  for (size_t i = 0; i < local.size(); ++i)
  {
    const float value = local[i] > 0.0f ? local[i] : 0.0f;
    std::uint32_t bits = 0;
    std::memcpy(&bits, &value, sizeof(bits));
    keys[i] = (static_cast<unsigned long long>(bits) << 32) | static_cast<unsigned int>(rank);
  }
  std::vector<unsigned long long> nearest(keys.size());
  if (!this->Controller->AllReduce(
        keys.data(), nearest.data(), vtkIdType(keys.size()), vtkCommunicator::MIN_OP))
  {
    return false;
  }
  this->Bytes += keys.size() * sizeof(unsigned long long);
  for (size_t i = 0; i < local.size(); ++i)
  {
    const std::uint32_t bits = static_cast<std::uint32_t>(nearest[i] >> 32);
    std::memcpy(&local[i], &bits, sizeof(bits));
  }
  WriteTexture(depth, GL_DEPTH_COMPONENT, local);
  // Each pixel's color comes from its nearest rank alone: a sum of one term.
  color.resize(4 * keys.size(), 0);
  for (size_t i = 0; i < keys.size(); ++i)
  {
    if (nearest[i] != keys[i])
    {
      std::fill_n(color.begin() + 4 * i, 4, static_cast<unsigned char>(0));
    }
  }
  std::vector<unsigned char> composited(color.size());
  if (!this->Controller->Reduce(
        color.data(), composited.data(), vtkIdType(color.size()), vtkCommunicator::SUM_OP, 0))
  {
    return false;
  }
  this->Bytes += color.size();
  color.swap(composited);
  return true;
}

bool vtkSPTParallelReduction::ReduceWords(vtkSPTDepthKeyBuffer* keys, ReadWords read,
  WriteWords write, size_t missed, unsigned int identity, int operation)
{
  const std::vector<unsigned int> local =
    keys ? (keys->*read)() : std::vector<unsigned int>(missed, identity);
  std::vector<unsigned int> global(local.size());
  this->Bytes += local.size() * sizeof(unsigned int);
  const bool reduced = this->Controller->AllReduce(
                         local.data(), global.data(), vtkIdType(local.size()), operation) != 0;
  if (reduced && keys)
  {
    (keys->*write)(global);
  }
  return reduced;
}

bool vtkSPTParallelReduction::ReduceKeys(vtkSPTDepthKeyBuffer* keys, size_t missed)
{
  return this->ReduceWords(keys, &vtkSPTDepthKeyBuffer::Read, &vtkSPTDepthKeyBuffer::Write, missed,
    0xFFFFFFFFu, vtkCommunicator::MIN_OP);
}

bool vtkSPTParallelReduction::ReduceSlabs(vtkSPTDepthKeyBuffer* keys, size_t missed)
{
  return this->ReduceWords(keys, &vtkSPTDepthKeyBuffer::ReadSlabs,
    &vtkSPTDepthKeyBuffer::WriteSlabs, missed, 0u, vtkCommunicator::SUM_OP);
}

bool vtkSPTParallelReduction::AllSucceeded(bool ok)
{
  const int local = ok ? 1 : 0;
  int global = 0;
  return this->Controller->AllReduce(&local, &global, 1, vtkCommunicator::MIN_OP) && global == 1;
}

bool vtkSPTParallelReduction::ReduceSums(
  const std::vector<vtkTextureObject*>& textures, size_t texels)
{
  const bool root = this->Controller->GetLocalProcessId() == 0;
  for (vtkTextureObject* texture : textures)
  {
    const bool allocated = texture->GetHandle() != 0 &&
      size_t(texture->GetWidth()) * size_t(texture->GetHeight()) == texels;
    const std::vector<float> local =
      allocated ? ReadTexture(texture, GL_RGBA, 4) : std::vector<float>(4 * texels, 0.0f);
    std::vector<float> global(local.size());
    if (!this->Controller->Reduce(
          local.data(), global.data(), vtkIdType(local.size()), vtkCommunicator::SUM_OP, 0))
    {
      return false;
    }
    this->Bytes += local.size() * sizeof(float);
    if (allocated)
    {
      WriteTexture(texture, GL_RGBA, root ? global : std::vector<float>(local.size(), 0.0f));
    }
  }
  return true;
}

bool vtkSPTParallelReduction::ShareTable(
  vtkPreIntegrationTable* table, bool prepared, bool pending, std::string& error)
{
  // One record per rank: prepared, pending, and the samples' signature in two 32-bit halves
  // (exact in doubles).
  const int ranks = this->Controller->GetNumberOfProcesses();
  const std::uint64_t signature = prepared ? table->GetSignature() : 0;
  const double local[4] = { prepared ? 1.0 : 0.0, pending ? 1.0 : 0.0, double(signature >> 32),
    double(signature & 0xffffffffull) };
  std::vector<double> records(4 * size_t(ranks));
  this->Bytes += sizeof(local);
  if (!this->Controller->AllGather(local, records.data(), 4))
  {
    error = "The ranks could not exchange their transfer functions";
    return false;
  }
  bool anyPending = false;
  for (int r = 0; r < ranks; ++r)
  {
    const double* record = &records[4 * size_t(r)];
    if (record[0] == 0.0)
    {
      return true;
    }
    if (record[2] != records[2] || record[3] != records[3])
    {
      std::ostringstream message;
      message << "Rank " << r
              << "'s transfer function differs from rank 0's over the shared scalar range "
                 "(every rank needs the same color and opacity functions)";
      error = message.str();
      return false;
    }
    anyPending = anyPending || record[1] != 0.0;
  }
  if (!anyPending)
  {
    return true;
  }
  // Equal shares of the pairs (the last ranks' padded), gathered in rank order: the pairs in
  // their order.
  const vtkIdType pairs = table->GetNumberOfScalarPairs();
  const vtkIdType share = (pairs + ranks - 1) / ranks;
  const vtkIdType first = std::min(pairs, this->Controller->GetLocalProcessId() * share);
  const vtkIdType last = std::min(pairs, first + share);
  const size_t values = size_t(share) * size_t(table->GetValuesPerScalarPair());
  std::vector<float> mine(values, 0.0f);
  table->IntegrateScalarPairs(first, last, mine.data());
  std::vector<float> all(values * size_t(ranks));
  this->Bytes += values * sizeof(float);
  if (!this->Controller->AllGather(mine.data(), all.data(), vtkIdType(values)))
  {
    error = "The ranks could not exchange their parts of the pre-integration table";
    return false;
  }
  table->SetIntegrated(all.data());
  return true;
}

bool vtkSPTParallelReduction::AllMinimum(int* values, int count)
{
  const std::vector<int> local(values, values + count);
  this->Bytes += local.size() * sizeof(int);
  return this->Controller->AllReduce(
           local.data(), values, vtkIdType(count), vtkCommunicator::MIN_OP) != 0;
}

bool vtkSPTParallelReduction::ShareTileNoise(bool ok, std::vector<double>& values)
{
  // One minimum: of the success flags, and of the count of rank 0's values against the
  // others' largest; then rank 0's values.
  const bool root = this->Controller->GetLocalProcessId() == 0;
  const double local[2] = { ok ? 1.0 : 0.0,
    root ? double(values.size()) : std::numeric_limits<double>::infinity() };
  double global[2] = { 0.0, 0.0 };
  this->Bytes += sizeof(local);
  if (!this->Controller->AllReduce(local, global, 2, vtkCommunicator::MIN_OP))
  {
    return false;
  }
  values.resize(static_cast<size_t>(global[1]), -1.0);
  this->Bytes += static_cast<vtkIdType>(values.size() * sizeof(double));
  if (!values.empty() &&
    !this->Controller->Broadcast(values.data(), static_cast<vtkIdType>(values.size()), 0))
  {
    return false;
  }
  return global[0] == 1.0;
}

void vtkSPTParallelReduction::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Controller: " << this->Controller << "\n";
  os << indent << "Bytes: " << this->Bytes << "\n";
}
