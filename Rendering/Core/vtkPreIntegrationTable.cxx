#include "vtkPreIntegrationTable.h"

#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkSMPTools.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <sstream>

namespace
{
// Transfer-function samples per table cell, and quadrature steps per table cell that a
// segment's scalar sweeps through. Steps hold color and attenuation constant, which is exact
// for homogeneous segments; the error elsewhere is second order in the step.
constexpr int TransferFunctionSamplesPerCell = 8;
constexpr int StepsPerCell = 2;
// The largest table integrated: 1 GiB of RGBA floats (1024 x 1024 scalar pairs of 64 lengths),
// held once on the host and once as a texture, and at most 100 times the integration work of
// the default table (128 x 128 x 64, about a quarter of a second on two cores).
constexpr double MaxTableBytes = double(1 << 30);
constexpr double MaxRelativeWork = 100.0;

// The integration's work: for every scalar pair, a quadrature step per table cell its scalars
// sweep (a third of the axis on average) and every length.
double IntegrationWork(int scalarResolution, int lengthResolution)
{
  const double n = scalarResolution;
  return n * n * (1.0 + StepsPerCell * n / 3.0) * lengthResolution;
}
}

vtkStandardNewMacro(vtkPreIntegrationTable);

vtkPreIntegrationTable::vtkPreIntegrationTable() = default;

vtkPreIntegrationTable::~vtkPreIntegrationTable() = default;

double vtkPreIntegrationTable::GetScalar(int i) const
{
  const double t = this->ScalarResolution > 1 ? double(i) / (this->ScalarResolution - 1) : 0.0;
  return this->ScalarRange[0] + t * (this->ScalarRange[1] - this->ScalarRange[0]);
}

double vtkPreIntegrationTable::GetLength(int k) const
{
  // The length axis is sqrt(length / MaxLength), so short segments get most of the samples.
  const double t = this->LengthResolution > 1 ? double(k) / (this->LengthResolution - 1) : 0.0;
  return this->MaxLength * t * t;
}

bool vtkPreIntegrationTable::Update(vtkVolumeProperty* property, const double scalarRange[2],
  double maxLength, int scalarResolution, int lengthResolution)
{
  bool pending = false;
  if (!this->Prepare(property, scalarRange, maxLength, scalarResolution, lengthResolution, pending))
  {
    return false;
  }
  if (pending)
  {
    // In one process each pair's lengths go straight to the texture's layout: no copy.
    const vtkIdType count = this->GetNumberOfScalarPairs();
    std::vector<float> table(size_t(count) * this->LengthResolution * 4);
    this->IntegrateScalarPairs(0, count, table.data(), 4, 4 * count);
    this->Commit(table);
  }
  return true;
}

bool vtkPreIntegrationTable::CheckSize(int scalarResolution, int lengthResolution)
{
  const int scalars = std::max(2, scalarResolution);
  const int lengths = std::max(2, lengthResolution);
  const double bytes = 16.0 * scalars * scalars * lengths;
  const double work = IntegrationWork(scalars, lengths) / IntegrationWork(128, 64);
  if (bytes > MaxTableBytes || work > MaxRelativeWork)
  {
    std::ostringstream message;
    message << "A pre-integration table of " << scalars << " x " << scalars << " x " << lengths
            << " samples would take " << bytes / (1 << 20) << " MiB (at most "
            << MaxTableBytes / (1 << 20) << ") and " << std::ceil(work)
            << " times the integration time of the default 128 x 128 x 64 (at most "
            << MaxRelativeWork
            << "): lower PreIntegrationScalarResolution or PreIntegrationThicknessResolution.";
    this->LastError = message.str();
    return false;
  }
  return true;
}

bool vtkPreIntegrationTable::Prepare(vtkVolumeProperty* property, const double scalarRange[2],
  double maxLength, int scalarResolution, int lengthResolution, bool& pending)
{
  this->LastError.clear();
  pending = false;
  if (!property)
  {
    this->LastError = "No volume property to pre-integrate.";
    return false;
  }
  if (!this->CheckSize(scalarResolution, lengthResolution))
  {
    return false;
  }
  const bool unchanged = !this->Pending && property == this->LastProperty &&
    this->CheckTime > property->GetMTime() &&
    this->HasAxes(scalarRange, maxLength, scalarResolution, lengthResolution);
  if (unchanged)
  {
    return true;
  }
  // Sampling the functions is cheap; integrating the table is not. A property can be touched
  // without a change of its functions (VTK creates default functions on first access), so
  // the table is integrated again only when the samples or the axes differ.
  const int resolution = std::max(2, scalarResolution);
  const int samples = TransferFunctionSamplesPerCell * (resolution - 1) + 1;
  this->LastProperty = nullptr;
  if (!this->Samples.Update(property, scalarRange, samples))
  {
    this->LastError = this->Samples.GetLastError();
    return false;
  }
  const vtkMTimeType sampled =
    std::max(this->Samples.GetColorTime(), this->Samples.GetAttenuationTime());
  const bool sameAxes =
    this->HasAxes(scalarRange, maxLength, resolution, std::max(2, lengthResolution));
  if (!this->Pending && sameAxes && !this->Table.empty() && sampled <= this->IntegratedSamples)
  {
    this->LastProperty = property;
    this->CheckTime.Modified();
    return true;
  }
  this->ScalarRange[0] = scalarRange[0];
  this->ScalarRange[1] = scalarRange[1];
  this->MaxLength = maxLength;
  this->ScalarResolution = resolution;
  this->LengthResolution = std::max(2, lengthResolution);
  this->Pending = true;
  this->PendingProperty = property;
  this->PendingSamples = sampled;
  pending = true;
  return true;
}

vtkIdType vtkPreIntegrationTable::GetNumberOfScalarPairs() const
{
  return vtkIdType(this->ScalarResolution) * this->ScalarResolution;
}

void vtkPreIntegrationTable::IntegrateScalarPairs(vtkIdType first, vtkIdType last, float* out) const
{
  this->IntegrateScalarPairs(first, last, out, this->GetValuesPerScalarPair(), 4);
}

void vtkPreIntegrationTable::IntegrateScalarPairs(
  vtkIdType first, vtkIdType last, float* out, vtkIdType pairStride, vtkIdType lengthStride) const
{
  vtkSMPTools::For(first, last,
    [=](vtkIdType begin, vtkIdType end)
    {
      const int n = this->ScalarResolution;
      for (vtkIdType pair = begin; pair < end; ++pair)
      {
        this->IntegrateScalarPair(
          int(pair % n), int(pair / n), out + (pair - first) * pairStride, lengthStride);
      }
    });
}

void vtkPreIntegrationTable::SetIntegrated(const float* pairs)
{
  // From each pair's lengths to the texture's layout: front scalar fastest, then back scalar,
  // then length.
  const vtkIdType count = this->GetNumberOfScalarPairs();
  const int lengths = this->LengthResolution;
  std::vector<float> table(size_t(count) * lengths * 4);
  for (vtkIdType pair = 0; pair < count; ++pair)
  {
    const float* from = pairs + pair * 4 * lengths;
    for (int k = 0; k < lengths; ++k)
    {
      std::copy(from + 4 * k, from + 4 * k + 4, table.begin() + 4 * (k * count + pair));
    }
  }
  this->Commit(table);
}

void vtkPreIntegrationTable::Commit(std::vector<float>& table)
{
  ++this->IntegrationCount;
  this->Pending = false;
  this->IntegratedSamples = this->PendingSamples;
  this->LastProperty = this->PendingProperty;
  this->CheckTime.Modified();
  // A property can be touched without a change of its functions (VTK creates default
  // functions on first access): the build time, which callers cache by, moves only when the
  // contents do.
  if (table != this->Table)
  {
    this->Table.swap(table);
    this->BuildTime.Modified();
    this->Modified();
  }
}

std::uint64_t vtkPreIntegrationTable::GetSignature() const
{
  // FNV-1a over the bytes of the samples and of the axes.
  std::uint64_t hash = 14695981039346656037ull;
  auto add = [&hash](const void* data, size_t bytes)
  {
    const unsigned char* byte = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < bytes; ++i)
    {
      hash = (hash ^ byte[i]) * 1099511628211ull;
    }
  };
  const std::vector<double>& color = this->Samples.GetColor();
  const std::vector<double>& attenuation = this->Samples.GetAttenuation();
  add(color.data(), color.size() * sizeof(double));
  add(attenuation.data(), attenuation.size() * sizeof(double));
  add(this->ScalarRange, sizeof(this->ScalarRange));
  add(&this->MaxLength, sizeof(this->MaxLength));
  add(&this->ScalarResolution, sizeof(this->ScalarResolution));
  add(&this->LengthResolution, sizeof(this->LengthResolution));
  return hash;
}

bool vtkPreIntegrationTable::HasAxes(
  const double scalarRange[2], double maxLength, int scalarResolution, int lengthResolution) const
{
  // The longest edge comes from float coordinates: normalized in another frame (a parallel
  // render's pieces take the shared frame after their first render), the same edge measures a
  // few units in the seventh digit apart, far below a step of the length axis.
  const double lengthTolerance = 1e-6 * std::max(maxLength, this->MaxLength);
  return scalarRange[0] == this->ScalarRange[0] && scalarRange[1] == this->ScalarRange[1] &&
    std::abs(maxLength - this->MaxLength) <= lengthTolerance &&
    scalarResolution == this->ScalarResolution && lengthResolution == this->LengthResolution;
}

void vtkPreIntegrationTable::IntegrateScalarPair(
  int front, int back, float* out, vtkIdType stride) const
{
  // The color and attenuation at the middle of each step; the same for every length.
  const int steps = 1 + StepsPerCell * std::abs(back - front);
  std::vector<double> tau(steps), color(3 * steps);
  this->SampleSteps(front, back, tau, color);
  const int lengths = this->LengthResolution;
  std::vector<LengthPair> pairs((lengths + 1) / 2);
  const double intervals = lengths > 1 ? double(lengths - 1) : 1.0;
  const double perUnitDepth = this->MaxLength / (intervals * intervals * steps);
  IntegrateLengths(tau, color, perUnitDepth, lengths, pairs);
  for (int k = 0; k < lengths; ++k)
  {
    const LengthPair& p = pairs[k / 2];
    float* entry = out + vtkIdType(k) * stride;
    entry[0] = float(p.Red[k % 2]);
    entry[1] = float(p.Green[k % 2]);
    entry[2] = float(p.Blue[k % 2]);
    entry[3] = float(1.0 - p.Transmittance[k % 2]);
  }
}

void vtkPreIntegrationTable::SampleSteps(
  int front, int back, std::vector<double>& tau, std::vector<double>& color) const
{
  const int steps = static_cast<int>(tau.size());
  const double fineFront = double(front) * TransferFunctionSamplesPerCell;
  const double fineBack = double(back) * TransferFunctionSamplesPerCell;
  const std::vector<double>& attenuation = this->Samples.GetAttenuation();
  const std::vector<double>& colors = this->Samples.GetColor();
  for (int m = 0; m < steps; ++m)
  {
    const double x = fineFront + (fineBack - fineFront) * (m + 0.5) / steps;
    const int i0 = std::min(int(x), this->Samples.GetNumberOfSamples() - 2);
    const double w = x - i0;
    tau[m] = (1.0 - w) * attenuation[i0] + w * attenuation[i0 + 1];
    for (int c = 0; c < 3; ++c)
    {
      color[3 * m + c] = (1.0 - w) * colors[3 * i0 + c] + w * colors[3 * i0 + 3 + c];
    }
  }
}

void vtkPreIntegrationTable::IntegrateLengths(const std::vector<double>& tau,
  const std::vector<double>& color, double perUnitDepth, int lengths,
  std::vector<LengthPair>& pairs)
{
  // Front to back, step by step, every length at once. Step m of length k has the optical
  // depth tau_m * (k / (L - 1))^2 * MaxLength / steps = c_m k^2, so its transmittance is
  // a^(k^2) with a = exp(-c_m): each length's factor follows from the one two lengths before
  // by products, and each complement by sums of positive terms, exact to rounding where c_m is
  // tiny (no 1 - x of an x near 1). One exponential and one expm1 per step instead of one per
  // step and length.
  // A longer segment keeps less light at every step: the lengths whose light is not spent
  // (transmittance above 1e-7) are the first `lit`, and only they take more steps, as a ray
  // stops; the pairs of lengths below take the one after an odd `lit` along (a length more, or
  // the spare one of the last pair), which only makes it more exact.
  const int steps = static_cast<int>(tau.size());
  int lit = lengths;
  for (int m = 0; m < steps && lit > 0; ++m)
  {
    // From length k to k + 2 the factor grows by a^(4k + 4), which grows by a^8. The powers
    // of a are products, their complements 1 - a^2n = (1 - a^n)(1 + a^n).
    const double a = std::exp(-tau[m] * perUnitDepth);
    const double a1 = -std::expm1(-tau[m] * perUnitDepth); // 1 - a
    const double a2 = a * a, a4 = a2 * a2, a8 = a4 * a4;
    const double c2 = a1 * (1.0 + a), c4 = c2 * (1.0 + a2), c8 = c4 * (1.0 + a4);
    double factor[2] = { 1.0, a };         // a^(k^2) for the chain's length k
    double complement[2] = { 0.0, a1 };    // 1 - a^(k^2)
    double next[2] = { a4, a8 };           // a^(4k + 4): from k to k + 2
    double nextComplement[2] = { c4, c8 }; // 1 - a^(4k + 4)
    const double r = color[3 * m];
    const double g = color[3 * m + 1];
    const double b = color[3 * m + 2];
    const int litPairs = (lit + 1) / 2;
    for (int pair = 0; pair < litPairs; ++pair)
    {
      LengthPair& p = pairs[pair];
      for (int chain = 0; chain < 2; ++chain)
      {
        const double weight = p.Transmittance[chain] * complement[chain];
        p.Red[chain] += weight * r;
        p.Green[chain] += weight * g;
        p.Blue[chain] += weight * b;
        p.Transmittance[chain] *= factor[chain];
        complement[chain] += factor[chain] * nextComplement[chain];
        factor[chain] *= next[chain];
        nextComplement[chain] += next[chain] * c8;
        next[chain] *= a8;
      }
    }
    while (lit > 0 && pairs[(lit - 1) / 2].Transmittance[(lit - 1) % 2] <= 1.0e-7)
    {
      --lit;
    }
  }
}

vtkTextureObject* vtkPreIntegrationTable::GetTexture(vtkOpenGLRenderWindow* renWin)
{
  if (this->Table.empty())
  {
    return nullptr;
  }
  if (!this->Texture->GetHandle() || this->Texture->GetContext() != renWin ||
    this->UploadTime < this->BuildTime)
  {
    this->Texture->SetContext(renWin);
    this->Texture->SetWrapS(vtkTextureObject::ClampToEdge);
    this->Texture->SetWrapT(vtkTextureObject::ClampToEdge);
    this->Texture->SetWrapR(vtkTextureObject::ClampToEdge);
    this->Texture->SetMinificationFilter(vtkTextureObject::Linear);
    this->Texture->SetMagnificationFilter(vtkTextureObject::Linear);
    const unsigned int ns = static_cast<unsigned int>(this->ScalarResolution);
    if (!this->Texture->Create3DFromRaw(ns, ns, static_cast<unsigned int>(this->LengthResolution),
          4, VTK_FLOAT, const_cast<float*>(this->Table.data())))
    {
      vtkErrorMacro("Could not upload the " << ns << "x" << ns << "x" << this->LengthResolution
                                            << " pre-integration table as a 3D texture.");
      this->Texture->ReleaseGraphicsResources(renWin);
      return nullptr;
    }
    this->UploadTime.Modified();
  }
  return this->Texture;
}

void vtkPreIntegrationTable::SetUniforms(
  vtkShaderProgram* program, vtkTextureObject* texture, double maxThickness) const
{
  const int scalarSamples = this->ScalarResolution;
  const int thicknessSamples = this->LengthResolution;
  const float texelScale[3] = { float(scalarSamples - 1) / scalarSamples,
    float(scalarSamples - 1) / scalarSamples, float(thicknessSamples - 1) / thicknessSamples };
  const float texelOffset[3] = { 0.5f / scalarSamples, 0.5f / scalarSamples,
    0.5f / thicknessSamples };
  program->SetUniformi("preIntegrationTable", texture->GetTextureUnit());
  program->SetUniform3f("tableTexelScale", texelScale);
  program->SetUniform3f("tableTexelOffset", texelOffset);
  program->SetUniformf("thicknessToTable", maxThickness > 0.0 ? float(1.0 / maxThickness) : 0.0f);
}

size_t vtkPreIntegrationTable::GetGPUMemorySize() const
{
  return this->Texture->GetHandle() ? this->Table.size() * sizeof(float) : 0;
}

void vtkPreIntegrationTable::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Texture->ReleaseGraphicsResources(window);
}

void vtkPreIntegrationTable::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ScalarResolution: " << this->ScalarResolution << "\n";
  os << indent << "LengthResolution: " << this->LengthResolution << "\n";
  os << indent << "ScalarRange: " << this->ScalarRange[0] << " " << this->ScalarRange[1] << "\n";
  os << indent << "MaxLength: " << this->MaxLength << "\n";
  os << indent << "GPUMemorySize: " << this->GetGPUMemorySize() << "\n";
}
