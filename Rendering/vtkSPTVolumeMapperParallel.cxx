#include "vtkSPTVolumeMapper.h"
#include "vtkSPTVolumeMapperInternals.h"

#include "vtkAbstractVolumeMapper.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkMultiProcessController.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkRenderer.h"
#include "vtkSPTOpenGL.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include "vtkSPTParallelFrame.h"
#include "vtkSavedGLState.h"
#include "vtkTetrahedralMesh.h"

#include <algorithm>

// The parallel render of vtkSPTVolumeMapper: this rank's piece, combined with the other
// ranks' by reductions (vtkSPTParallelReduction, vtkSPTParallelFrame).

vtkSPTParallelReduction::Settings vtkSPTVolumeMapper::vtkInternals::DescribePiece(
  vtkSPTVolumeMapper* self, vtkRenderer* ren, vtkVolume* vol, RenderTarget& target, size_t shared,
  vtkSPTParallelReduction::Piece& piece)
{
  piece.OpaqueScene = HasOpaqueScene(ren);
  piece.Ready = self->BeginFrame(ren, target) && vol->GetProperty() &&
    self->GetEnsemble()->Prepare(target.Window, target.Width, target.Height, self->SubpixelLevel);
  vtkTetrahedralMesh* mesh = self->GetMesh();
  // An empty piece is not an error: the rank draws nothing and still takes part.
  const bool prepared = piece.Ready && self->PrepareMesh(vol, true);
  piece.HasCells = prepared;
  piece.Ready = piece.Ready &&
    (prepared || (mesh->GetLastError().empty() && mesh->GetNumberOfTetrahedra() == 0));
  if (piece.HasCells)
  {
    int cellFlag = -1;
    vtkDataArray* scalars = vtkAbstractMapper::GetScalars(self->GetDataSetInput(), self->ScalarMode,
      self->ArrayAccessMode, self->ArrayId, self->ArrayName, cellFlag);
    piece.ArrayName = scalars && scalars->GetName() ? scalars->GetName() : "";
    piece.Components = scalars ? scalars->GetNumberOfComponents() : 0;
    piece.CellScalars = mesh->GetCellScalars();
    piece.GlobalIds = !mesh->GetRandomIds().empty();
    std::copy(mesh->GetDataBounds(), mesh->GetDataBounds() + 6, piece.Bounds);
    std::copy(mesh->GetDataScalarRange(), mesh->GetDataScalarRange() + 2, piece.ScalarRange);
    piece.MaxEdgeLength = mesh->GetMaxEdgeLength() * mesh->GetScale();
  }
  const bool atomics = target.Window && vtkSPTDepthKeyBuffer::IsSupported(target.Window);
  return { { "RepetitionLevel", self->RepetitionLevel },
    { "RepetitionsPerPass", self->RepetitionsPerPass }, { "SmallCellSize", self->SmallCellSize },
    { "Seed", self->Seed }, { "SubpixelLevel", self->SubpixelLevel },
    { "Estimator", self->Estimator }, { "ExactCoverage", self->ExactCoverage ? 1 : 0 },
    { "StratifiedSampling", self->StratifiedSampling ? 1 : 0 },
    { "PreIntegrationScalarResolution", self->PreIntegrationScalarResolution },
    { "PreIntegrationThicknessResolution", self->PreIntegrationThicknessResolution },
    { "image width", target.Width }, { "image height", target.Height },
    { "SPT volumes in the renderer", double(shared) },
    { "image load/store (OpenGL 4.4)", atomics ? 1 : 0 } };
}

bool vtkSPTVolumeMapper::vtkInternals::PrepareSharedPiece(vtkSPTVolumeMapper* self,
  vtkRenderer* ren, vtkVolume* vol, RenderTarget& target,
  const vtkSPTParallelReduction::Agreement& agreement, vtkSPTFrame::Volume& out)
{
  // Every piece is normalized and mapped to the table as the whole is.
  vtkTetrahedralMesh* mesh = self->GetMesh();
  mesh->SetSharedFrame(agreement.Bounds, agreement.ScalarRange);
  if (!self->PrepareMesh(vol, true) || !self->ComputeMatrices(ren, vol, this->Matrices))
  {
    return false;
  }
  if (!this->Table->Update(vol->GetProperty(), mesh->GetScalarRange(), agreement.MaxEdgeLength,
        self->PreIntegrationScalarResolution, self->PreIntegrationThicknessResolution))
  {
    vtkErrorWithObjectMacro(self, << this->Table->GetLastError());
    return false;
  }
  if (!this->Buffers->Upload(target.Window, mesh))
  {
    return false;
  }
  out.Buffers = this->Buffers;
  out.Table = this->Table;
  out.TableTexture = this->Table->GetTexture(target.Window);
  out.Matrices = &this->Matrices;
  out.MaxThickness = agreement.MaxEdgeLength / mesh->GetScale();
  return out.TableTexture != nullptr;
}

void vtkSPTVolumeMapper::vtkInternals::RenderParallel(
  vtkSPTVolumeMapper* self, vtkRenderer* ren, vtkVolume* vol, size_t shared)
{
  vtkSPTParallelReduction* reduction = this->Reduction;
  reduction->ResetBytes();
  const bool root = reduction->GetController()->GetLocalProcessId() == 0;
  RenderTarget target;
  vtkSPTParallelReduction::Piece piece;
  const auto settings = this->DescribePiece(self, ren, vol, target, shared, piece);
  vtkSPTParallelReduction::Agreement agreement;
  std::string error;
  bool agreed = reduction->Agree(settings, piece, agreement, error);
  if (agreed && (shared > 1 || settings.back().second == 0.0))
  {
    agreed = false;
    error = shared > 1 ? "Several SPT volumes in one renderer are not combined across ranks"
                       : "Parallel SPT needs image load/store (OpenGL 4.4) on every rank";
  }
  if (!agreed)
  {
    if (root && error != this->ParallelError)
    {
      vtkErrorWithObjectMacro(self, << error << "; nothing is drawn on any rank.");
    }
    this->ParallelError = error;
    return;
  }
  this->ParallelError.clear();
  if (!agreement.GlobalIds && agreement.AnyCells && root && !this->WarnedNoGlobalIds)
  {
    vtkWarningWithObjectMacro(self,
      "The pieces have no global cell ids (cell data GlobalIds): the random numbers follow "
      "each rank's own cell numbering, so the image is not that of one process.");
    this->WarnedNoGlobalIds = true;
  }
  std::vector<vtkSPTFrame::Volume> volumes(1);
  // After the agreement, a rank whose piece fails still takes part, drawing nothing.
  if (!piece.HasCells || !this->PrepareSharedPiece(self, ren, vol, target, agreement, volumes[0]))
  {
    volumes.clear();
  }
  this->DrawParallel(self, ren, vol, target, volumes, agreement);
}

vtkSPTVolumeMapper::vtkInternals::FramePlan vtkSPTVolumeMapper::vtkInternals::PlanParallel(
  vtkSPTVolumeMapper* self, vtkVolume* vol, int perPass, std::vector<double> signature)
{
  FramePlan plan;
  plan.PerPass = perPass;
  const int chosen = self->ChooseRepetitions(vol, self->RepetitionLevel, plan.PerPass);
  int count = chosen;
  // The fewest repetitions of any rank's budget come with its repetitions per traversal: a
  // rank that can afford only single passes chooses fewer than one group.
  int agreed[3] = { self->ContinueAccumulation(std::move(signature), count), chosen, plan.PerPass };
  if (!this->Reduction->AllMinimum(agreed, 3))
  {
    agreed[0] = agreed[1] = 0; // nothing drawn; the frame's last exchange fails too
  }
  plan.First = agreed[0];
  plan.Count = plan.First > 0
    ? std::min(agreed[1], self->MaximumProgressiveRepetitions - plan.First)
    : agreed[1];
  plan.PerPass = agreed[2];
  plan.Cheapest = plan.PerPass == 1 && self->RepetitionsPerPass > 1;
  const bool coverageDrawn = plan.First > 0 && this->CoverageDrawn;
  plan.Coverage = self->ExactCoverage && !coverageDrawn && !plan.Cheapest;
  return plan;
}

void vtkSPTVolumeMapper::vtkInternals::DrawParallel(vtkSPTVolumeMapper* self, vtkRenderer* ren,
  vtkVolume* vol, const RenderTarget& target, const std::vector<vtkSPTFrame::Volume>& volumes,
  const vtkSPTParallelReduction::Agreement& agreement)
{
  vtkOpenGLClearErrorMacro();
  vtkSavedGLState savedState(target.Window->GetState());
  vtkSPTFrame::Settings settings;
  settings.Estimator = self->Estimator;
  settings.StratifiedSampling = self->StratifiedSampling != 0;
  settings.SmallCellSize = self->SmallCellSize;
  settings.SubpixelLevel = self->SubpixelLevel;
  settings.Seed = self->Seed;
  settings.OpaqueScene = agreement.OpaqueScene;
  settings.GlobalIds = agreement.GlobalIds && !volumes.empty();
  // Every rank has the same ensemble size, so the same repetitions per traversal.
  const int perPass = RepetitionsPerTraversal(self->RepetitionsPerPass, self->GetEnsemble());
  const FramePlan plan = this->PlanParallel(self, vol, perPass, Signature(ren, { self }, target));
  if (plan.Cheapest)
  {
    settings.Estimator = SURVIVOR_ESTIMATOR; // one repetition per group, with keys
  }
  this->DrawParallelFrame(self, target, volumes, settings, plan);
  vtkOpenGLCheckErrorMacro("failed after Render");
}

void vtkSPTVolumeMapper::vtkInternals::DrawParallelFrame(vtkSPTVolumeMapper* self,
  const RenderTarget& target, const std::vector<vtkSPTFrame::Volume>& volumes,
  vtkSPTFrame::Settings& settings, const FramePlan& plan)
{
  vtkSPTParallelReduction* reduction = this->Reduction;
  vtkOpenGLState* ostate = target.Window->GetState();
  vtkEnsembleBuffer* ensemble = self->GetEnsemble();
  ostate->PushFramebufferBindings();
  // Every rank starts a new accumulation or none does (the plan is shared).
  const bool started =
    plan.First > 0 || this->StartAccumulation(self, target, self->TargetError > 0.0);
  if (plan.First == 0 && settings.OpaqueScene)
  {
    reduction->ReduceSceneDepth(ensemble->GetSceneDepthTexture());
  }
  vtkSPTParallelFrame frame(
    target.Window, ensemble, this->DepthKeys, volumes, settings, self, reduction);
  if (!started)
  {
    frame.Fail();
  }
  self->StartTiming();
  int drawn = 0;
  if (plan.Count > 0 && self->TargetError > 0.0)
  {
    drawn = frame.DrawToTarget(plan.First, plan.Count, plan.PerPass, plan.Coverage,
      self->ExactCoverage && (this->CoverageDrawn || plan.Coverage), self->TargetError,
      this->Target);
  }
  else if (plan.Count > 0)
  {
    frame.Draw(plan.First, plan.Count, plan.PerPass, plan.Coverage, false);
    drawn = plan.Count;
  }
  // A failure on any rank is known to all at a shared decision: then no rank resolves.
  const bool ok = drawn >= 0 && frame.Finish();
  const double seconds = self->StopTiming();
  self->LastPointCellCount = volumes.empty() ? 0 : frame.GetPointCellCount(0);
  ostate->PopFramebufferBindings();
  if (!ok)
  {
    self->ForgetAccumulation();
    return;
  }
  self->AddRepetitions(drawn, plan.PerPass, seconds);
  this->CoverageDrawn = this->CoverageDrawn || (plan.Coverage && drawn > 0);
  self->EstimatedError = self->TargetError > 0.0 ? this->Target.Estimate : -1.0;
  if (reduction->GetController()->GetLocalProcessId() == 0)
  {
    ensemble->Resolve(target.X, target.Y, self->GetAccumulatedRepetitions(),
      self->ExactCoverage && this->CoverageDrawn);
    ensemble->MarkFootprint(target.X, target.Y);
  }
}
