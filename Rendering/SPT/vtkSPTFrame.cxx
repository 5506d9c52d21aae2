#include "vtkSPTFrame.h"

#include "vtkObject.h"
#include "vtkOpenGLLoader.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

#include "vtkEnsembleBuffer.h"
#include "vtkPreIntegrationTable.h"
#include "vtkSPTComputeTraversal.h"
#include "vtkSPTDepthKeyBuffer.h"
#include "vtkSPTMeshBuffers.h"
#include "vtkTetrahedralMesh.h"
#include "vtkVolumeViewMatrices.h"

#include "vtkHashRandom.h"
#include "vtkSPTDepthSlabs.h"
#include "vtkSPTFacePlane.h"
#include "vtkSPTPassColorsFS.h"
#include "vtkSPTPassCoverageFS.h"
#include "vtkSPTPassDepthColorsFS.h"
#include "vtkSPTPassKeysFS.h"
#include "vtkSPTPassSingleFS.h"
#include "vtkSPTPointCell.h"
#include "vtkSPTTetrahedraCS.h"
#include "vtkSPTTetrahedraFS.h"
#include "vtkSPTTetrahedraGS.h"
#include "vtkSPTTetrahedraPointsVS.h"
#include "vtkSPTTetrahedraVS.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <initializer_list>
#include <memory>
#include <string>

namespace
{
constexpr int DepthKeyImageUnit = 0;
// The compute traversal's fixed-point sums.
constexpr int SumsImageUnit = 1;
// The depth slabs' sums, then their controls.
constexpr int SlabDepthsImageUnit = 2;
// A slab whose optical depth reaches this hides what lies behind it to within float precision
// (exp(-40) = 4e-18): it adds no more.
constexpr int SlabDepthCap = 40;
// The compute traversal takes the cells drawn as points that are about this many pixels across
// or less: a sample's work grows with the group's lanes, and at 256 repetitions per traversal on
// a 200,000-cell TetGen mesh, computing all its points (up to 8 pixels across) took 1.13 to 1.17
// of the frame that computes those up to 4 pixels (0.69 to 0.88 at 2 to 32 repetitions); on the
// 1M-cell one, 4 pixels take nearly all its points.
constexpr double ComputedCellSize = 4.0;
// ... and only where they are at least this many per sample of the image.
constexpr double ComputedCellsPerSample = 0.25;

// Texture objects active for a scope, deactivated in reverse order on every way out.
class ScopedTextures
{
public:
  explicit ScopedTextures(std::initializer_list<vtkTextureObject*> textures)
    : Textures(textures)
  {
    for (vtkTextureObject* texture : this->Textures)
    {
      texture->Activate();
    }
  }
  ~ScopedTextures()
  {
    for (auto it = this->Textures.rbegin(); it != this->Textures.rend(); ++it)
    {
      (*it)->Deactivate();
    }
  }
  ScopedTextures(const ScopedTextures&) = delete;
  ScopedTextures& operator=(const ScopedTextures&) = delete;

private:
  std::vector<vtkTextureObject*> Textures;
};

// How far beyond the target a step with a measured noise aims, in variance: a step costs a
// traversal pair whatever its repetitions (up to a group), and the estimate is itself noisy:
// aiming at the target exactly falls short about half the time, and a step of a few
// repetitions more costs another pair.
constexpr double StepMargin = 1.25;

// The repetitions to add to each half for the noise to fall from `estimate` to StepMargin below
// `target` in variance, if it falls as one over the square root of the repetitions: at least
// one, at most 16 times what each half holds.
int RepetitionsToTarget(int half, double estimate, double target)
{
  const double ratio = estimate / target;
  const double more = std::ceil(half * (StepMargin * ratio * ratio - 1.0));
  return static_cast<int>(std::max(1.0, std::min(more, 16.0 * half)));
}

// The noise of one repetition that the first image of a mapper assumes before it has measured
// any (RMSE of premultiplied RGBA): a little above the largest measured on the benchmark's
// scenes at their defaults (0.025 on the torus, 0.020 to 0.023 on the Oxygen Post and the
// drill; 0.004 to 0.006 on Blunt Fin and SPX). At the default target of 0.005 it draws 16 + 16.
constexpr double FirstImageNoisePerRepetition = 0.0275;

// The repetitions per half of an image's first step: as many as the noise of one repetition
// predicts for the target, times `margin` in variance, at least one and at most `most`. A
// measured noise gets the margin of every step (StepMargin); the first image's assumed one none,
// as the assumption is already a pessimistic one. A target of 0 (one below the rounding) draws
// `most`.
int FirstHalfToTarget(double noisePerRepetition, double target, double margin, int most)
{
  if (!(target > 0.0))
  {
    return most;
  }
  const double ratio = noisePerRepetition / target;
  const double half = std::ceil(0.5 * margin * ratio * ratio);
  return static_cast<int>(std::max(1.0, std::min(half, double(most))));
}
}

vtkSPTFrame::vtkSPTFrame(vtkOpenGLRenderWindow* window, vtkEnsembleBuffer* ensemble,
  vtkSPTDepthKeyBuffer* depthKeys, const std::vector<Volume>& volumes, const Settings& settings,
  vtkObject* reporter)
  : Window(window)
  , Ensemble(ensemble)
  , DepthKeys(depthKeys)
  , Volumes(volumes)
  , FrameSettings(settings)
  , Reporter(reporter)
{
  for (const Volume& volume : volumes)
  {
    this->NearPlaneCuts = this->NearPlaneCuts || volume.Matrices->NearPlaneCutsBounds;
  }
  const int mostSlabs = MaximumDepthSlabs; // a value: std::min takes references
  this->FrameSettings.DepthSlabs = std::max(1, std::min(this->FrameSettings.DepthSlabs, mostSlabs));
  this->ChooseSmallCells();
  this->ChooseSlabs();
}

void vtkSPTFrame::ChooseSlabs()
{
  // Any split of each ray between its segments composites exactly in expectation; equal parts
  // of the depth the volumes' bounds span within the clipping range are a split that every
  // volume of the frame (and every rank, whose bounds are the whole's) agrees on.
  const int slabs = this->FrameSettings.DepthSlabs;
  std::fill(std::begin(this->SlabStarts), std::end(this->SlabStarts), 2.0f);
  if (slabs <= 1 || this->Volumes.empty())
  {
    return;
  }
  const vtkVolumeViewMatrices& view = *this->Volumes.front().Matrices;
  double nearest = VTK_DOUBLE_MAX;
  double farthest = -VTK_DOUBLE_MAX;
  for (const Volume& volume : this->Volumes)
  {
    nearest = std::min(nearest, volume.Matrices->BoundsDistance[0]);
    farthest = std::max(farthest, volume.Matrices->BoundsDistance[1]);
  }
  nearest = std::max(nearest, view.ClippingDistance[0]);
  farthest = std::min(farthest, view.ClippingDistance[1]);
  if (!(nearest < farthest) || view.ViewScale <= 0.0)
  {
    return; // nothing in view: one slab
  }
  for (int k = 1; k < slabs; ++k)
  {
    const double distance = nearest + (farthest - nearest) * k / slabs;
    // The window depth of that distance, through the first volume's projection.
    const double z = -distance / view.ViewScale;
    const double clipZ = view.ViewToClip[2][2] * z + view.ViewToClip[2][3];
    const double clipW = view.ViewToClip[3][2] * z + view.ViewToClip[3][3];
    const double depth = clipW != 0.0 ? 0.5 * clipZ / clipW + 0.5 : 2.0;
    this->SlabStarts[k - 1] = static_cast<float>(std::max(0.0, std::min(depth, 1.0)));
  }
}

std::string vtkSPTFrame::SlabDefines(PassKind kind) const
{
  const bool groups =
    kind == PassKind::Keys || kind == PassKind::KeysAndCoverage || kind == PassKind::Colors;
  if (!groups || this->FrameSettings.DepthSlabs <= 1)
  {
    return "";
  }
  return "#define SPT_DEPTH_SLABS " + std::to_string(this->FrameSettings.DepthSlabs) +
    "\n#define SPT_SLAB_FIXED_ONE " + std::to_string(vtkSPTDepthKeyBuffer::GetSlabFixedOne()) +
    "u\n#define SPT_SLAB_DEPTH_CAP " + std::to_string(SlabDepthCap) + "u\n#define SPT_SLAB_TERMS " +
    std::to_string(vtkSPTDepthKeyBuffer::SlabTerms) + "\n";
}

void vtkSPTFrame::ChooseSmallCells()
{
  // The cells drawn as points are about SmallCellSize pixels across at the depth of the mesh's
  // centre, and no point may exceed the largest size OpenGL draws, wherever it lies. Of them,
  // the compute traversal takes the leading classes, about ComputedCellSize pixels across.
  GLfloat pointSizes[2] = { 1.0f, 1.0f };
  glGetFloatv(GL_POINT_SIZE_RANGE, pointSizes);
  const double halfSize[2] = { 0.5 * this->Ensemble->GetPassWidth(),
    0.5 * this->Ensemble->GetPassHeight() };
  this->PointCellCounts.clear();
  this->ComputeCellCounts.clear();
  vtkIdType computed = 0;
  for (const Volume& volume : this->Volumes)
  {
    const double* bound = volume.Matrices->NDCPerLength;
    const double* typical = volume.Matrices->TypicalNDCPerLength;
    const double largestPixels = std::max(bound[0] * halfSize[0], bound[1] * halfSize[1]);
    const double typicalPixels = std::max(typical[0] * halfSize[0], typical[1] * halfSize[1]);
    const bool inView = largestPixels > 0.0 && typicalPixels > 0.0;
    const double length = inView ? std::min(this->FrameSettings.SmallCellSize / typicalPixels,
                                     (pointSizes[1] - 1.0) / largestPixels)
                                 : -1.0;
    this->PointCellCounts.push_back(volume.Buffers->CountSmallCells(length));
    const double computeLength = !inView || this->FrameSettings.ComputeEveryPoint
      ? length
      : std::min(length, ComputedCellSize / typicalPixels);
    this->ComputeCellCounts.push_back(
      this->FrameSettings.Compute ? volume.Buffers->CountSmallCells(computeLength) : 0);
    computed += this->ComputeCellCounts.back();
  }
  // A traversal that computes clears the fixed-point sums and adds them to the image, a pass
  // over every sample: it pays where the cells it takes from the rasterizer are many.
  const double samples =
    double(this->Ensemble->GetPassWidth()) * double(this->Ensemble->GetPassHeight());
  if (!this->FrameSettings.ComputeEveryPoint && computed < ComputedCellsPerSample * samples)
  {
    this->ComputeCellCounts.assign(this->Volumes.size(), 0);
  }
  this->ComputedCellCounts.assign(this->Volumes.size(), 0);
}

vtkIdType vtkSPTFrame::GetPointCellCount(size_t volume) const
{
  return this->PointCellCounts[volume];
}

vtkIdType vtkSPTFrame::GetComputedCellCount(size_t volume) const
{
  return this->ComputedCellCounts[volume];
}

bool vtkSPTFrame::Draws(size_t volume, bool points) const
{
  const vtkIdType pointCells = this->PointCellCounts[volume];
  return points ? pointCells > 0
                : pointCells < this->Volumes[volume].Buffers->GetMesh()->GetNumberOfTetrahedra();
}

vtkShaderProgram*& vtkSPTFrame::ProgramOf(PassKind kind, size_t volume, bool points)
{
  const bool cellScalars = this->Volumes[volume].Buffers->GetMesh()->GetCellScalars();
  return this->Programs[static_cast<int>(kind)][cellScalars ? 1 : 0][points ? 1 : 0];
}

vtkShaderProgram* vtkSPTFrame::ReadyProgram(
  bool cellScalars, bool clippedCells, bool points, PassKind kind, int lanes, bool halves)
{
  const char* const passes[NumberOfPassKinds] = { vtkSPTPassSingleFS, vtkSPTPassKeysFS,
    vtkSPTPassKeysFS, vtkSPTPassColorsFS, vtkSPTPassCoverageFS, vtkSPTPassDepthColorsFS,
    vtkSPTPassDepthColorsFS };
  // Both stages: scalars per cell, the path for cells that a clipping plane cuts (compiled in
  // only while one cuts some volume's bounds: a fragment stage pays for its branches),
  // and the scene depth (only when opaque geometry was drawn).
  std::string common = cellScalars ? "#define SPT_CELL_SCALARS\n" : "";
  common += clippedCells && !points ? "#define SPT_CLIPPED_CELLS\n" : "";
  common += this->FrameSettings.OpaqueScene ? "#define SPT_SCENE_DEPTH\n" : "";
  common += this->FrameSettings.GlobalIds ? "#define SPT_GLOBAL_IDS\n" : "";
  std::string vertex = points ? vtkSPTTetrahedraPointsVS : vtkSPTTetrahedraVS;
  std::string geometry = points ? "" : vtkSPTTetrahedraGS;
  vtkShaderProgram::Substitute(vertex, "//Volume::Defines::Dec", common);
  vtkShaderProgram::Substitute(geometry, "//Volume::Defines::Dec", common);
  vtkShaderProgram::Substitute(vertex, "//SPT::FacePlane::Impl", vtkSPTFacePlane);
  vtkShaderProgram::Substitute(geometry, "//SPT::FacePlane::Impl", vtkSPTFacePlane);
  vtkShaderProgram::Substitute(vertex, "//SPT::PointCell::Impl", vtkSPTPointCell);

  std::string defines =
    common + this->SlabDefines(kind) + "#define SPT_REPETITIONS_PER_PASS " + std::to_string(lanes);
  if (kind == PassKind::KeysAndCoverage || kind == PassKind::DepthColorsAndCoverage)
  {
    defines += "\n#define SPT_WRITE_COVERAGE";
  }
  if (kind == PassKind::Colors && this->FrameSettings.Estimator == VISIBILITY_ESTIMATOR)
  {
    defines += "\n#define SPT_VISIBILITY_WEIGHTED";
  }
  if (kind == PassKind::Colors && halves)
  {
    defines += "\n#define ENSEMBLE_SECOND_HALF"; // a second output only where one is bound
  }
  // VTK declares GLSL 1.50; image load/store comes as the extension.
  const bool atomics =
    kind == PassKind::Keys || kind == PassKind::KeysAndCoverage || kind == PassKind::Colors;
  std::string fragment = vtkSPTTetrahedraFS;
  // The slabs' controls are kept as float bits in an integer image.
  const std::string slabs =
    this->SlabDefines(kind).empty() ? "" : "\n#extension GL_ARB_shader_bit_encoding : require";
  vtkShaderProgram::Substitute(fragment, "//SPT::Extensions::Dec",
    atomics ? "#extension GL_ARB_shader_image_load_store : require" + slabs : "");
  vtkShaderProgram::Substitute(fragment, "//SPT::Pass::Dec", defines);
  vtkShaderProgram::Substitute(fragment, "//Volume::Random::Impl", vtkHashRandom);
  vtkShaderProgram::Substitute(fragment, "//SPT::Slabs::Impl", vtkSPTDepthSlabs);
  vtkShaderProgram::Substitute(fragment, "//SPT::Pass::Impl", passes[static_cast<int>(kind)]);
  return this->Window->GetShaderCache()->ReadyShaderProgram(
    vertex.c_str(), fragment.c_str(), geometry.c_str());
}

vtkShaderProgram* vtkSPTFrame::ReadyComputeProgram(
  bool cellScalars, PassKind kind, int lanes, bool halves)
{
  // The pass's fragment code, with the cell's planes and the sample's position set by the
  // compute pass's main() (vtkSPTTetrahedraCS.glsl) instead of read from the points.
  const bool colors = kind == PassKind::Colors;
  std::string defines = cellScalars ? "#define SPT_CELL_SCALARS\n" : "";
  defines += this->FrameSettings.OpaqueScene ? "#define SPT_SCENE_DEPTH\n" : "";
  defines += this->FrameSettings.GlobalIds ? "#define SPT_GLOBAL_IDS\n" : "";
  defines += this->SlabDefines(kind);
  defines += "#define SPT_REPETITIONS_PER_PASS " + std::to_string(lanes) + "\n";
  defines += kind == PassKind::KeysAndCoverage ? "#define SPT_WRITE_COVERAGE\n" : "";
  defines += colors ? "#define SPT_COMPUTE_COLORS\n" : "";
  defines += colors && this->FrameSettings.Estimator == VISIBILITY_ESTIMATOR
    ? "#define SPT_VISIBILITY_WEIGHTED\n"
    : "";
  defines += colors && halves ? "#define ENSEMBLE_SECOND_HALF\n" : "";
  defines += "#define SPT_COMPUTE_GROUP_SIZE " + std::to_string(vtkSPTComputeTraversal::GroupSize) +
    "\n#define SPT_FIXED_ONE " + std::to_string(vtkSPTComputeTraversal::FixedPointOne);
  std::string source = vtkSPTTetrahedraFS;
  vtkShaderProgram::Substitute(source, "//VTK::System::Dec", "#version 430\n#define SPT_COMPUTE");
  vtkShaderProgram::Substitute(source, "//SPT::Extensions::Dec", "");
  vtkShaderProgram::Substitute(source, "//VTK::Output::Dec", "");
  vtkShaderProgram::Substitute(source, "//SPT::Pass::Dec", defines);
  vtkShaderProgram::Substitute(source, "//Volume::Random::Impl", vtkHashRandom);
  vtkShaderProgram::Substitute(source, "//SPT::Slabs::Impl", vtkSPTDepthSlabs);
  vtkShaderProgram::Substitute(source, "//SPT::Pass::Impl",
    std::string(colors ? vtkSPTPassColorsFS : vtkSPTPassKeysFS) + vtkSPTTetrahedraCS);
  vtkShaderProgram::Substitute(source, "//SPT::FacePlane::Impl", vtkSPTFacePlane);
  vtkShaderProgram::Substitute(source, "//SPT::PointCell::Impl", vtkSPTPointCell);
  return this->FrameSettings.Compute->GetProgram(this->Window, source);
}

bool vtkSPTFrame::Computes(PassKind kind, size_t volume) const
{
  return this->FrameSettings.Compute &&
    (kind == PassKind::Keys || kind == PassKind::KeysAndCoverage || kind == PassKind::Colors) &&
    this->ComputeCellCounts[volume] > 0;
}

vtkIdType vtkSPTFrame::FirstRasterizedPoint(PassKind kind, size_t volume) const
{
  return this->Computes(kind, volume) ? this->ComputeCellCounts[volume] : 0;
}

bool vtkSPTFrame::Rasterizes(PassKind kind, size_t volume, bool points) const
{
  return points ? this->PointCellCounts[volume] > this->FirstRasterizedPoint(kind, volume)
                : this->Draws(volume, false);
}

bool vtkSPTFrame::ComputesMostCells() const
{
  vtkIdType computed = 0;
  vtkIdType cells = 0;
  for (size_t v = 0; v < this->Volumes.size(); ++v)
  {
    computed += this->FrameSettings.Compute ? this->ComputeCellCounts[v] : 0;
    cells += this->Volumes[v].Buffers->GetMesh()->GetNumberOfTetrahedra();
  }
  return computed > 0 && 2 * computed >= cells;
}

bool vtkSPTFrame::Computes(PassKind kind) const
{
  for (size_t v = 0; v < this->Volumes.size(); ++v)
  {
    if (this->Computes(kind, v))
    {
      return true;
    }
  }
  return false;
}

bool vtkSPTFrame::ReadyPrograms(
  const bool (&needed)[NumberOfPassKinds], int lanes, int first, int count, bool halves)
{
  // Each call has uniforms of its own (first, count, halves).
  for (auto& byScalars : this->Programs)
  {
    for (auto& byPrimitive : byScalars)
    {
      byPrimitive[0] = byPrimitive[1] = nullptr;
    }
  }
  for (auto& byScalars : this->ComputePrograms)
  {
    byScalars[0] = byScalars[1] = nullptr;
  }
  for (int k = 0; k < NumberOfPassKinds; ++k)
  {
    for (size_t v = 0; v < this->Volumes.size(); ++v)
    {
      const PassKind kind = static_cast<PassKind>(k);
      const bool cellScalars = this->Volumes[v].Buffers->GetMesh()->GetCellScalars();
      if (needed[k] && this->Computes(kind, v) && !this->ComputePrograms[k][cellScalars ? 1 : 0])
      {
        vtkShaderProgram* program = this->ReadyComputeProgram(cellScalars, kind, lanes, halves);
        if (!program)
        {
          // The traversal warned and will not be asked again in this context. The rasterizer
          // takes its cells from this group on (the same estimate: the sums differ by the fixed
          // point's rounding), so every program is chosen again.
          this->ComputeCellCounts.assign(this->Volumes.size(), 0);
          return this->ReadyPrograms(needed, lanes, first, count, halves);
        }
        this->ComputePrograms[k][cellScalars ? 1 : 0] = program;
        vtkSPTComputeTraversal::Use(this->Window, program);
        this->SetFrameUniforms(program, first, count, halves);
        program->SetUniformi("sums", SumsImageUnit);
      }
      for (const bool points : { false, true })
      {
        vtkShaderProgram*& program = this->ProgramOf(kind, v, points);
        if (!needed[k] || !this->Rasterizes(kind, v, points) || program)
        {
          continue;
        }
        program = this->ReadyProgram(this->Volumes[v].Buffers->GetMesh()->GetCellScalars(),
          this->NearPlaneCuts, points, kind, lanes, halves);
        if (!program)
        {
          vtkErrorWithObjectMacro(this->Reporter, "Could not compile the SPT shaders.");
          return false;
        }
        this->SetFrameUniforms(program, first, count, halves);
      }
    }
  }
  return true;
}

void vtkSPTFrame::Traverse(PassKind kind, int repetition, int inGroup)
{
  for (size_t v = 0; v < this->Volumes.size(); ++v)
  {
    const Volume& volume = this->Volumes[v];
    // The smallest cells in a compute pass, the other small cells as points, then triangles
    // for the others.
    for (const Primitive primitive :
      { Primitive::Computed, Primitive::Points, Primitive::Outlines })
    {
      const bool compute = primitive == Primitive::Computed;
      const bool points = primitive != Primitive::Outlines;
      if (compute ? !this->Computes(kind, v) : !this->Rasterizes(kind, v, points))
      {
        continue;
      }
      // The ensemble's accumulation binds its own program between passes; uniforms go to the
      // bound program.
      const bool cellScalars = volume.Buffers->GetMesh()->GetCellScalars();
      vtkShaderProgram* program = compute
        ? this->ComputePrograms[static_cast<int>(kind)][cellScalars ? 1 : 0]
        : this->ProgramOf(kind, v, points);
      if (compute)
      {
        vtkSPTComputeTraversal::Use(this->Window, program);
      }
      else
      {
        this->Window->GetShaderCache()->ReadyShaderProgram(program);
      }
      ScopedTextures textures({ volume.TableTexture, volume.Buffers->GetScalarTexture(),
        volume.Buffers->GetPointTexture(), volume.Buffers->GetTetrahedronTexture(),
        volume.Buffers->GetMeshIndexTexture() });
      std::unique_ptr<ScopedTextures> randomIds;
      if (this->FrameSettings.GlobalIds)
      {
        randomIds.reset(new ScopedTextures({ volume.Buffers->GetRandomIdTexture() }));
        program->SetUniformi("randomIds", volume.Buffers->GetRandomIdTexture()->GetTextureUnit());
      }
      SetVolumeUniforms(program, volume);
      if (kind == PassKind::DepthColors || kind == PassKind::DepthColorsAndCoverage)
      {
        // Active for the traversal (DrawDepthSurvivors()).
        program->SetUniformi(
          "survivorDepth", this->Ensemble->GetPassDepthTexture()->GetTextureUnit());
      }
      program->SetUniformi("repetition", repetition);
      program->SetUniformi("repetitionsInGroup", inGroup);
      program->SetUniformi("meshIndices", volume.Buffers->GetMeshIndexTexture()->GetTextureUnit());
      if (compute)
      {
        // The points' fragments pass the depth test against the farthest survivor when the
        // frame set one (PrepareSurvivors()): the compute pass makes the same test.
        vtkTextureObject* survivors = this->Ensemble->GetPassDepthTexture();
        const bool skipBehind = kind == PassKind::Colors &&
          this->Window->GetState()->GetEnumState(GL_DEPTH_TEST) && survivors->GetHandle();
        std::unique_ptr<ScopedTextures> farthest;
        if (kind == PassKind::Colors)
        {
          program->SetUniformi("behindSurvivorsSkipped", skipBehind ? 1 : 0);
        }
        if (skipBehind)
        {
          farthest.reset(new ScopedTextures({ survivors }));
          program->SetUniformi("farthestSurvivor", survivors->GetTextureUnit());
        }
        vtkSPTComputeTraversal::Dispatch(program, 0, this->ComputeCellCounts[v]);
        this->ComputedCellCounts[v] = this->ComputeCellCounts[v];
      }
      else
      {
        this->DrawTetrahedra(
          volume, program, points, this->FirstRasterizedPoint(kind, v), this->PointCellCounts[v]);
      }
    }
  }
}

void vtkSPTFrame::DrawTetrahedra(const Volume& volume, vtkShaderProgram* program, bool points,
  vtkIdType firstPoint, vtkIdType pointCells)
{
  if (points)
  {
    vtkOpenGLState* ostate = this->Window->GetState();
    ostate->vtkglEnable(GL_PROGRAM_POINT_SIZE);
    volume.Buffers->DrawPoints(program, firstPoint, pointCells - firstPoint);
    ostate->vtkglDisable(GL_PROGRAM_POINT_SIZE);
  }
  else
  {
    volume.Buffers->Bind(program);
    volume.Buffers->Draw(
      program, pointCells, volume.Buffers->GetMesh()->GetNumberOfTetrahedra() - pointCells);
    volume.Buffers->Unbind();
  }
}

bool vtkSPTFrame::DrawRepetitions(int first, int count, int perPass, bool coverage, bool halves)
{
  vtkOpenGLState* ostate = this->Window->GetState();
  // The programs this render needs, by pass kind and by scalars per cell or per point; the
  // others stay null. Groups draw the coverage with their first key traversal; single passes
  // need a traversal of its own. The survivor estimator draws one repetition at a time (one
  // per pass, or a render of one) as the paper does: the depth test finds the survivor in one
  // traversal, where keys would take two.
  // The visibility estimator one repetition at a time finds its survivors the same way, and
  // its color traversal then reads the survivor's depth (unless the ranks of a parallel frame
  // combine keys, the error target counts two halves, or a compute pass takes most of the
  // cells: there a group of one, whose keys and colors it computes, costs less than two
  // rasterized traversals).
  // Depth slabs need a survivor per slab, and their sums drawn with the coverage: keys,
  // whatever the repetitions (the mapper's cheapest frame draws no slabs).
  const bool oneAtATime = std::min(perPass, count) == 1 && !this->FrameSettings.AlwaysKeys &&
    this->FrameSettings.DepthSlabs == 1;
  const bool single = oneAtATime && this->FrameSettings.Estimator == SURVIVOR_ESTIMATOR;
  const bool depthSurvivors = oneAtATime && this->FrameSettings.Estimator == VISIBILITY_ESTIMATOR &&
    !halves && !this->ComputesMostCells();
  const bool keys = !single && !depthSurvivors;
  const bool needed[NumberOfPassKinds] = { single || depthSurvivors,
    keys && (!coverage || count > perPass), keys && coverage, keys, single && coverage,
    depthSurvivors && (!coverage || count > 1), depthSurvivors && coverage };
  // A render of fewer repetitions than a group draws only those: the fragment loops run over
  // the group's count, and the programs are compiled for the next power of two.
  const int lanes = std::min(perPass, count);
  // Active before the frame's uniforms name its unit.
  ScopedTextures sceneDepth({ this->Ensemble->GetSceneDepthTexture() });
  if (!this->ReadyPrograms(
        needed, vtkSPTDepthKeyBuffer::GetCompiledLanes(lanes), first, count, halves) ||
    (keys &&
      !this->DepthKeys->Prepare(this->Window, this->Ensemble->GetPassWidth(),
        this->Ensemble->GetPassHeight(), lanes, this->FrameSettings.DepthSlabs)))
  {
    return false;
  }
  ostate->vtkglDisable(GL_CULL_FACE);
  ostate->vtkglDisable(GL_SCISSOR_TEST);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunction(ostate);
  ostate->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ONE);
  if (depthSurvivors)
  {
    return this->DrawDepthSurvivors(first, count, coverage);
  }
  return single ? this->DrawSingles(first, count, coverage, halves)
                : this->DrawGroups(first, count, lanes, coverage, halves);
}

bool vtkSPTFrame::DrawDepthSurvivors(int first, int count, bool coverage)
{
  vtkOpenGLState* ostate = this->Window->GetState();
  vtkEnsembleBuffer* ensemble = this->Ensemble;
  bool ok = true;
  for (int r = first; ok && r < first + count; ++r)
  {
    // The survivor: the single pass's depth test keeps the nearest kept segment's front, as
    // the keys' atomic minimum would, and its color is not needed.
    ensemble->BeginPass();
    ostate->vtkglColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    ostate->vtkglDisable(GL_BLEND);
    ostate->vtkglEnable(GL_DEPTH_TEST);
    ostate->vtkglDepthFunc(GL_LESS);
    ostate->vtkglDepthMask(GL_TRUE);
    this->Traverse(PassKind::Single, r, 1);
    // Every fragment in front of it adds its color, read against its depth: no depth test
    // (the rasterized depth is the cell's nearest vertex, not the segment's front), and the
    // first traversal of the image adds every segment's coverage too.
    const bool withCoverage = coverage && r == first;
    ok = ensemble->BeginSumBesideDepthPass(withCoverage);
    if (ok)
    {
      ostate->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
      ostate->vtkglEnable(GL_BLEND);
      ostate->vtkglDisable(GL_DEPTH_TEST);
      ostate->vtkglDepthMask(GL_FALSE);
      ScopedTextures survivorDepth({ ensemble->GetPassDepthTexture() });
      this->Traverse(withCoverage ? PassKind::DepthColorsAndCoverage : PassKind::DepthColors, r, 1);
    }
  }
  ostate->vtkglDisable(GL_BLEND);
  ostate->vtkglDepthMask(GL_TRUE);
  return ok;
}

bool vtkSPTFrame::DrawSingles(int first, int count, bool coverage, bool halves)
{
  vtkOpenGLState* ostate = this->Window->GetState();
  if (coverage)
  {
    // Every segment once, added: no depth test, nothing random.
    if (!this->Ensemble->BeginCoveragePass())
    {
      return false;
    }
    ostate->vtkglDisable(GL_DEPTH_TEST);
    ostate->vtkglDepthMask(GL_FALSE);
    ostate->vtkglEnable(GL_BLEND);
    this->Traverse(PassKind::Coverage, first, 1);
  }
  ostate->vtkglDisable(GL_BLEND);
  ostate->vtkglDepthMask(GL_TRUE);
  ostate->vtkglEnable(GL_DEPTH_TEST);
  ostate->vtkglDepthFunc(GL_LESS);
  for (int r = first; r < first + count; ++r)
  {
    this->Ensemble->BeginPass();
    this->Traverse(PassKind::Single, r, 1);
    this->Ensemble->EndPass(halves && r >= first + count / 2);
  }
  return true;
}

bool vtkSPTFrame::TraverseAdding(
  PassKind kind, int repetition, int inGroup, bool adds, bool secondTarget)
{
  // A compute pass adds in fixed point, and then into the pass's targets.
  const bool computeSums = adds && this->Computes(kind);
  vtkSPTComputeTraversal* compute = this->FrameSettings.Compute;
  if (computeSums)
  {
    if (!compute->PrepareSums(
          this->Window, this->Ensemble->GetPassWidth(), this->Ensemble->GetPassHeight()))
    {
      return false;
    }
    compute->BindSumsImage(SumsImageUnit);
  }
  this->Traverse(kind, repetition, inGroup);
  vtkSPTDepthKeyBuffer::Barrier();
  if (!computeSums)
  {
    return true;
  }
  vtkSPTComputeTraversal::UnbindSumsImage(SumsImageUnit);
  // The color traversal's depth test (against the farthest survivor) is not the sums'.
  vtkOpenGLState* ostate = this->Window->GetState();
  vtkOpenGLState::ScopedglEnableDisable depthTest(ostate, GL_DEPTH_TEST);
  ostate->vtkglDisable(GL_DEPTH_TEST);
  if (!compute->AddSums(this->Window, secondTarget))
  {
    vtkErrorWithObjectMacro(
      this->Reporter, "Could not compile the shader that adds the compute traversal's sums.");
    return false;
  }
  return true;
}

bool vtkSPTFrame::DrawGroups(int first, int count, int perPass, bool coverage, bool halves)
{
  vtkOpenGLState* ostate = this->Window->GetState();
  vtkEnsembleBuffer* ensemble = this->Ensemble;
  // Visibility is the atomic minimum of the keys: no depth buffer. A group shorter than
  // perPass (the last one) still runs all perPass decisions; its extra layers are not read.
  ostate->vtkglDisable(GL_DEPTH_TEST);
  ostate->vtkglDepthMask(GL_FALSE);
  this->DepthKeys->BindImage(DepthKeyImageUnit);
  const bool slabs = this->FrameSettings.DepthSlabs > 1;
  if (slabs)
  {
    // Drawn with the coverage, in the image's first key traversal; kept for its later groups
    // and frames.
    if (coverage)
    {
      this->DepthKeys->ClearSlabs();
    }
    this->DepthKeys->BindSlabImage(SlabDepthsImageUnit);
  }
  bool ok = true;
  for (int r = first; ok && r < first + count; r += perPass)
  {
    const int inGroup = std::min(perPass, first + count - r);
    this->DepthKeys->Clear();
    vtkSPTDepthKeyBuffer::Barrier();
    // The first key traversal also adds up the coverage: it visits every segment anyway.
    const bool withCoverage = coverage && r == first;
    if (withCoverage)
    {
      ok = ensemble->BeginCoveragePass();
      ostate->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
      ostate->vtkglEnable(GL_BLEND);
    }
    else
    {
      ensemble->BeginSumPass(); // written to nothing: the color mask is off
      ostate->vtkglColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
      ostate->vtkglDisable(GL_BLEND);
    }
    const PassKind keysKind = withCoverage ? PassKind::KeysAndCoverage : PassKind::Keys;
    ok = ok && this->TraverseAdding(keysKind, r, inGroup, withCoverage, false);
    if (ok && this->FrameSettings.AfterKeys)
    {
      ok = this->FrameSettings.AfterKeys(this->DepthKeys, slabs && withCoverage);
      vtkSPTDepthKeyBuffer::Barrier();
    }
    if (ok && slabs && withCoverage)
    {
      ok = this->WriteSlabsMeanColor();
    }
    if (ok)
    {
      ensemble->BeginSumPass(halves);
      // The repetitions from first + count / 2 on form the second half.
      const int secondHalfFrom = halves ? std::max(first + count / 2 - r, 0) : inGroup;
      bool culled = false;
      ok = this->PrepareSurvivors(inGroup, secondHalfFrom, culled);
      if (ok)
      {
        ostate->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        ostate->vtkglEnable(GL_BLEND);
        ok = this->TraverseAdding(PassKind::Colors, r, inGroup, true, halves);
      }
      if (culled)
      {
        ostate->vtkglDisable(GL_DEPTH_TEST);
      }
    }
  }
  vtkSPTDepthKeyBuffer::UnbindImage(DepthKeyImageUnit);
  if (slabs)
  {
    vtkSPTDepthKeyBuffer::UnbindImage(SlabDepthsImageUnit);
  }
  ostate->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  ostate->vtkglDisable(GL_BLEND);
  ostate->vtkglDepthMask(GL_TRUE);
  return ok;
}

bool vtkSPTFrame::WriteSlabsMeanColor()
{
  // The coverage's color becomes m * sum(tau) (vtkSPTSlabsMeanFS.glsl): blended, it is read
  // nowhere while it is written.
  vtkOpenGLState* ostate = this->Window->GetState();
  if (!this->Ensemble->BindCoverage())
  {
    vtkErrorWithObjectMacro(this->Reporter, "The coverage of the depth slabs is not allocated.");
    return false;
  }
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunction(ostate);
  ostate->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  ostate->vtkglEnable(GL_BLEND);
  ostate->vtkglBlendFuncSeparate(GL_DST_ALPHA, GL_ZERO, GL_ZERO, GL_ONE);
  const bool written =
    this->DepthKeys->DrawSlabsMeanColor(SlabDepthsImageUnit, this->SlabDefines(PassKind::Colors));
  vtkSPTDepthKeyBuffer::Barrier();
  if (!written)
  {
    vtkErrorWithObjectMacro(this->Reporter,
      "Could not compile the shader of the depth slabs' mean color; the frame is not drawn.");
  }
  return written;
}

bool vtkSPTFrame::PrepareSurvivors(int inGroup, int secondHalfFrom, bool& culled)
{
  // The visibility estimator counts the survivors behind each fragment: sorted keys make that
  // a binary search. Every fragment is rasterized at its cell's nearest vertex, no deeper than
  // its segment's front, but the exit faces of the cells that the near plane cuts lie behind
  // theirs: then no culling.
  const bool sortKeys = this->FrameSettings.Estimator == VISIBILITY_ESTIMATOR;
  const bool cull = !this->NearPlaneCuts;
  culled = false;
  if (!sortKeys && !cull)
  {
    return true;
  }
  vtkOpenGLState* ostate = this->Window->GetState();
  ostate->vtkglColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  ostate->vtkglDisable(GL_BLEND);
  if (cull)
  {
    ostate->vtkglEnable(GL_DEPTH_TEST);
    ostate->vtkglDepthFunc(GL_ALWAYS);
    ostate->vtkglDepthMask(GL_TRUE);
  }
  const bool done = this->DepthKeys->PrepareSurvivors(
    DepthKeyImageUnit, SlabDepthsImageUnit, inGroup, secondHalfFrom, sortKeys);
  vtkSPTDepthKeyBuffer::Barrier();
  if (!cull || !done)
  {
    ostate->vtkglDisable(GL_DEPTH_TEST);
    if (!done && sortKeys)
    {
      vtkErrorWithObjectMacro(this->Reporter,
        "Could not compile the shader that sorts the depth keys; the frame is not drawn.");
    }
    return done || !sortKeys;
  }
  ostate->vtkglDepthFunc(GL_LEQUAL);
  ostate->vtkglDepthMask(GL_FALSE);
  culled = true;
  return true;
}

int vtkSPTFrame::DrawToTarget(int first, int count, int perPass, bool coverage, bool exactCoverage,
  double target, TargetState& state)
{
  TargetSteps steps;
  steps.Draw = [this, perPass](int from, int repetitions, bool withCoverage, bool halves)
  { return this->DrawRepetitions(from, repetitions, perPass, withCoverage, halves); };
  steps.Estimate = [this, exactCoverage](int halfCount, double& estimate)
  {
    estimate = this->Ensemble->EstimateNoise(halfCount, exactCoverage);
    return true;
  };
  return StepToTarget(steps, first, count, perPass, coverage, target, state);
}

int vtkSPTFrame::StepToTarget(const TargetSteps& steps, int first, int count, int perPass,
  bool coverage, double target, TargetState& state)
{
  if (!state.Balanced)
  {
    // A lone repetition went to the first half: its noise is no longer estimated.
    return steps.Draw(first, count, coverage, false) ? count : -1;
  }
  if (state.HalfCount > 0 && state.Estimate <= target)
  {
    return 0; // the image meets the target (or shows nothing)
  }
  int drawn = 0;
  // Each step aims beyond the target. The first of an image aims with the noise per
  // repetition of the images before it (the noise changes little with the view, and any
  // shortfall takes one more step); the first image's first step aims with an assumed noise
  // per repetition, in at most one traversal pair.
  if (state.HalfCount == 0 && state.FirstHalf == 0 && count >= 2)
  {
    state.FirstHalf = state.NoisePerRepetition > 0.0
      ? FirstHalfToTarget(state.NoisePerRepetition, target, StepMargin, count / 2)
      : FirstHalfToTarget(
          FirstImageNoisePerRepetition, target, 1.0, std::max(1, std::min(perPass, count) / 2));
  }
  int half = state.HalfCount > 0 ? RepetitionsToTarget(state.HalfCount, state.Estimate, target)
                                 : state.FirstHalf;
  while (count - drawn >= 2)
  {
    half = std::min(half, (count - drawn) / 2);
    if (!steps.Draw(first + drawn, 2 * half, coverage && drawn == 0, true))
    {
      return -1;
    }
    drawn += 2 * half;
    state.HalfCount += half;
    if (!steps.Estimate(state.HalfCount, state.Estimate))
    {
      return -1;
    }
    if (state.Estimate > 0.0)
    {
      state.NoisePerRepetition = state.Estimate * std::sqrt(2.0 * state.HalfCount);
    }
    if (state.Estimate <= target)
    {
      break; // met, or nothing to see (negative)
    }
    half = RepetitionsToTarget(state.HalfCount, state.Estimate, target);
  }
  if (drawn == 0)
  {
    // Room for one repetition only (the cap or the time budget).
    if (!steps.Draw(first, 1, coverage, false))
    {
      return -1;
    }
    state.Balanced = false;
    state.Estimate = -1.0;
    drawn = 1;
  }
  return drawn;
}

void vtkSPTFrame::SetFrameUniforms(
  vtkShaderProgram* program, int first, int count, bool halves) const
{
  vtkEnsembleBuffer* ensemble = this->Ensemble;
  const float passSize[2] = { float(ensemble->GetPassWidth()), float(ensemble->GetPassHeight()) };
  program->SetUniformi("sceneDepthTexture", ensemble->GetSceneDepthTexture()->GetTextureUnit());
  program->SetUniformi("subpixelLevel", this->FrameSettings.SubpixelLevel);
  program->SetUniform2f("passSizeInPixels", passSize);
  program->SetUniformi("seed", static_cast<int>(this->FrameSettings.Seed));
  // Strata: the repetitions of this draw form one block (progressive renders add blocks),
  // or two, one per half, so that the halves stay independent.
  const int block = halves ? count / 2 : count;
  program->SetUniformi("stratumCount", this->FrameSettings.StratifiedSampling ? block : 0);
  program->SetUniformi("stratumOrigin", first);
  program->SetUniformi("secondHalfStart", halves ? first + block : INT_MAX);
  int bits = 0;
  while ((1 << bits) < block)
  {
    ++bits;
  }
  program->SetUniformi("stratumMask", (1 << bits) - 1);
  program->SetUniformi("stratumShift", std::max((bits + 1) / 2, 1));
  if (program->IsUniformUsed("depthKeys"))
  {
    program->SetUniformi("depthKeys", DepthKeyImageUnit);
  }
  if (program->IsUniformUsed("slabSums"))
  {
    program->SetUniformi("slabSums", SlabDepthsImageUnit);
  }
  if (program->IsUniformUsed("slabStartsLow"))
  {
    program->SetUniform4f("slabStartsLow", this->SlabStarts);
    program->SetUniform4f("slabStartsHigh", this->SlabStarts + 4);
  }
}

void vtkSPTFrame::SetVolumeUniforms(vtkShaderProgram* program, const Volume& volume)
{
  const vtkVolumeViewMatrices& matrices = *volume.Matrices;
  program->SetUniformMatrix4x4("MCVCMatrix", const_cast<float*>(matrices.MCVC));
  program->SetUniformMatrix4x4("VCDCMatrix", const_cast<float*>(matrices.VCDC));
  program->SetUniformMatrix4x4("DCVCMatrix", const_cast<float*>(matrices.DCVC));
  program->SetUniformMatrix3x3("VCMCLinear", const_cast<float*>(matrices.VCMCLinear));
  volume.Table->SetUniforms(program, volume.TableTexture, volume.MaxThickness);
  const int scalarUnit = volume.Buffers->GetScalarTexture()->GetTextureUnit();
  program->SetUniformi("scalars", scalarUnit);
  program->SetUniformi("cellScalars", scalarUnit);
  program->SetUniformi("points", volume.Buffers->GetPointTexture()->GetTextureUnit());
  program->SetUniformi("tetrahedra", volume.Buffers->GetTetrahedronTexture()->GetTextureUnit());
  program->SetUniformi("cellIdOffset", static_cast<int>(volume.CellIdOffset));
  const bool parallel = matrices.ParallelProjection;
  const float eyeVC[4] = { 0.0f, 0.0f, parallel ? 1.0f : 0.0f, parallel ? 0.0f : 1.0f };
  program->SetUniform4f("eyeVC", eyeVC);
}
