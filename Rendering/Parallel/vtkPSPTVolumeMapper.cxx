#include "vtkPSPTVolumeMapper.h"
#include "vtkSPTVolumeMapperInternals.h"

#include "vtkAbstractVolumeMapper.h"
#include "vtkCullerCollection.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkFrustumCoverageCuller.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLLoader.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkRenderer.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include "vtkSPTParallelFrame.h"
#include "vtkSPTParallelReduction.h"
#include "vtkSavedGLState.h"
#include "vtkTetrahedralMesh.h"

#include <algorithm>
#include <string>
#include <vector>

/**
 * The parallel render: this rank's pieces of the renderer's SPT volumes, drawn with their
 * mappers' own buffers, tables and accumulation (vtkSPTVolumeMapper::vtkInternals), combined
 * with the other ranks' by reductions (vtkSPTParallelReduction, vtkSPTParallelFrame).
 */
class vtkPSPTVolumeMapper::vtkInternals
{
public:
  using SPTInternals = vtkSPTVolumeMapper::vtkInternals;
  using FramePlan = SPTInternals::FramePlan;
  using SharedList = vtkSPTVolumeMapper::SharedVolumeList;

  vtkNew<vtkSPTParallelReduction> Reduction;
  bool WarnedCulling = false; // while the renderer has a frustum culler
  std::string ParallelError;  // reported once, until the ranks agree again
  // Rank 0's: the opaque scene of all ranks, composited when the accumulation started, that
  // the volume is resolved over (RGBA bytes per pixel; empty when no rank draws one).
  std::vector<unsigned char> SceneColor;

  // The state of a mapper of the frame between renders.
  static SPTInternals& Of(vtkSPTVolumeMapper* mapper) { return *mapper->Internals; }

  // This rank's pieces of the shared volumes, combined with the other ranks' by reductions.
  void RenderParallel(vtkSPTVolumeMapper* self, vtkRenderer* ren, const SharedList& shared);
  // The ranks agree on each volume's settings and axes and share its table; false on every
  // rank where they do not (the reason in `error`, empty where the image has no pixels).
  bool AgreeOnVolumes(vtkSPTVolumeMapper* self, vtkRenderer* ren, const SharedList& shared,
    RenderTarget& target, std::vector<vtkSPTParallelReduction::Piece>& pieces,
    std::vector<vtkSPTParallelReduction::Agreement>& agreements, std::string& error);
  // Prepare this rank's pieces that have cells, numbered as one process numbers the whole,
  // and draw them with the other ranks'.
  void DrawPieces(vtkSPTVolumeMapper* self, vtkRenderer* ren, const SharedList& shared,
    RenderTarget& target, const std::vector<vtkSPTParallelReduction::Piece>& pieces,
    const std::vector<vtkSPTParallelReduction::Agreement>& agreements);
  // This rank's settings and piece of the frame's first volume, for the ranks to agree on;
  // prepares the mesh and the ensemble.
  static vtkSPTParallelReduction::Settings DescribePiece(vtkSPTVolumeMapper* self, vtkRenderer* ren,
    vtkVolume* vol, RenderTarget& target, size_t shared, vtkSPTParallelReduction::Piece& piece);
  // The same for a later volume of the frame (the `index`th, from 0): what is its own.
  static vtkSPTParallelReduction::Settings DescribeMember(vtkSPTVolumeMapper* mapper,
    vtkRenderer* ren, vtkVolume* vol, size_t index, vtkSPTParallelReduction::Piece& piece);
  // The mesh of one piece, prepared and described.
  static void DescribeMesh(
    vtkSPTVolumeMapper* mapper, vtkVolume* vol, vtkSPTParallelReduction::Piece& piece);
  // The volume's pre-integration table over the agreed axes, its scalar pairs integrated in
  // equal shares by the ranks (`reduction`'s), every rank receiving all. False on every rank,
  // with the reason in `error`, where the ranks' transfer functions differ. Collective.
  static bool ShareTable(vtkSPTVolumeMapper* self, vtkVolume* vol,
    const vtkSPTParallelReduction::Agreement& agreement, vtkSPTParallelReduction* reduction,
    std::string& error);
  // The piece in the ranks' shared frame, ready to draw; false when it has nothing to draw.
  static bool PrepareSharedPiece(vtkSPTVolumeMapper* self, vtkRenderer* ren, vtkVolume* vol,
    RenderTarget& target, const vtkSPTParallelReduction::Agreement& agreement,
    vtkSPTFrame::Volume& out);
  // Plan the frame with the other ranks, draw it, combine the ranks' keys and sums, and
  // resolve on rank 0. `volumes` are this rank's pieces that have cells, of `owners`;
  // `all` are the mappers of every shared volume.
  void DrawParallel(vtkSPTVolumeMapper* self, vtkRenderer* ren, vtkVolume* vol,
    const RenderTarget& target, const std::vector<vtkSPTFrame::Volume>& volumes,
    const std::vector<vtkSPTVolumeMapper*>& owners, const std::vector<vtkSPTVolumeMapper*>& all,
    const vtkSPTParallelReduction::Agreement& agreement);
  void DrawParallelFrame(vtkSPTVolumeMapper* self, const RenderTarget& target,
    const std::vector<vtkSPTFrame::Volume>& volumes, const std::vector<vtkSPTVolumeMapper*>& owners,
    const std::vector<vtkSPTVolumeMapper*>& all, vtkSPTFrame::Settings& settings,
    const FramePlan& plan);
  // A new accumulation where the plan starts one, with the opaque scene of every rank
  // composited; false where it cannot start. A collective call.
  bool StartParallelAccumulation(vtkSPTVolumeMapper* self, const RenderTarget& target,
    const vtkSPTFrame::Settings& settings, const FramePlan& plan);
  // Rank 0: the opaque geometry of every rank, then the volume resolved over it.
  void ResolveOnRoot(vtkSPTVolumeMapper* self, const RenderTarget& target);
  // Makes `agreement` the least of every rank's. A collective call.
  bool AgreeOnPlan(SPTInternals::PlanAgreement& agreement);
};

vtkStandardNewMacro(vtkPSPTVolumeMapper);

vtkPSPTVolumeMapper::vtkPSPTVolumeMapper()
  : Internals(new vtkInternals)
{
}

vtkPSPTVolumeMapper::~vtkPSPTVolumeMapper() = default;

void vtkPSPTVolumeMapper::SetController(vtkMultiProcessController* controller)
{
  if (controller != this->Internals->Reduction->GetController())
  {
    this->Internals->Reduction->SetController(controller);
    if (!controller)
    {
      this->GetMesh()->SetSharedFrame(nullptr, nullptr);
    }
    this->Modified();
  }
}

vtkMultiProcessController* vtkPSPTVolumeMapper::GetController()
{
  return this->Internals->Reduction->GetController();
}

bool vtkPSPTVolumeMapper::RenderAcrossRanks(vtkRenderer* ren, const SharedVolumeList& shared)
{
  if (!this->Internals->Reduction->GetController())
  {
    return false;
  }
  this->WarnOfCulling(ren);
  this->Internals->RenderParallel(this, ren, shared);
  return true;
}

void vtkPSPTVolumeMapper::WarnOfCulling(vtkRenderer* ren)
{
  // Every rank must render every frame: VTK's frustum culler would skip the render of a rank
  // whose piece lies outside the view, and the others would wait for it in the first exchange.
  bool culls = false;
  vtkCullerCollection* cullers = ren->GetCullers();
  vtkCollectionSimpleIterator it;
  cullers->InitTraversal(it);
  while (vtkCuller* culler = cullers->GetNextCuller(it))
  {
    culls = culls || vtkFrustumCoverageCuller::SafeDownCast(culler) != nullptr;
  }
  if (culls && !this->Internals->WarnedCulling)
  {
    vtkWarningMacro("The renderer culls props outside the view (vtkFrustumCoverageCuller): a "
                    "rank whose piece lies outside it would not render, and the others would "
                    "wait for it. Remove the renderer's cullers "
                    "(renderer->GetCullers()->RemoveAllItems()), as ParaView's parallel "
                    "rendering does.");
  }
  this->Internals->WarnedCulling = culls;
}

void vtkPSPTVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Controller: " << this->GetController() << "\n";
}

void vtkPSPTVolumeMapper::vtkInternals::DescribeMesh(
  vtkSPTVolumeMapper* mapper, vtkVolume* vol, vtkSPTParallelReduction::Piece& piece)
{
  vtkTetrahedralMesh* mesh = mapper->GetMesh();
  // An empty piece is not an error: the rank draws nothing and still takes part.
  const bool prepared = piece.Ready && mapper->PrepareMesh(vol, true);
  piece.HasCells = prepared;
  piece.Ready = piece.Ready &&
    (prepared || (mesh->GetLastError().empty() && mesh->GetNumberOfTetrahedra() == 0));
  if (piece.HasCells)
  {
    int cellFlag = -1;
    vtkDataArray* scalars = vtkAbstractMapper::GetScalars(mapper->GetDataSetInput(),
      mapper->ScalarMode, mapper->ArrayAccessMode, mapper->ArrayId, mapper->ArrayName, cellFlag);
    piece.ArrayName = scalars && scalars->GetName() ? scalars->GetName() : "";
    piece.Components = scalars ? scalars->GetNumberOfComponents() : 0;
    piece.CellScalars = mesh->GetCellScalars();
    piece.GlobalIds = !mesh->GetRandomIds().empty();
    std::copy(mesh->GetDataBounds(), mesh->GetDataBounds() + 6, piece.Bounds);
    std::copy(mesh->GetDataScalarRange(), mesh->GetDataScalarRange() + 2, piece.ScalarRange);
    piece.MaxEdgeLength = mesh->GetMaxEdgeLength() * mesh->GetScale();
    piece.Tetrahedra = double(mesh->GetNumberOfTetrahedra());
  }
}

vtkSPTParallelReduction::Settings vtkPSPTVolumeMapper::vtkInternals::DescribePiece(
  vtkSPTVolumeMapper* self, vtkRenderer* ren, vtkVolume* vol, RenderTarget& target, size_t shared,
  vtkSPTParallelReduction::Piece& piece)
{
  piece.OpaqueScene = HasOpaqueScene(ren);
  piece.Ready = self->BeginFrame(ren, target) && vol->GetProperty() &&
    self->GetEnsemble()->Prepare(target.Window, target.Width, target.Height, self->SubpixelLevel);
  piece.EmptyImage = target.Width <= 0 || target.Height <= 0;
  DescribeMesh(self, vol, piece);
  const bool atomics = target.Window && vtkSPTDepthKeyBuffer::IsSupported(target.Window);
  if (target.Window)
  {
    Of(self).ColorBits = vtkOpenGLLoader::DrawColorBits(); // where the image will be resolved
  }
  return { { "RepetitionLevel", self->RepetitionLevel },
    { "RepetitionsPerPass", self->RepetitionsPerPass }, { "SmallCellSize", self->SmallCellSize },
    { "Seed", self->Seed }, { "SubpixelLevel", self->SubpixelLevel },
    { "Estimator", self->Estimator }, { "ExactCoverage", self->ExactCoverage ? 1 : 0 },
    { "DepthSlabs", self->DepthSlabs }, { "StratifiedSampling", self->StratifiedSampling ? 1 : 0 },
    { "ReuseNoiseEstimate", self->ReuseNoiseEstimate ? 1 : 0 },
    { "TargetError", self->TargetError },
    { "bits per color channel of the image", Of(self).ColorBits },
    { "ProgressiveRefinement", self->ProgressiveRefinement ? 1 : 0 },
    { "MaximumProgressiveRepetitions", self->MaximumProgressiveRepetitions },
    { "PreIntegrationScalarResolution", self->PreIntegrationScalarResolution },
    { "PreIntegrationThicknessResolution", self->PreIntegrationThicknessResolution },
    { "image width", target.Width }, { "image height", target.Height },
    { "SPT volumes in the renderer", double(shared) },
    { "image load/store (OpenGL 4.4)", atomics ? 1 : 0 } };
}

vtkSPTParallelReduction::Settings vtkPSPTVolumeMapper::vtkInternals::DescribeMember(
  vtkSPTVolumeMapper* mapper, vtkRenderer* ren, vtkVolume* vol, size_t index,
  vtkSPTParallelReduction::Piece& piece)
{
  // The frame's sampling settings are the first volume's; a later volume brings its piece and
  // its table.
  RenderTarget own;
  piece.Ready = mapper->BeginFrame(ren, own) && vol->GetProperty();
  DescribeMesh(mapper, vol, piece);
  const std::string volume = "SPT volume " + std::to_string(index + 1) + "'s ";
  return { { volume + "PreIntegrationScalarResolution", mapper->PreIntegrationScalarResolution },
    { volume + "PreIntegrationThicknessResolution", mapper->PreIntegrationThicknessResolution } };
}

bool vtkPSPTVolumeMapper::vtkInternals::ShareTable(vtkSPTVolumeMapper* self, vtkVolume* vol,
  const vtkSPTParallelReduction::Agreement& agreement, vtkSPTParallelReduction* reduction,
  std::string& error)
{
  // The axes PrepareSharedPiece() gives the table: the pieces' shared scalar range and longest
  // edge. A rank that cannot prepare reports why when it prepares its piece.
  bool pending = false;
  const bool prepared =
    Of(self).Table->Prepare(vol->GetProperty(), agreement.ScalarRange, agreement.MaxEdgeLength,
      self->PreIntegrationScalarResolution, self->PreIntegrationThicknessResolution, pending);
  return reduction->ShareTable(Of(self).Table, prepared, pending, error);
}

bool vtkPSPTVolumeMapper::vtkInternals::PrepareSharedPiece(vtkSPTVolumeMapper* self,
  vtkRenderer* ren, vtkVolume* vol, RenderTarget& target,
  const vtkSPTParallelReduction::Agreement& agreement, vtkSPTFrame::Volume& out)
{
  // Every piece is normalized and mapped to the table as the whole is.
  vtkTetrahedralMesh* mesh = self->GetMesh();
  mesh->SetSharedFrame(agreement.Bounds, agreement.ScalarRange);
  SPTInternals& spt = Of(self);
  if (!self->PrepareMesh(vol, true) || !self->ComputeMatrices(ren, vol, spt.Matrices))
  {
    return false;
  }
  return spt.Upload(self, vol, target.Window, agreement.MaxEdgeLength,
    agreement.MaxEdgeLength / mesh->GetScale(), out);
}

void vtkPSPTVolumeMapper::vtkInternals::RenderParallel(
  vtkSPTVolumeMapper* self, vtkRenderer* ren, const SharedList& shared)
{
  vtkSPTParallelReduction* reduction = this->Reduction;
  reduction->ResetBytes();
  const bool root = reduction->GetController()->GetLocalProcessId() == 0;
  RenderTarget target;
  std::vector<vtkSPTParallelReduction::Piece> pieces(shared.size());
  std::vector<vtkSPTParallelReduction::Agreement> agreements(shared.size());
  std::string error;
  const bool agreed = this->AgreeOnVolumes(self, ren, shared, target, pieces, agreements, error);
  if (!agreed && error.empty())
  {
    return; // an image with no pixels on every rank: nothing to draw
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
  this->DrawPieces(self, ren, shared, target, pieces, agreements);
}

bool vtkPSPTVolumeMapper::vtkInternals::AgreeOnVolumes(vtkSPTVolumeMapper* self, vtkRenderer* ren,
  const SharedList& shared, RenderTarget& target,
  std::vector<vtkSPTParallelReduction::Piece>& pieces,
  std::vector<vtkSPTParallelReduction::Agreement>& agreements, std::string& error)
{
  // The ranks agree on the first volume, whose settings include the number of volumes, then
  // on each later one: every rank makes the same collective calls, or stops at the same one.
  vtkSPTParallelReduction* reduction = this->Reduction;
  bool agreed = true;
  for (size_t v = 0; v < shared.size() && agreed; ++v)
  {
    vtkVolume* vol = shared[v].first;
    const auto settings = v == 0
      ? this->DescribePiece(self, ren, vol, target, shared.size(), pieces[0])
      : DescribeMember(shared[v].second, ren, vol, v, pieces[v]);
    agreed = reduction->Agree(settings, pieces[v], agreements[v], error);
    if (!agreed && v > 0)
    {
      error = "SPT volume " + std::to_string(v + 1) + " of the renderer: " + error;
    }
    else if (agreed && v == 0 && settings.back().second == 0.0)
    {
      agreed = false;
      error = "Parallel SPT needs image load/store (OpenGL 4.4) on every rank";
    }
  }
  // Each volume's table, in shares: every rank takes part (the agreement is the same on all),
  // whether its piece has cells or not.
  for (size_t v = 0; v < shared.size() && agreed; ++v)
  {
    vtkSPTVolumeMapper* mapper = shared[v].second;
    if (agreements[v].AnyCells &&
      !ShareTable(mapper, shared[v].first, agreements[v], reduction, error))
    {
      agreed = false;
      error = v > 0 ? "SPT volume " + std::to_string(v + 1) + " of the renderer: " + error : error;
    }
  }
  return agreed;
}

void vtkPSPTVolumeMapper::vtkInternals::DrawPieces(vtkSPTVolumeMapper* self, vtkRenderer* ren,
  const SharedList& shared, RenderTarget& target,
  const std::vector<vtkSPTParallelReduction::Piece>& pieces,
  const std::vector<vtkSPTParallelReduction::Agreement>& agreements)
{
  const bool root = this->Reduction->GetController()->GetLocalProcessId() == 0;
  // What the frame draws: each rank's pieces that have cells. The volumes' cells are numbered
  // one after another by their counts over all ranks, as one process numbers the whole.
  vtkSPTParallelReduction::Agreement frame = agreements[0];
  std::vector<vtkSPTFrame::Volume> volumes;
  std::vector<vtkSPTVolumeMapper*> owners;
  std::vector<vtkSPTVolumeMapper*> all;
  double cellIds = 0.0;
  for (size_t v = 0; v < shared.size(); ++v)
  {
    vtkSPTVolumeMapper* mapper = shared[v].second;
    all.push_back(mapper);
    if (agreements[v].AnyCells)
    {
      frame.GlobalIds =
        frame.AnyCells ? frame.GlobalIds && agreements[v].GlobalIds : agreements[v].GlobalIds;
      frame.AnyCells = true;
    }
    // After the agreement, a rank whose piece fails still takes part, drawing nothing of it.
    vtkSPTFrame::Volume volume;
    if (pieces[v].HasCells &&
      PrepareSharedPiece(mapper, ren, shared[v].first, target, agreements[v], volume))
    {
      volume.CellIdOffset = static_cast<unsigned int>(cellIds);
      volumes.push_back(volume);
      owners.push_back(mapper);
    }
    cellIds += agreements[v].Tetrahedra;
  }
  if (!frame.GlobalIds && frame.AnyCells && root && !Of(self).WarnedNoGlobalIds)
  {
    vtkWarningWithObjectMacro(self,
      "The pieces have no global cell ids (cell data GlobalIds): the random numbers follow "
      "each rank's own cell numbering, so the image is not that of one process.");
    Of(self).WarnedNoGlobalIds = true;
  }
  this->DrawParallel(self, ren, shared.front().first, target, volumes, owners, all, frame);
}

bool vtkPSPTVolumeMapper::vtkInternals::AgreeOnPlan(SPTInternals::PlanAgreement& agreement)
{
  // The terms in the order of the aggregate, for the reduction.
  int terms[] = { agreement.First, agreement.Count, agreement.PerPass, agreement.SameImage,
    agreement.Pairs };
  const bool agreed = this->Reduction->AllMinimum(terms, 5);
  agreement = { terms[0], terms[1], terms[2], terms[3], terms[4] };
  return agreed;
}

void vtkPSPTVolumeMapper::vtkInternals::DrawParallel(vtkSPTVolumeMapper* self, vtkRenderer* ren,
  vtkVolume* vol, const RenderTarget& target, const std::vector<vtkSPTFrame::Volume>& volumes,
  const std::vector<vtkSPTVolumeMapper*>& owners, const std::vector<vtkSPTVolumeMapper*>& all,
  const vtkSPTParallelReduction::Agreement& agreement)
{
  vtkOpenGLClearErrorMacro();
  vtkSavedGLState savedState(target.Window->GetState());
  // Every rank has the same ensemble size, so the same repetitions per traversal; the keys
  // that the ranks exchange stay within the fixed budget.
  vtkSPTFrame::Settings settings = Of(self).FrameSettings(
    self, target.Window, agreement.OpaqueScene, agreement.GlobalIds && !volumes.empty());
  const int perPass = SPTInternals::RepetitionsPerTraversal(self->RepetitionsPerPass,
    self->GetEnsemble(), settings.DepthSlabs, SPTInternals::FixedKeyBudget);
  const FramePlan plan =
    Of(self).Plan(self, vol, perPass, SPTInternals::Signature(ren, all, target), settings,
      [this](SPTInternals::PlanAgreement& terms) { return this->AgreeOnPlan(terms); });
  this->DrawParallelFrame(self, target, volumes, owners, all, settings, plan);
  vtkOpenGLCheckErrorMacro("failed after Render");
}

bool vtkPSPTVolumeMapper::vtkInternals::StartParallelAccumulation(vtkSPTVolumeMapper* self,
  const RenderTarget& target, const vtkSPTFrame::Settings& settings, const FramePlan& plan)
{
  vtkSPTParallelReduction* reduction = this->Reduction;
  vtkEnsembleBuffer* ensemble = self->GetEnsemble();
  const bool root = reduction->GetController()->GetLocalProcessId() == 0;
  // Every rank starts a new accumulation or none does (the plan is shared). Opaque geometry
  // on any rank hides the volume on every rank (the global minimum of the scene depth), and
  // rank 0 resolves the volume over every rank's geometry.
  if (plan.First == 0)
  {
    this->SceneColor.clear();
    if (settings.OpaqueScene)
    {
      this->SceneColor = ensemble->ReadSceneColor(target.X, target.Y);
    }
  }
  const bool started = plan.First > 0 ||
    Of(self).StartAccumulation(self, target, self->TargetError > 0.0, plan.SameImage);
  if (plan.First == 0 && settings.OpaqueScene &&
    (!reduction->CompositeScene(ensemble->GetSceneDepthTexture(), this->SceneColor) || !root))
  {
    this->SceneColor.clear();
  }
  return started;
}

void vtkPSPTVolumeMapper::vtkInternals::DrawParallelFrame(vtkSPTVolumeMapper* self,
  const RenderTarget& target, const std::vector<vtkSPTFrame::Volume>& volumes,
  const std::vector<vtkSPTVolumeMapper*>& owners, const std::vector<vtkSPTVolumeMapper*>& all,
  vtkSPTFrame::Settings& settings, const FramePlan& plan)
{
  vtkSPTParallelReduction* reduction = this->Reduction;
  vtkOpenGLState* ostate = target.Window->GetState();
  vtkEnsembleBuffer* ensemble = self->GetEnsemble();
  const bool root = reduction->GetController()->GetLocalProcessId() == 0;
  ostate->PushFramebufferBindings();
  SPTInternals& spt = Of(self);
  const bool started = this->StartParallelAccumulation(self, target, settings, plan);
  vtkSPTParallelFrame frame(
    target.Window, ensemble, spt.DepthKeys, volumes, settings, self, reduction);
  if (!started)
  {
    frame.Fail();
  }
  self->StartTiming();
  int drawn = 0;
  if (plan.Count > 0 && self->TargetError > 0.0)
  {
    drawn = frame.DrawToTarget(plan.First, plan.Count, plan.PerPass, plan.Coverage,
      self->ExactCoverage && (spt.CoverageDrawn || plan.Coverage), spt.NoiseTarget(self),
      spt.Target);
  }
  else if (plan.Count > 0)
  {
    frame.Draw(plan.First, plan.Count, plan.PerPass, plan.Coverage, false);
    drawn = plan.Count;
  }
  // A failure on any rank is known to all at a shared decision: then no rank resolves.
  const bool ok = drawn >= 0 && frame.Finish();
  const double seconds = self->StopTiming();
  ostate->PopFramebufferBindings();
  if (!ok)
  {
    self->ForgetAccumulation();
    return;
  }
  self->AddRepetitions(drawn, plan.PerPass, plan.Kind, seconds);
  spt.CoverageDrawn = spt.CoverageDrawn || (plan.Coverage && drawn > 0);
  spt.Report(self, all, owners, frame, static_cast<vtkIdType>(reduction->GetBytes()));
  if (root)
  {
    this->ResolveOnRoot(self, target);
  }
}

void vtkPSPTVolumeMapper::vtkInternals::ResolveOnRoot(
  vtkSPTVolumeMapper* self, const RenderTarget& target)
{
  vtkEnsembleBuffer* ensemble = self->GetEnsemble();
  if (!this->SceneColor.empty() && !ensemble->DrawScene(target.X, target.Y, this->SceneColor))
  {
    vtkErrorWithObjectMacro(self,
      "Could not draw the opaque geometry of the other ranks: the "
      "volume is shown over rank 0's alone.");
  }
  ensemble->Resolve(target.X, target.Y, self->GetAccumulatedRepetitions(),
    self->ExactCoverage && Of(self).CoverageDrawn);
  ensemble->MarkFootprint(target.X, target.Y);
}
