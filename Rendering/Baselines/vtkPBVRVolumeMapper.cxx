#include "vtkPBVRVolumeMapper.h"

#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLLoader.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkTimeStamp.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include "vtkBatchedVertexArray.h"
#include "vtkEnsembleBuffer.h"
#include "vtkPBVRParticleGenerator.h"
#include "vtkSavedGLState.h"
#include "vtkTetrahedralMesh.h"
#include "vtkTransferFunctionSamples.h"
#include "vtkVolumeViewMatrices.h"

#include "vtkHashRandom.h"
#include "vtkPBVRParticlesFS.h"
#include "vtkPBVRParticlesVS.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace
{
// Samples of the transfer functions over the scalar range: the opacity that sets the particle
// density and the color table of the vertex shader.
constexpr int TransferFunctionSamples = 4096;
// Particles are made for no nearer depth than this multiple of the data's bounding radius:
// nearer ones (the camera inside or close to the data) are drawn as larger points.
constexpr double NearestGenerationDepth = 1.0;
// Draw calls stay far below GLsizei's range.
constexpr vtkIdType MaxParticlesPerDraw = vtkIdType(1) << 28;

// The particles that fit in a memory bound (MiB), within the range of a draw's int count.
size_t ParticlesInMemory(int memory)
{
  return std::min(size_t(memory) * 1024 * 1024 / vtkPBVRParticleGenerator::BytesPerParticle,
    size_t(std::numeric_limits<int>::max() - 1));
}

// What a particle set was generated for (the generator's settings, and the mesh and opacity
// they were applied to), and which views it serves. Particles follow the opacity (their
// density) and the cross-section of the pixels they are drawn into: a set made for a
// cross-section S serves every view that needs S to 2 S (the surplus is thinned when drawn);
// beyond that, or below S, particles are made again. A generation that failed (too many
// particles for the memory bound) is not tried again until a view needs particles larger by a
// quarter, fewer sets or more memory.
struct ParticleKey : vtkPBVRParticleGenerator::Settings
{
  // Particles serve views whose cross-section is at most this multiple of theirs.
  static constexpr double LargestFootprintRatio = 2.0;
  // After a failed generation, a view must need particles this much larger to try again.
  static constexpr double RetryFootprintRatio = 1.25;

  vtkMTimeType MeshBuild = 0;
  vtkMTimeType OpacityChange = 0;

  // Whether both keys describe the same density of particles.
  bool SameModel(const ParticleKey& o) const
  {
    return this->MeshBuild == o.MeshBuild && this->OpacityChange == o.OpacityChange &&
      this->Seed == o.Seed && this->SamplingMode == o.SamplingMode;
  }

  // Whether particles generated for this key serve a view that needs a cross-section `needed`
  // and `sets` particle sets within the memory of `wanted`.
  bool Serves(const ParticleKey& wanted, double needed, int sets, size_t particles) const
  {
    return this->SameModel(wanted) && needed >= this->Footprint &&
      needed <= LargestFootprintRatio * this->Footprint && this->Sets >= sets &&
      particles <= wanted.MaximumParticles;
  }

  // Whether a generation for `wanted` fails again as the one for this key did: it can only
  // succeed with larger particles, fewer sets or more memory.
  bool FailsAgain(const ParticleKey& wanted) const
  {
    return this->SameModel(wanted) && this->Sets <= wanted.Sets &&
      wanted.Footprint <= RetryFootprintRatio * this->Footprint &&
      this->MaximumParticles >= wanted.MaximumParticles;
  }
};
}

class vtkPBVRVolumeMapper::vtkInternals
{
public:
  vtkTetrahedralMesh* Mesh = nullptr;    // the base class's
  vtkEnsembleBuffer* Ensemble = nullptr; // the base class's
  vtkNew<vtkPBVRParticleGenerator> Generator;
  vtkVolumeViewMatrices Transforms;

  // The transfer functions, sampled over the mesh's scalar range. Only a change of the opacity
  // calls for new particles; colors are looked up when drawn.
  vtkTransferFunctionSamples Samples;
  vtkTimeStamp ColorUploadTime;
  vtkNew<vtkTextureObject> ColorTexture;

  // The mesh's bounding sphere about its normalized origin.
  double MeshRadius = 0.0;
  vtkMTimeType RadiusBuild = 0;

  // The particles and what they were made for.
  ParticleKey Generated;
  bool HaveParticles = false;
  ParticleKey Failed;
  bool HaveFailed = false;
  vtkIdType GenerationCount = 0;
  vtkNew<vtkOpenGLBufferObject> ParticleBuffer;
  vtkBatchedVertexArray VertexArray;
  size_t UploadedBytes = 0;

  vtkTextureObject* GetColorTexture(vtkOpenGLRenderWindow* renWin)
  {
    vtkTextureObject* texture = this->ColorTexture;
    if (texture->GetHandle() && texture->GetContext() == renWin &&
      this->ColorUploadTime > this->Samples.GetColorTime())
    {
      return texture;
    }
    std::vector<float> rgba(4 * TransferFunctionSamples, 1.0f);
    for (int i = 0; i < TransferFunctionSamples; ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        rgba[4 * i + c] = static_cast<float>(this->Samples.GetColor()[3 * i + c]);
      }
    }
    texture->SetContext(renWin);
    texture->SetWrapS(vtkTextureObject::ClampToEdge);
    texture->SetWrapT(vtkTextureObject::ClampToEdge);
    texture->SetMinificationFilter(vtkTextureObject::Linear);
    texture->SetMagnificationFilter(vtkTextureObject::Linear);
    if (!texture->Create2DFromRaw(TransferFunctionSamples, 1, 4, VTK_FLOAT, rgba.data()))
    {
      texture->ReleaseGraphicsResources(renWin);
      return nullptr;
    }
    this->ColorUploadTime.Modified();
    return texture;
  }

  void UpdateMeshRadius()
  {
    if (this->RadiusBuild == this->Mesh->GetBuildTime())
    {
      return;
    }
    const std::vector<float>& points = this->Mesh->GetPoints();
    double radius2 = 0.0;
    for (unsigned int id : this->Mesh->GetTetrahedra())
    {
      const float* p = &points[3 * size_t(id)];
      radius2 = std::max(radius2, double(p[0]) * p[0] + double(p[1]) * p[1] + double(p[2]) * p[2]);
    }
    this->MeshRadius = std::sqrt(radius2);
    this->RadiusBuild = this->Mesh->GetBuildTime();
  }

  double SmallestFootprint(int passWidth, int passHeight, bool atGenerationDepth = true) const
  {
    // The cross-section of one pass pixel at clip w, in normalized view units, is
    // 4 w^2 / (P00 P11 width height), perspective and parallel alike; per unit length of a
    // perspective ray at angle phi to the axis, it is that times cos(phi). The smallest one over
    // the data's bounding sphere is at its nearest w, at the corner of the frustum.
    const vtkVolumeViewMatrices& t = this->Transforms;
    const double(*p)[4] = t.ViewToClip;
    const double radius =
      this->MeshRadius * vtkVolumeViewMatrices::LargestSingularValue(t.ModelToViewLinear);
    // The mesh's normalized origin in view coordinates, and its w.
    const double centerW = p[3][0] * t.ModelToView[0][3] + p[3][1] * t.ModelToView[1][3] +
      p[3][2] * t.ModelToView[2][3] + p[3][3];
    const double wGradient = std::sqrt(p[3][0] * p[3][0] + p[3][1] * p[3][1] + p[3][2] * p[3][2]);
    double nearestW = centerW - wGradient * radius;
    double cosine = 1.0;
    if (!t.ParallelProjection)
    {
      // Nothing nearer than the near plane, n = P23 / (P22 - 1), is drawn, and nothing nearer
      // than the generation's nearest depth needs particles of its own size.
      nearestW = std::max(nearestW, p[2][3] / (p[2][2] - 1.0));
      if (atGenerationDepth)
      {
        nearestW = std::max(nearestW, NearestGenerationDepth * wGradient * radius);
      }
      const double tanX = (1.0 + std::abs(p[0][2])) / std::abs(p[0][0]);
      const double tanY = (1.0 + std::abs(p[1][2])) / std::abs(p[1][1]);
      cosine = 1.0 / std::sqrt(1.0 + tanX * tanX + tanY * tanY);
    }
    const double areaVC = 4.0 * nearestW * nearestW * cosine /
      (std::abs(p[0][0] * p[1][1]) * double(passWidth) * double(passHeight));
    // In model units: volumes scale by |det|, ray lengths by at most the largest singular value.
    const double volumeRatio = std::abs(vtkMath::Determinant3x3(t.ViewToModelLinear));
    return areaVC * volumeRatio / vtkVolumeViewMatrices::LargestSingularValue(t.ViewToModelLinear);
  }

  // The side of the largest point drawn (pixels), and the guard band that keeps the points
  // centred outside the pass (see PlacePoints()).
  double LargestPointSize = 1.0;
  int GuardBand = 0;
  void PlacePoints(int passWidth, int passHeight)
  {
    // A particle's point covers generated / own cross-section pixels; the nearest visible one
    // has the smallest cross-section.
    const double nearest = this->SmallestFootprint(passWidth, passHeight, false);
    const double side = std::sqrt(this->Generated.Footprint / nearest);
    float range[2] = { 1.0f, 1.0f };
    glGetFloatv(GL_POINT_SIZE_RANGE, range);
    this->LargestPointSize =
      std::isfinite(side) ? std::min(std::max(side, 1.0), double(range[1])) : double(range[1]);
    // OpenGL clips a point by its centre: a point up to half its side outside the pass still
    // covers pixels of it. A wider viewport, with the projection shrunk to match, keeps those.
    this->GuardBand =
      this->LargestPointSize > 1.0 ? int(std::ceil(0.5 * this->LargestPointSize)) : 0;
  }

  bool Generate(const ParticleKey& wanted)
  {
    this->ReleaseParticles();
    std::vector<double> attenuation(this->Samples.GetAttenuation());
    for (double& tau : attenuation)
    {
      tau *= this->Mesh->GetScale(); // per normalized model unit
    }
    if (!this->Generator->Generate(this->Mesh, attenuation, wanted))
    {
      this->Failed = wanted;
      this->HaveFailed = true;
      return false;
    }
    this->HaveFailed = false;
    ++this->GenerationCount;
    return true;
  }

  bool Upload()
  {
    this->UploadedBytes = 0;
    this->VertexArray.ForgetLayout();
    const std::vector<unsigned short>& particles = this->Generator->GetParticles();
    const bool uploaded = particles.empty() ||
      this->ParticleBuffer->Upload(particles, vtkOpenGLBufferObject::ArrayBuffer);
    this->UploadedBytes = uploaded ? particles.size() * sizeof(unsigned short) : 0;
    this->Generator->ReleaseParticles(); // on the GPU now, or failed for good
    return uploaded;
  }

  void ReleaseParticles()
  {
    this->ParticleBuffer->ReleaseGraphicsResources();
    this->VertexArray.ReleaseGraphicsResources();
    this->UploadedBytes = 0;
    this->HaveParticles = false;
  }

  void SetUniforms(vtkShaderProgram* program, vtkTextureObject* colors,
    vtkTextureObject* sceneDepth, unsigned int seed, int subpixelLevel)
  {
    vtkVolumeViewMatrices& transforms = this->Transforms;
    const double(*p)[4] = transforms.ViewToClip;
    const int width = this->Ensemble->GetPassWidth();
    const int height = this->Ensemble->GetPassHeight();
    const float pixelArea =
      static_cast<float>(4.0 / (std::abs(p[0][0] * p[1][1]) * width * height));
    const float colorTexel[2] = { float(TransferFunctionSamples - 1) / TransferFunctionSamples,
      0.5f / TransferFunctionSamples };
    transforms.SetUniforms(program);
    program->SetUniformf("viewToModelVolume",
      static_cast<float>(std::abs(vtkMath::Determinant3x3(transforms.ViewToModelLinear))));
    program->SetUniformf("pixelAreaFactor", pixelArea);
    program->SetUniformi("parallelProjection", transforms.ParallelProjection ? 1 : 0);
    program->SetUniformf("largestPointSize", static_cast<float>(this->LargestPointSize));
    const float clipScale[2] = { float(width) / float(width + 2 * this->GuardBand),
      float(height) / float(height + 2 * this->GuardBand) };
    program->SetUniform2f("clipScale", clipScale);
    program->SetUniformf("generatedFootprint", static_cast<float>(this->Generated.Footprint));
    program->SetUniformi("seed", static_cast<int>(seed));
    program->SetUniformi("colorTable", colors->GetTextureUnit());
    program->SetUniform2f("colorTexelScaleOffset", colorTexel);
    program->SetUniformi("sceneDepthTexture", sceneDepth->GetTextureUnit());
    program->SetUniformi("subpixelLevel", subpixelLevel);
    float pixelScale[2];
    this->Ensemble->GetPixelScale(pixelScale);
    program->SetUniform2f("pixelScale", pixelScale);
  }

  void DrawSet(vtkOpenGLState* ostate, vtkShaderProgram* program, int set)
  {
    const vtkIdType first = this->Generator->GetSetOffset(set);
    const vtkIdType end = this->Generator->GetSetOffset(set + 1);
    if (end <= first)
    {
      return;
    }
    this->VertexArray.Bind(program,
      { { "particleMC", this->ParticleBuffer, vtkPBVRParticleGenerator::BytesPerParticle,
        VTK_UNSIGNED_SHORT, 4, true } });
    vtkOpenGLState::ScopedglViewport viewport(ostate);
    const int band = this->GuardBand;
    ostate->vtkglViewport(-band, -band, this->Ensemble->GetPassWidth() + 2 * band,
      this->Ensemble->GetPassHeight() + 2 * band);
    vtkBatchedVertexArray::DrawArrays(GL_POINTS, first, end - first, MaxParticlesPerDraw);
    this->VertexArray.Release();
  }
};

vtkStandardNewMacro(vtkPBVRVolumeMapper);

vtkPBVRVolumeMapper::vtkPBVRVolumeMapper()
  : Internals(new vtkInternals)
{
  this->Internals->Mesh = this->GetMesh();
  this->Internals->Ensemble = this->GetEnsemble();
  // Every set is drawn unless asked otherwise, as the papers' PBVR does.
  this->AutoAdjustRepetitions = 0;
}

vtkPBVRVolumeMapper::~vtkPBVRVolumeMapper() = default;

vtkIdType vtkPBVRVolumeMapper::GetNumberOfParticles()
{
  return this->Internals->HaveParticles ? this->Internals->Generator->GetNumberOfParticles() : 0;
}

int vtkPBVRVolumeMapper::GetNumberOfParticleSets()
{
  return this->Internals->HaveParticles ? this->Internals->Generated.Sets : 0;
}

double vtkPBVRVolumeMapper::GetParticleSize()
{
  const vtkInternals& internals = *this->Internals;
  return internals.HaveParticles
    ? std::sqrt(internals.Generated.Footprint) * internals.Mesh->GetScale()
    : 0.0;
}

vtkIdType vtkPBVRVolumeMapper::GetGPUMemorySize()
{
  const vtkInternals& internals = *this->Internals;
  const size_t colors =
    internals.ColorTexture->GetHandle() ? size_t(4) * sizeof(float) * TransferFunctionSamples : 0;
  return static_cast<vtkIdType>(
    internals.UploadedBytes + colors + internals.Ensemble->GetGPUMemorySize());
}

vtkIdType vtkPBVRVolumeMapper::GetGenerationCount()
{
  return this->Internals->GenerationCount;
}

double vtkPBVRVolumeMapper::GetGenerationTime()
{
  return this->Internals->Generator->GetGenerationTime();
}

bool vtkPBVRVolumeMapper::PrepareParticles(
  vtkRenderer* ren, vtkVolume* vol, int passWidth, int passHeight)
{
  vtkInternals& internals = *this->Internals;
  if (!this->ComputeMatrices(ren, vol, internals.Transforms))
  {
    return false;
  }
  internals.UpdateMeshRadius();
  const double needed = internals.SmallestFootprint(passWidth, passHeight);
  if (!(needed > 0.0) || !std::isfinite(needed))
  {
    vtkErrorMacro("The camera is inside or too close to the volume: no particle size fits "
                  "the nearest point of the data.");
    return false;
  }

  ParticleKey wanted;
  wanted.MeshBuild = internals.Mesh->GetBuildTime();
  wanted.OpacityChange = internals.Samples.GetAttenuationTime();
  wanted.Seed = this->Seed;
  wanted.SamplingMode = this->SamplingMode;
  wanted.MaximumParticles = ParticlesInMemory(this->MaximumParticleMemory);
  if (internals.HaveParticles &&
    internals.Generated.Serves(
      wanted, needed, this->RepetitionLevel, size_t(internals.Generator->GetNumberOfParticles())))
  {
    return true;
  }
  wanted.Footprint = needed;
  wanted.Sets = this->RepetitionLevel;
  if (internals.HaveFailed && internals.Failed.FailsAgain(wanted))
  {
    return false; // reported when it failed
  }

  if (!internals.Generate(wanted))
  {
    vtkErrorMacro(<< internals.Generator->GetLastError() << " Raise MaximumParticleMemory ("
                  << this->MaximumParticleMemory << " MiB), or lower RepetitionLevel ("
                  << this->RepetitionLevel << "), SubpixelLevel (" << this->SubpixelLevel
                  << ") or the opacity.");
    return false;
  }
  if (!internals.Upload())
  {
    vtkErrorMacro("Could not upload " << internals.Generator->GetNumberOfParticles()
                                      << " particles to the GPU (out of GPU memory?).");
    internals.ReleaseParticles();
    internals.Failed = wanted;
    internals.HaveFailed = true;
    return false;
  }
  internals.Generated = wanted;
  internals.HaveParticles = true;
  return true;
}

void vtkPBVRVolumeMapper::Render(vtkRenderer* ren, vtkVolume* vol)
{
  vtkInternals& internals = *this->Internals;
  RenderTarget target;
  if (!this->BeginFrame(ren, target))
  {
    return;
  }
  vtkOpenGLRenderWindow* renWin = target.Window;

  if (!this->PrepareMesh(vol, true))
  {
    internals.ReleaseParticles();
    return;
  }
  if (!internals.Samples.Update(
        vol->GetProperty(), this->GetMesh()->GetScalarRange(), TransferFunctionSamples))
  {
    vtkErrorMacro(<< internals.Samples.GetLastError());
    return;
  }

  vtkOpenGLClearErrorMacro();
  vtkOpenGLState* ostate = renWin->GetState();
  vtkSavedGLState savedState(ostate);

  vtkEnsembleBuffer* ensemble = internals.Ensemble;
  if (!ensemble->Prepare(renWin, target.Width, target.Height, this->SubpixelLevel,
        this->ChooseSampleDistance(vol)) ||
    !this->PrepareParticles(ren, vol, ensemble->GetPassWidth(), ensemble->GetPassHeight()))
  {
    return;
  }
  // The sets that fit the time allotted, after those accumulated when refining progressively;
  // at most the sets generated.
  int perPass = 1;
  Traversal kind = Traversal::Single;
  int count = this->ChooseRepetitions(vol, this->RepetitionLevel, perPass, kind);
  std::vector<double> signature;
  internals.Transforms.AppendSignature(signature);
  signature.push_back(double(internals.GenerationCount));
  signature.push_back(double(this->GetMTime()));
  const int viewport[4] = { target.X, target.Y, target.Width, target.Height };
  AppendSceneSignature(ren, viewport, signature);
  signature.push_back(ensemble->GetSampleDistance());
  const int first = this->ContinueAccumulation(std::move(signature), count);
  count = std::max(0, std::min(count, internals.Generated.Sets - first));
  this->DrawSets(target.X, target.Y, first, count);
  vtkOpenGLCheckErrorMacro("failed after Render");
}

void vtkPBVRVolumeMapper::DrawSets(int x, int y, int first, int count)
{
  vtkInternals& internals = *this->Internals;
  vtkOpenGLRenderWindow* renWin = this->GetContext();
  vtkOpenGLState* ostate = renWin->GetState();
  vtkEnsembleBuffer* ensemble = internals.Ensemble;
  vtkTextureObject* colors = internals.GetColorTexture(renWin);
  std::string vertex = vtkPBVRParticlesVS;
  vtkShaderProgram::Substitute(vertex, "//Volume::Random::Impl",
    internals.Transforms.ClippingPlaneDefine("PBVR") + vtkHashRandom);
  vtkShaderProgram* program =
    renWin->GetShaderCache()->ReadyShaderProgram(vertex.c_str(), vtkPBVRParticlesFS, "");
  if (!colors || !program)
  {
    vtkErrorMacro(
      "Could not " << (colors ? "compile the PBVR shaders." : "upload the color table."));
    this->ForgetAccumulation();
    return;
  }
  ostate->PushFramebufferBindings();
  if (first == 0)
  {
    ensemble->CaptureSceneDepth(x, y);
    ensemble->ClearSum();
    this->ResetAccumulation();
  }
  colors->Activate();
  vtkTextureObject* sceneDepth = ensemble->GetSceneDepthTexture();
  sceneDepth->Activate();

  ostate->vtkglDisable(GL_BLEND);
  ostate->vtkglDisable(GL_CULL_FACE);
  ostate->vtkglDisable(GL_SCISSOR_TEST);
  ostate->vtkglEnable(GL_DEPTH_TEST);
  ostate->vtkglDepthFunc(GL_LESS);
  ostate->vtkglPointSize(1.0f);
  // Particles nearer than the depth they were generated for are drawn larger (the vertex
  // shader sets their size).
  vtkOpenGLState::ScopedglEnableDisable programPointSize(ostate, GL_PROGRAM_POINT_SIZE);
  ostate->vtkglEnable(GL_PROGRAM_POINT_SIZE);
  internals.PlacePoints(ensemble->GetPassWidth(), ensemble->GetPassHeight());
  this->StartTiming();
  for (int set = first; set < first + count; ++set)
  {
    ensemble->BeginPass();
    // The ensemble's accumulation binds its own program between passes.
    renWin->GetShaderCache()->ReadyShaderProgram(program);
    if (set == first)
    {
      internals.SetUniforms(program, colors, sceneDepth, this->Seed, this->SubpixelLevel);
    }
    internals.DrawSet(ostate, program, set);
    ensemble->EndPass();
  }
  this->AddRepetitions(count, 1, Traversal::Single, this->StopTiming());
  sceneDepth->Deactivate();
  colors->Deactivate();
  ostate->PopFramebufferBindings();
  ensemble->Resolve(x, y, this->GetAccumulatedRepetitions());
}

void vtkPBVRVolumeMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  vtkInternals& internals = *this->Internals;
  internals.ReleaseParticles();
  internals.ColorTexture->ReleaseGraphicsResources(window);
  this->Superclass::ReleaseGraphicsResources(window);
}

void vtkPBVRVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent
     << "SamplingMode: " << (this->SamplingMode == REJECTION ? "Rejection" : "CellAverage") << "\n";
  os << indent << "MaximumParticleMemory: " << this->MaximumParticleMemory << " MiB\n";
  os << indent << "NumberOfParticles: " << this->GetNumberOfParticles() << "\n";
  os << indent << "NumberOfParticleSets: " << this->GetNumberOfParticleSets() << "\n";
  os << indent << "ParticleSize: " << this->GetParticleSize() << "\n";
  os << indent << "GenerationCount: " << this->GetGenerationCount() << "\n";
  os << indent << "GenerationTime: " << this->GetGenerationTime() << " s\n";
  os << indent << "GPUMemorySize: " << this->GetGPUMemorySize() << "\n";
}
