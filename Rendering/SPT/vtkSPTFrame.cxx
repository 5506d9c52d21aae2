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

#include <algorithm>
#include <climits>
#include <cmath>
#include <initializer_list>
#include <memory>
#include <string>

namespace
{
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

// The scissor box, the stencil test and the stencil's write mask, which the passes of an image
// restricted to some tiles set (vtkEnsembleTiles), as they were, on every way out.
class ScopedTileTests
{
public:
  explicit ScopedTileTests(vtkOpenGLState* state)
    : State(state)
    , Box(state)
    , Stencil(state, GL_STENCIL_TEST)
  {
    glGetIntegerv(GL_STENCIL_WRITEMASK, &this->WriteMask);
  }
  ~ScopedTileTests() { this->State->vtkglStencilMask(static_cast<unsigned int>(this->WriteMask)); }
  ScopedTileTests(const ScopedTileTests&) = delete;
  ScopedTileTests& operator=(const ScopedTileTests&) = delete;

private:
  vtkOpenGLState* State;
  vtkOpenGLState::ScopedglScissor Box;
  vtkOpenGLState::ScopedglEnableDisable Stencil;
  GLint WriteMask = 0;
};

// The passes over the keys limited to the footprint (vtkSPTFrame::Footprint), until it goes out
// of scope.
class ScopedFootprint
{
public:
  ScopedFootprint(vtkOpenGLState* state, const int footprint[4])
    : Box(state)
    , Test(state, GL_SCISSOR_TEST)
  {
    state->vtkglEnable(GL_SCISSOR_TEST);
    state->vtkglScissor(footprint[0], footprint[1], footprint[2], footprint[3]);
  }

private:
  vtkOpenGLState::ScopedglScissor Box;
  vtkOpenGLState::ScopedglEnableDisable Test;
};
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
    this->ClippingPlanes = this->ClippingPlanes || volume.Matrices->ClippingPlaneCount > 0;
  }
  const int mostSlabs = MaximumDepthSlabs; // a value: std::min takes references
  this->FrameSettings.DepthSlabs = std::max(1, std::min(this->FrameSettings.DepthSlabs, mostSlabs));
  this->ChooseSmallCells();
  this->ChooseSlabs();
}

void vtkSPTFrame::Traverse(PassKind kind, int repetition, int inGroup)
{
  for (size_t v = 0; v < this->Volumes.size(); ++v)
  {
    // The smallest cells in a compute pass, the other small cells as points, then triangles
    // for the others.
    for (const Primitive primitive :
      { Primitive::Computed, Primitive::Points, Primitive::Outlines })
    {
      this->TraversePrimitive(kind, v, primitive, repetition, inGroup);
    }
  }
}

void vtkSPTFrame::TraversePrimitive(
  PassKind kind, size_t v, Primitive primitive, int repetition, int inGroup)
{
  const Volume& volume = this->Volumes[v];
  const bool compute = primitive == Primitive::Computed;
  const bool points = primitive != Primitive::Outlines;
  if (compute ? !this->Computes(kind, v) : !this->Rasterizes(kind, v, points))
  {
    return;
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
  ScopedTextures textures(
    { volume.TableTexture, volume.Buffers->GetScalarTexture(), volume.Buffers->GetPointTexture(),
      volume.Buffers->GetTetrahedronTexture(), volume.Buffers->GetMeshIndexTexture() });
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
    program->SetUniformi("survivorDepth", this->Ensemble->GetPassDepthTexture()->GetTextureUnit());
  }
  program->SetUniformi("repetition", repetition);
  program->SetUniformi("repetitionsInGroup", inGroup);
  program->SetUniformi("meshIndices", volume.Buffers->GetMeshIndexTexture()->GetTextureUnit());
  if (compute)
  {
    this->DispatchComputed(program, kind, v);
  }
  else
  {
    this->DrawTetrahedra(
      volume, program, points, this->FirstRasterizedPoint(kind, v), this->PointCellCounts[v]);
  }
}

void vtkSPTFrame::DispatchComputed(vtkShaderProgram* program, PassKind kind, size_t v)
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
  const bool single = oneAtATime && !this->FrameSettings.VisibilityEstimator;
  const bool depthSurvivors =
    oneAtATime && this->FrameSettings.VisibilityEstimator && !halves && !this->ComputesMostCells();
  const bool keys = !single && !depthSurvivors;
  const bool needed[NumberOfPassKinds] = { single || depthSurvivors,
    keys && (!coverage || count > perPass), keys && coverage, keys, single && coverage,
    depthSurvivors && (!coverage || count > 1), depthSurvivors && coverage };
  // A render of fewer repetitions than a group draws only those: the fragment loops run over
  // the group's count, and the programs are compiled for the next power of two.
  const int passRepetitions = std::min(perPass, count);
  // Active before the frame's uniforms name its unit.
  ScopedTextures sceneDepth({ this->Ensemble->GetSceneDepthTexture() });
  if (!this->ReadyPrograms(needed, vtkSPTDepthKeyBuffer::GetCompiledRepetitions(passRepetitions),
        first, count, halves) ||
    (keys &&
      !this->DepthKeys->Prepare(this->Window, this->Ensemble->GetPassWidth(),
        this->Ensemble->GetPassHeight(), passRepetitions, this->FrameSettings.DepthSlabs)))
  {
    return false;
  }
  ostate->vtkglDisable(GL_CULL_FACE);
  ostate->vtkglDisable(GL_SCISSOR_TEST);
  ScopedTileTests tileTests(ostate);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunction(ostate);
  ostate->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ONE);
  if (depthSurvivors)
  {
    return this->DrawDepthSurvivors(first, count, coverage);
  }
  return single ? this->DrawSingles(first, count, coverage, halves)
                : this->DrawGroups(first, count, passRepetitions, coverage, halves);
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
  vtkSPTDepthKeyBuffer::UnbindImage(SumsImageUnit);
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

void vtkSPTFrame::ChooseFootprint()
{
  const int size[2] = { this->Ensemble->GetPassWidth(), this->Ensemble->GetPassHeight() };
  double ndc[4] = { 1.0, -1.0, 1.0, -1.0 };
  for (const Volume& volume : this->Volumes)
  {
    const double* bounds = volume.Matrices->ScreenBounds;
    for (int axis = 0; axis < 2; ++axis)
    {
      ndc[2 * axis] = std::min(ndc[2 * axis], bounds[2 * axis]);
      ndc[2 * axis + 1] = std::max(ndc[2 * axis + 1], bounds[2 * axis + 1]);
    }
  }
  const bool whole = this->NearPlaneCuts || this->FrameSettings.AfterKeys;
  // Only the tiles drawn, where the error target restricted the image to some.
  int tiles[4];
  this->Ensemble->GetTiles().GetSampleBox(tiles);
  for (int axis = 0; axis < 2; ++axis)
  {
    // A sample is drawn where its center, (i + 0.5) / size in [0, 1], lies in a primitive.
    const double low = 0.5 * (ndc[2 * axis] + 1.0) * size[axis];
    const double high = 0.5 * (ndc[2 * axis + 1] + 1.0) * size[axis];
    const int from = whole ? 0 : std::max(0, static_cast<int>(std::floor(low)) - 1);
    const int to = whole ? size[axis] : std::min(size[axis], static_cast<int>(std::ceil(high)) + 1);
    const int first = std::max(from, tiles[axis]);
    const int last = std::min(to, tiles[axis] + tiles[2 + axis]);
    this->Footprint[axis] = first;
    this->Footprint[2 + axis] = std::max(0, last - first);
  }
}

bool vtkSPTFrame::DrawGroups(int first, int count, int perPass, bool coverage, bool halves)
{
  vtkOpenGLState* ostate = this->Window->GetState();
  this->ChooseFootprint();
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
    // The first key traversal also adds up the coverage: it visits every segment anyway.
    const bool withCoverage = coverage && r == first;
    ok = this->DrawGroupKeys(r, inGroup, withCoverage);
    if (ok)
    {
      // The repetitions from first + count / 2 on form the second half.
      const int secondHalfFrom = halves ? std::max(first + count / 2 - r, 0) : inGroup;
      ok = this->DrawGroupColors(r, inGroup, secondHalfFrom, halves);
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

bool vtkSPTFrame::DrawGroupKeys(int r, int inGroup, bool withCoverage)
{
  vtkOpenGLState* ostate = this->Window->GetState();
  vtkEnsembleBuffer* ensemble = this->Ensemble;
  const bool slabs = this->FrameSettings.DepthSlabs > 1;
  bool ok = true;
  this->DepthKeys->Clear(this->Footprint);
  vtkSPTDepthKeyBuffer::Barrier();
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
  return ok;
}

bool vtkSPTFrame::DrawGroupColors(int r, int inGroup, int secondHalfFrom, bool halves)
{
  vtkOpenGLState* ostate = this->Window->GetState();
  this->Ensemble->BeginSumPass(halves);
  bool culled = false;
  bool ok = this->PrepareSurvivors(inGroup, secondHalfFrom, culled);
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
  bool written = false;
  {
    ScopedFootprint footprint(ostate, this->Footprint);
    written =
      this->DepthKeys->DrawSlabsMeanColor(SlabDepthsImageUnit, this->SlabDefines(PassKind::Colors));
  }
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
  const bool sortKeys = this->FrameSettings.VisibilityEstimator;
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
  bool done = false;
  {
    ScopedFootprint footprint(ostate, this->Footprint);
    done = this->DepthKeys->PrepareSurvivors(
      DepthKeyImageUnit, SlabDepthsImageUnit, inGroup, secondHalfFrom, sortKeys);
  }
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
  double target, vtkSPTErrorTarget::State& state)
{
  vtkSPTErrorTarget::Steps steps;
  steps.Draw = [this, perPass](int from, int repetitions, bool withCoverage, bool halves)
  {
    const bool drawn = this->DrawRepetitions(from, repetitions, perPass, withCoverage, halves);
    this->Ensemble->GetTiles().AddRepetitions(repetitions);
    return drawn;
  };
  steps.Estimate = [this, exactCoverage, target](int halfCount, double& estimate, double& median)
  { return this->EstimateNoise(halfCount, exactCoverage, target, estimate, median); };
  return vtkSPTErrorTarget::StepToTarget(steps, first, count, perPass, coverage, target, state);
}

bool vtkSPTFrame::EstimateNoise(
  int halfCount, bool exactCoverage, double target, double& estimate, double& median)
{
  std::vector<bool> active;
  estimate = vtkSPTErrorTarget::ChooseTiles(
    this->Ensemble->EstimateTileNoise(halfCount, exactCoverage), target, active, median);
  return estimate <= target || this->Ensemble->RestrictToTiles(active);
}
