#include "vtkSPTVolumeMapper.h"

#include "vtkAbstractVolumeMapper.h"
#include "vtkDataSet.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkPropCollection.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkTimerLog.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtk_glew.h"

#include "vtkSPTDepthKeyBuffer.h"
#include "vtkSPTEnsembleBuffer.h"
#include "vtkSPTMeshBuffers.h"
#include "vtkSPTPreIntegrationTable.h"
#include "vtkSPTRenderSetup.h"
#include "vtkSPTViewMatrices.h"

#include "vtkSPTPassColorsFS.h"
#include "vtkSPTPassCoverageFS.h"
#include "vtkSPTPassKeysFS.h"
#include "vtkSPTPassSingleFS.h"
#include "vtkSPTRandom.h"
#include "vtkSPTTetrahedraFS.h"
#include "vtkSPTTetrahedraGS.h"
#include "vtkSPTTetrahedraVS.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

namespace
{
// How one traversal of the tetrahedra writes (see the vtkSPTPass*FS.glsl shaders).
enum class PassKind
{
  Single,           // one repetition, opaque with the depth test
  Keys,             // several repetitions: nearest survivors by atomic minimum of depth keys
  KeysAndCoverage,  // the same, and every segment's optical depth terms (first group)
  Colors,           // several repetitions: the survivors' (or visible segments') colors added
  Coverage,         // every segment's optical depth terms, for the single passes
  NumberOfKinds
};

constexpr int NumberOfPassKinds = static_cast<int>(PassKind::NumberOfKinds);

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

constexpr int DepthKeyImageUnit = 0;

// When the prop last changed in a way that changes what it draws. vtkVolume::GetRedrawMTime()
// of VTK 9.2 dereferences a null transfer function for point scalars of more than four
// components (it asks the property for one per component), so volumes are handled here.
vtkMTimeType RedrawTime(vtkProp* prop)
{
  vtkVolume* volume = vtkVolume::SafeDownCast(prop);
  if (!volume)
  {
    return prop->GetRedrawMTime();
  }
  vtkMTimeType time = volume->GetMTime();
  if (vtkVolumeProperty* property = volume->GetProperty())
  {
    time = std::max(time, property->GetMTime()); // includes its transfer functions
  }
  if (vtkAbstractVolumeMapper* mapper = volume->GetMapper())
  {
    time = std::max(time, mapper->GetMTime());
    if (vtkDataSet* input = mapper->GetDataSetInput())
    {
      time = std::max(time, input->GetMTime());
    }
  }
  return time;
}

// The time budget (AutoAdjustRepetitions). A traversal that draws several repetitions costs
// little more than one that draws one (llvmpipe, 48,000 tetrahedra at 200 x 200: 1 repetition
// 0.58 s, 16 repetitions 1.5 s), so cutting a group short saves little: the budget is spent in
// whole groups, and when not even one group fits, in single-repetition passes, the cheapest
// frame there is (0.36 s there), as many as fit and at least one.
struct RepetitionBudget
{
  double TimePerGroup = 0.0;      // seconds per traversal group of several repetitions
  double TimePerSinglePass = 0.0; // seconds per repetition drawn one per traversal

  // How many repetitions to draw, and how many per traversal (perPass may drop to 1).
  int Choose(double allotted, int level, int& perPass) const
  {
    int most = level;
    if (perPass > 1)
    {
      const int groups = (level + perPass - 1) / perPass;
      if (this->TimePerGroup <= 0.0 || allotted >= groups * this->TimePerGroup)
      {
        return level;
      }
      if (allotted >= this->TimePerGroup)
      {
        return std::min(level, static_cast<int>(allotted / this->TimePerGroup) * perPass);
      }
      most = std::min(level, perPass);
      perPass = 1;
      if (this->TimePerSinglePass <= 0.0)
      {
        return 1; // measured by this frame
      }
    }
    if (this->TimePerSinglePass <= 0.0 || allotted >= most * this->TimePerSinglePass)
    {
      return most;
    }
    return std::max(1, static_cast<int>(allotted / this->TimePerSinglePass));
  }

  void Measure(double seconds, int count, int perPass)
  {
    if (perPass > 1)
    {
      this->TimePerGroup = seconds / ((count + perPass - 1) / perPass);
    }
    else
    {
      this->TimePerSinglePass = seconds / count;
    }
  }
};
}

class vtkSPTVolumeMapper::vtkInternals
{
public:
  vtkNew<vtkSPTMeshBuffers> Mesh;
  vtkNew<vtkSPTPreIntegrationTable> Table;
  vtkNew<vtkSPTEnsembleBuffer> Ensemble;
  vtkNew<vtkSPTDepthKeyBuffer> DepthKeys;
  vtkOpenGLRenderWindow* Context = nullptr;
  vtkSPTRenderSetup Setup;

  vtkSPTViewMatrices Matrices;

  // Progressive refinement: what the accumulated sum was drawn from, and how many repetitions
  // it holds.
  std::vector<double> SumSignature;
  int AccumulatedRepetitions = 0;

  // The error target: repetitions in each half of the ensemble, whether the halves are still
  // of equal size, and the last noise estimate.
  int HalfCount = 0;
  bool Balanced = true;
  double Estimate = -1.0;

  RepetitionBudget Budget;
  bool WarnedNoImageAtomics = false;
  bool CoverageDrawn = false; // the coverage buffer belongs to the accumulated sum
  bool OpaqueScene = false;   // opaque geometry was drawn before the volume

  vtkShaderProgram* ReadyProgram(vtkOpenGLRenderWindow* renWin, bool cellScalars,
    bool nearPlaneCuts, bool sceneDepth, PassKind kind, int repetitionsPerPass, int estimator);
  std::vector<double> Signature(vtkRenderer* ren, vtkSPTVolumeMapper* self, int x, int y,
    int width, int height) const;

  // Draw repetitions [first, first + count) into the ensemble's sum, perPass per traversal;
  // with halves, the second half of them also into the second half's sum (each half a block
  // of strata of its own). With coverage, the exact coverage is drawn too.
  bool DrawRepetitions(vtkSPTVolumeMapper* self, int first, int count, int perPass,
    int estimator, bool coverage, double maxThickness, vtkTextureObject* table,
    bool halves = false);
  // Draw at most count repetitions from first on, in rounds of two equal halves, until the
  // estimated noise meets the mapper's TargetError. Returns how many, or -1 on failure.
  int DrawToTarget(vtkSPTVolumeMapper* self, int first, int count, int perPass, int estimator,
    bool coverage, double maxThickness, vtkTextureObject* table);
  // Keys then colors for each group of perPass repetitions; with coverage, the first key
  // traversal also draws the exact coverage.
  bool DrawRepetitionGroups(int first, int count, int perPass, bool coverage, bool halves,
    const std::function<void(PassKind, int, int)>& traverse);
  void SetCommonUniforms(vtkSPTVolumeMapper* self, vtkShaderProgram* program,
    double maxThickness, vtkTextureObject* table, int first, int count, bool halves);
};

vtkShaderProgram* vtkSPTVolumeMapper::vtkInternals::ReadyProgram(vtkOpenGLRenderWindow* renWin,
  bool cellScalars, bool nearPlaneCuts, bool sceneDepth, PassKind kind, int repetitionsPerPass,
  int estimator)
{
  const char* const passes[NumberOfPassKinds] = { vtkSPTPassSingleFS, vtkSPTPassKeysFS,
    vtkSPTPassKeysFS, vtkSPTPassColorsFS, vtkSPTPassCoverageFS };
  // Both stages: scalars per cell, and the path for cells cut by the near plane, compiled in
  // only while the near plane cuts the mesh's bounds (a fragment stage pays for its branches).
  std::string common = cellScalars ? "#define SPT_CELL_SCALARS\n" : "";
  common += nearPlaneCuts ? "#define SPT_NEAR_PLANE_CUTS\n" : "";
  common += sceneDepth ? "#define SPT_SCENE_DEPTH\n" : "";
  std::string geometry = vtkSPTTetrahedraGS;
  vtkShaderProgram::Substitute(geometry, "//SPT::Defines::Dec", common);

  std::string defines =
    common + "#define SPT_REPETITIONS_PER_PASS " + std::to_string(repetitionsPerPass);
  if (kind == PassKind::KeysAndCoverage)
  {
    defines += "\n#define SPT_WRITE_COVERAGE";
  }
  if (kind == PassKind::Colors && estimator == VISIBILITY_ESTIMATOR)
  {
    defines += "\n#define SPT_VISIBILITY_WEIGHTED";
  }
  // VTK declares GLSL 1.50; image load/store comes as the extension.
  const bool atomics =
    kind == PassKind::Keys || kind == PassKind::KeysAndCoverage || kind == PassKind::Colors;
  std::string fragment = vtkSPTTetrahedraFS;
  vtkShaderProgram::Substitute(fragment, "//SPT::Extensions::Dec",
    atomics ? "#extension GL_ARB_shader_image_load_store : require" : "");
  vtkShaderProgram::Substitute(fragment, "//SPT::Pass::Dec", defines);
  vtkShaderProgram::Substitute(fragment, "//SPT::Random::Impl", vtkSPTRandom);
  vtkShaderProgram::Substitute(fragment, "//SPT::Pass::Impl", passes[static_cast<int>(kind)]);
  return renWin->GetShaderCache()->ReadyShaderProgram(
    vtkSPTTetrahedraVS, fragment.c_str(), geometry.c_str());
}

std::vector<double> vtkSPTVolumeMapper::vtkInternals::Signature(
  vtkRenderer* ren, vtkSPTVolumeMapper* self, int x, int y, int width, int height) const
{
  // Everything that changes the expected image: the matrices (camera, volume transform),
  // the viewport, the input and the table as built, the mapper's settings, and whatever any
  // prop of the renderer would draw differently (opaque geometry bounds the volume).
  std::vector<double> signature(this->Matrices.MCVC, this->Matrices.MCVC + 16);
  signature.insert(signature.end(), this->Matrices.VCDC, this->Matrices.VCDC + 16);
  vtkMTimeType redraw = 0;
  vtkPropCollection* props = ren->GetViewProps();
  vtkCollectionSimpleIterator it;
  props->InitTraversal(it);
  while (vtkProp* prop = props->GetNextProp(it))
  {
    redraw = std::max(redraw, prop->GetVisibility() ? RedrawTime(prop) : 0);
  }
  for (double value : { double(x), double(y), double(width), double(height),
         double(this->Mesh->GetBuildTime()), double(this->Table->GetBuildTime()),
         double(self->GetMTime()), double(redraw) })
  {
    signature.push_back(value);
  }
  return signature;
}

vtkStandardNewMacro(vtkSPTVolumeMapper);

vtkSPTVolumeMapper::vtkSPTVolumeMapper()
  : Internals(new vtkInternals)
{
}

vtkSPTVolumeMapper::~vtkSPTVolumeMapper() = default;

vtkIdType vtkSPTVolumeMapper::GetNumberOfTetrahedra()
{
  return this->Internals->Mesh->GetNumberOfTetrahedra();
}

vtkIdType vtkSPTVolumeMapper::GetNumberOfSkippedCells()
{
  return this->Internals->Mesh->GetNumberOfSkippedCells();
}

vtkIdType vtkSPTVolumeMapper::GetGPUMemorySize()
{
  const vtkInternals& internals = *this->Internals;
  return static_cast<vtkIdType>(internals.Mesh->GetGPUMemorySize() +
    internals.Table->GetGPUMemorySize() + internals.Ensemble->GetGPUMemorySize() +
    internals.DepthKeys->GetGPUMemorySize());
}

void vtkSPTVolumeMapper::Render(vtkRenderer* ren, vtkVolume* vol)
{
  vtkInternals& internals = *this->Internals;
  vtkSPTRenderSetup::Target target;
  if (!vtkSPTRenderSetup::BeginFrame(this, ren, target, internals.Context))
  {
    return;
  }
  vtkOpenGLRenderWindow* renWin = target.Window;
  const int width = target.Width, height = target.Height, x = target.X, y = target.Y;

  // Input and transfer functions: rebuilt only when they changed.
  if (!internals.Setup.UpdateMesh(this, internals.Mesh,
        this->VectorMode == COMPONENT ? this->VectorComponent : -1, true) ||
    !vtkSPTRenderSetup::CheckProperty(this, vol))
  {
    return;
  }
  vtkVolumeProperty* property = vol->GetProperty();
  if (!vtkSPTRenderSetup::ComputeMatrices(this, ren, vol, internals.Mesh, internals.Matrices))
  {
    return;
  }
  const double maxThickness = internals.Mesh->GetMaxEdgeLength();
  if (!internals.Table->Update(property, internals.Mesh->GetScalarRange(),
        maxThickness * internals.Mesh->GetScale(), this->PreIntegrationScalarResolution,
        this->PreIntegrationThicknessResolution))
  {
    vtkErrorMacro(<< internals.Table->GetLastError());
    return;
  }
  if (!internals.Mesh->Upload(renWin))
  {
    return;
  }
  vtkTextureObject* table = internals.Table->GetTexture(renWin);
  if (!table)
  {
    return;
  }

  vtkOpenGLClearErrorMacro();
  vtkOpenGLState* ostate = renWin->GetState();
  vtkSPTRenderSetup::SavedState savedState(ostate);

  vtkSPTEnsembleBuffer* ensemble = internals.Ensemble;
  if (!ensemble->Prepare(renWin, width, height, this->SubpixelLevel))
  {
    return;
  }
  // The survivors of several repetitions per traversal, and every repetition of the visibility
  // estimator, are found with image atomics; without them, one survivor per traversal.
  int perPass = this->RepetitionsPerPass;
  int estimator = this->Estimator;
  if ((perPass > 1 || estimator != SURVIVOR_ESTIMATOR) &&
    !vtkSPTDepthKeyBuffer::IsSupported(renWin))
  {
    if (estimator != SURVIVOR_ESTIMATOR && !internals.WarnedNoImageAtomics)
    {
      vtkWarningMacro("The visibility estimator needs image load/store (OpenGL 4.4); "
                      "drawing with the survivor estimator.");
      internals.WarnedNoImageAtomics = true;
    }
    perPass = 1;
    estimator = SURVIVOR_ESTIMATOR;
  }

  // What to draw: the repetitions that fit the time allotted, added to what is accumulated
  // when refining progressively.
  int count = this->RepetitionLevel;
  if (this->AutoAdjustRepetitions)
  {
    count = internals.Budget.Choose(vol->GetAllocatedRenderTime(), count, perPass);
  }
  // When not even one group of repetitions fits, the cheapest frame: the paper's single
  // passes, one traversal each, unbiased too; the exact coverage waits for a later frame.
  const bool cheapest = perPass == 1 && this->RepetitionsPerPass > 1;
  if (cheapest)
  {
    estimator = SURVIVOR_ESTIMATOR;
  }
  std::vector<double> signature = internals.Signature(ren, this, x, y, width, height);
  int first = 0;
  if (this->ProgressiveRefinement && signature == internals.SumSignature &&
    internals.AccumulatedRepetitions > 0)
  {
    first = internals.AccumulatedRepetitions;
    count = std::min(count, this->MaximumProgressiveRepetitions - first);
  }
  internals.SumSignature = signature;

  ostate->PushFramebufferBindings();
  const bool toTarget = this->TargetError > 0.0;
  if (first == 0)
  {
    internals.OpaqueScene = vtkSPTRenderSetup::HasOpaqueScene(ren);
    ensemble->CaptureSceneDepth(x, y);
    if (!ensemble->SetHalves(toTarget))
    {
      ostate->PopFramebufferBindings();
      internals.SumSignature.clear();
      return;
    }
    ensemble->ClearSum();
    internals.AccumulatedRepetitions = 0;
    internals.CoverageDrawn = false;
    internals.HalfCount = 0;
    internals.Balanced = true;
    internals.Estimate = -1.0;
  }
  // The coverage is additive and needs nothing random: any frame of an accumulation may draw it.
  const bool coverage = this->ExactCoverage && !internals.CoverageDrawn && !cheapest;
  if (count > 0)
  {
    vtkNew<vtkTimerLog> timer;
    timer->StartTimer();
    const int drawn = toTarget
      ? internals.DrawToTarget(
          this, first, count, perPass, estimator, coverage, maxThickness, table)
      : (internals.DrawRepetitions(
           this, first, count, perPass, estimator, coverage, maxThickness, table)
            ? count
            : -1);
    if (drawn < 0)
    {
      ostate->PopFramebufferBindings();
      internals.SumSignature.clear();
      return;
    }
    if (this->AutoAdjustRepetitions && drawn > 0)
    {
      glFinish();
      timer->StopTimer();
      this->TimePerRepetition = timer->GetElapsedTime() / drawn;
      internals.Budget.Measure(timer->GetElapsedTime(), drawn, perPass);
    }
    internals.AccumulatedRepetitions += drawn;
    internals.CoverageDrawn = internals.CoverageDrawn || (coverage && drawn > 0);
  }
  ostate->PopFramebufferBindings();
  this->EstimatedError = toTarget ? internals.Estimate : -1.0;
  this->LastRepetitionCount = internals.AccumulatedRepetitions;
  ensemble->Resolve(
    x, y, internals.AccumulatedRepetitions, this->ExactCoverage && internals.CoverageDrawn);
  vtkOpenGLCheckErrorMacro("failed after Render");
}

bool vtkSPTVolumeMapper::vtkInternals::DrawRepetitions(vtkSPTVolumeMapper* self, int first,
  int count, int perPass, int estimator, bool coverage, double maxThickness,
  vtkTextureObject* table, bool halves)
{
  vtkOpenGLRenderWindow* renWin = this->Context;
  vtkOpenGLState* ostate = renWin->GetState();
  vtkSPTEnsembleBuffer* ensemble = this->Ensemble;
  // The programs this render needs, indexed by PassKind; the others stay null. Groups draw
  // the coverage with their first key traversal; single passes need a traversal of its own.
  const bool single = perPass == 1 && estimator == SURVIVOR_ESTIMATOR;
  const bool needed[NumberOfPassKinds] = { single, !single && (!coverage || count > perPass),
    !single && coverage, !single, single && coverage };
  // A render of fewer repetitions than a group draws only those: the fragment loops are sized
  // by the compiled count.
  const int lanes = std::min(perPass, count);
  vtkShaderProgram* programs[NumberOfPassKinds] = {};
  for (int k = 0; k < NumberOfPassKinds; ++k)
  {
    if (!needed[k])
    {
      continue;
    }
    programs[k] = this->ReadyProgram(renWin, this->Mesh->GetCellScalars(),
      this->Matrices.NearPlaneCutsBounds, this->OpaqueScene, static_cast<PassKind>(k), lanes,
      estimator);
    if (!programs[k])
    {
      vtkErrorWithObjectMacro(self, "Could not compile the SPT shaders.");
      return false;
    }
  }
  if (!single && !this->DepthKeys->Prepare(
                   renWin, ensemble->GetPassWidth(), ensemble->GetPassHeight(), lanes))
  {
    return false;
  }
  ScopedTextures textures({ table, ensemble->GetSceneDepthTexture(),
    this->Mesh->GetScalarTexture(), this->Mesh->GetPointTexture(),
    this->Mesh->GetTetrahedronTexture() });
  for (vtkShaderProgram* program : programs)
  {
    if (program)
    {
      renWin->GetShaderCache()->ReadyShaderProgram(program);
      this->SetCommonUniforms(self, program, maxThickness, table, first, count, halves);
    }
  }

  ostate->vtkglDisable(GL_CULL_FACE);
  ostate->vtkglDisable(GL_SCISSOR_TEST);
  const vtkIdType tetrahedra = this->Mesh->GetNumberOfTetrahedra();
  auto traverse = [&](PassKind kind, int repetition, int inGroup) {
    // The ensemble's accumulation binds its own program between passes; uniforms go to the
    // bound program.
    vtkShaderProgram* program = programs[static_cast<int>(kind)];
    renWin->GetShaderCache()->ReadyShaderProgram(program);
    program->SetUniformi("repetition", repetition);
    program->SetUniformi("repetitionsInGroup", inGroup);
    this->Mesh->Bind(program);
    this->Mesh->Draw(program, 0, tetrahedra);
    this->Mesh->Unbind();
  };
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunction(ostate);
  ostate->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ONE);
  if (!single)
  {
    return this->DrawRepetitionGroups(first, count, lanes, coverage, halves, traverse);
  }
  if (coverage)
  {
    // Every segment once, added: no depth test, nothing random.
    if (!ensemble->BeginCoveragePass())
    {
      return false;
    }
    ostate->vtkglDisable(GL_DEPTH_TEST);
    ostate->vtkglDepthMask(GL_FALSE);
    ostate->vtkglEnable(GL_BLEND);
    traverse(PassKind::Coverage, first, 1);
  }
  ostate->vtkglDisable(GL_BLEND);
  ostate->vtkglDepthMask(GL_TRUE);
  ostate->vtkglEnable(GL_DEPTH_TEST);
  ostate->vtkglDepthFunc(GL_LESS);
  for (int r = first; r < first + count; ++r)
  {
    ensemble->BeginPass();
    traverse(PassKind::Single, r, 1);
    ensemble->EndPass(halves && r >= first + count / 2);
  }
  return true;
}

bool vtkSPTVolumeMapper::vtkInternals::DrawRepetitionGroups(int first, int count, int perPass,
  bool coverage, bool halves, const std::function<void(PassKind, int, int)>& traverse)
{
  vtkOpenGLState* ostate = this->Context->GetState();
  vtkSPTEnsembleBuffer* ensemble = this->Ensemble;
  // Visibility is the atomic minimum of the keys: no depth buffer. A group shorter than
  // perPass (the last one) still runs all perPass decisions; its extra layers are not read.
  ostate->vtkglDisable(GL_DEPTH_TEST);
  ostate->vtkglDepthMask(GL_FALSE);
  this->DepthKeys->BindImage(DepthKeyImageUnit);
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
    if (ok)
    {
      traverse(withCoverage ? PassKind::KeysAndCoverage : PassKind::Keys, r, inGroup);
      vtkSPTDepthKeyBuffer::Barrier();
      ensemble->BeginSumPass(halves);
      ostate->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
      ostate->vtkglEnable(GL_BLEND);
      traverse(PassKind::Colors, r, inGroup);
      vtkSPTDepthKeyBuffer::Barrier();
    }
  }
  this->DepthKeys->UnbindImage(DepthKeyImageUnit);
  ostate->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  ostate->vtkglDisable(GL_BLEND);
  ostate->vtkglDepthMask(GL_TRUE);
  return ok;
}

namespace
{
// The repetitions to add to each half for the noise to fall from `estimate` to `target`, if it
// falls as one over the square root of the repetitions (stratified sampling does better, so
// this rarely falls short): at least one, at most 16 times what each half holds.
int RepetitionsToTarget(int half, double estimate, double target)
{
  const double ratio = estimate / target;
  const double more = std::ceil(half * (ratio * ratio - 1.0));
  return static_cast<int>(std::max(1.0, std::min(more, 16.0 * half)));
}
}

int vtkSPTVolumeMapper::vtkInternals::DrawToTarget(vtkSPTVolumeMapper* self, int first,
  int count, int perPass, int estimator, bool coverage, double maxThickness,
  vtkTextureObject* table)
{
  const double target = self->TargetError;
  if (!this->Balanced)
  {
    // A lone repetition went to the first half: its noise is no longer estimated.
    return this->DrawRepetitions(
             self, first, count, perPass, estimator, coverage, maxThickness, table)
      ? count
      : -1;
  }
  if (this->HalfCount > 0 && this->Estimate <= target)
  {
    return 0; // the image meets the target (or shows nothing)
  }
  const bool exactCoverage = self->ExactCoverage && (this->CoverageDrawn || coverage);
  int drawn = 0;
  int half = this->HalfCount == 0 ? 1 : RepetitionsToTarget(this->HalfCount, this->Estimate, target);
  while (count - drawn >= 2)
  {
    half = std::min(half, (count - drawn) / 2);
    if (!this->DrawRepetitions(self, first + drawn, 2 * half, perPass, estimator,
          coverage && drawn == 0, maxThickness, table, true))
    {
      return -1;
    }
    drawn += 2 * half;
    this->HalfCount += half;
    this->Estimate = this->Ensemble->EstimateNoise(this->HalfCount, exactCoverage);
    if (this->Estimate <= target)
    {
      break; // met, or nothing to see (negative)
    }
    half = RepetitionsToTarget(this->HalfCount, this->Estimate, target);
  }
  if (drawn == 0)
  {
    // Room for one repetition only (the cap or the time budget).
    if (!this->DrawRepetitions(self, first, 1, perPass, estimator, coverage, maxThickness, table))
    {
      return -1;
    }
    this->Balanced = false;
    this->Estimate = -1.0;
    drawn = 1;
  }
  return drawn;
}

void vtkSPTVolumeMapper::vtkInternals::SetCommonUniforms(vtkSPTVolumeMapper* self,
  vtkShaderProgram* program, double maxThickness, vtkTextureObject* table, int first, int count,
  bool halves)
{
  vtkInternals& internals = *this;
  vtkSPTEnsembleBuffer* ensemble = internals.Ensemble;
  const float passSize[2] = { float(ensemble->GetPassWidth()), float(ensemble->GetPassHeight()) };
  program->SetUniformMatrix4x4("MCVCMatrix", internals.Matrices.MCVC);
  program->SetUniformMatrix4x4("VCDCMatrix", internals.Matrices.VCDC);
  program->SetUniformMatrix4x4("DCVCMatrix", internals.Matrices.DCVC);
  program->SetUniformMatrix3x3("VCMCLinear", internals.Matrices.VCMCLinear);
  internals.Table->SetUniforms(program, table, maxThickness);
  program->SetUniformi("sceneDepthTexture", ensemble->GetSceneDepthTexture()->GetTextureUnit());
  program->SetUniformi("subpixelLevel", self->SubpixelLevel);
  program->SetUniform2f("passSizeInPixels", passSize);
  program->SetUniformi("seed", static_cast<int>(self->Seed));
  // Strata: the repetitions of this draw form one block (progressive renders add blocks),
  // or two, one per half, so that the halves stay independent.
  const int block = halves ? count / 2 : count;
  program->SetUniformi("stratumCount", self->StratifiedSampling ? block : 0);
  program->SetUniformi("stratumOrigin", first);
  program->SetUniformi("secondHalfStart", halves ? first + block : VTK_INT_MAX);
  int bits = 0;
  while ((1 << bits) < block)
  {
    ++bits;
  }
  program->SetUniformi("stratumMask", (1 << bits) - 1);
  program->SetUniformi("stratumShift", std::max((bits + 1) / 2, 1));
  const int scalarUnit = internals.Mesh->GetScalarTexture()->GetTextureUnit();
  program->SetUniformi("scalars", scalarUnit);
  program->SetUniformi("cellScalars", scalarUnit);
  program->SetUniformi("points", internals.Mesh->GetPointTexture()->GetTextureUnit());
  program->SetUniformi("tetrahedra", internals.Mesh->GetTetrahedronTexture()->GetTextureUnit());
  const bool parallel = internals.Matrices.ParallelProjection;
  const float eyeVC[4] = { 0.0f, 0.0f, parallel ? 1.0f : 0.0f, parallel ? 0.0f : 1.0f };
  program->SetUniform4f("eyeVC", eyeVC);
  if (program->IsUniformUsed("depthKeys"))
  {
    program->SetUniformi("depthKeys", DepthKeyImageUnit);
  }
}

void vtkSPTVolumeMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  vtkInternals& internals = *this->Internals;
  internals.Mesh->ReleaseGraphicsResources(window);
  internals.Table->ReleaseGraphicsResources(window);
  internals.Ensemble->ReleaseGraphicsResources(window);
  internals.DepthKeys->ReleaseGraphicsResources(window);
  internals.Context = nullptr;
  internals.SumSignature.clear();
  internals.AccumulatedRepetitions = 0;
  internals.HalfCount = 0;
  internals.Balanced = true;
  internals.Estimate = -1.0;
  internals.Budget = RepetitionBudget();
  this->Superclass::ReleaseGraphicsResources(window);
}

void vtkSPTVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RepetitionLevel: " << this->RepetitionLevel << "\n";
  os << indent << "SubpixelLevel: " << this->SubpixelLevel << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "PreIntegrationScalarResolution: " << this->PreIntegrationScalarResolution
     << "\n";
  os << indent << "PreIntegrationThicknessResolution: "
     << this->PreIntegrationThicknessResolution << "\n";
  os << indent << "VectorMode: " << (this->VectorMode == MAGNITUDE ? "Magnitude" : "Component")
     << "\n";
  os << indent << "VectorComponent: " << this->VectorComponent << "\n";
  os << indent << "RepetitionsPerPass: " << this->RepetitionsPerPass << "\n";
  os << indent << "StratifiedSampling: " << (this->StratifiedSampling ? "On" : "Off") << "\n";
  os << indent << "ExactCoverage: " << (this->ExactCoverage ? "On" : "Off") << "\n";
  os << indent << "Estimator: "
     << (this->Estimator == SURVIVOR_ESTIMATOR ? "Survivor" : "Visibility") << "\n";
  os << indent << "ProgressiveRefinement: " << (this->ProgressiveRefinement ? "On" : "Off")
     << "\n";
  os << indent << "MaximumProgressiveRepetitions: " << this->MaximumProgressiveRepetitions
     << "\n";
  os << indent << "AutoAdjustRepetitions: " << (this->AutoAdjustRepetitions ? "On" : "Off")
     << "\n";
  os << indent << "TargetError: " << this->TargetError << "\n";
  os << indent << "EstimatedError: " << this->EstimatedError << "\n";
  os << indent << "LastRepetitionCount: " << this->LastRepetitionCount << "\n";
  os << indent << "TimePerRepetition: " << this->TimePerRepetition << "\n";
  os << indent << "NumberOfTetrahedra: " << this->GetNumberOfTetrahedra() << "\n";
  os << indent << "NumberOfSkippedCells: " << this->GetNumberOfSkippedCells() << "\n";
  os << indent << "GPUMemorySize: " << this->GetGPUMemorySize() << "\n";
}
