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

#include "vtkEnsembleBuffer.h"
#include "vtkSPTParallelReduction.h"
#include "vtkSavedGLState.h"
#include "vtkTetrahedralMesh.h"

#include <algorithm>
#include <string>
#include <vector>

namespace
{
/**
 * One rank's part of an SPT image drawn by several ranks: this rank's piece drawn as
 * vtkSPTFrame draws it, with the exchanges that combine it with the other ranks'
 * (vtkSPTParallelReduction): the depth keys after each key traversal, and the sums, which move
 * to rank 0 whenever the frame needs the whole image's (rank 0 holds the global sums, the
 * others nothing, between steps and between frames, so that a progressive render adds to
 * them).
 *
 * With an error target, the steps are those of vtkSPTFrame::DrawToTarget(), each followed by
 * the noise estimate of the whole image on rank 0 (EstimateNoise()), which every rank follows:
 * every rank draws the same repetitions and makes the same exchanges. A rank whose drawing fails
 * goes on taking part in every exchange with nothing kept and nothing added, and the ranks learn of
 * it at the next shared decision: no rank waits for another. Every drawing call is collective.
 */
class vtkSPTParallelFrame : public vtkSPTFrame
{
public:
  /// As vtkSPTFrame's; `settings.AfterKeys` is replaced by the key exchange.
  vtkSPTParallelFrame(vtkOpenGLRenderWindow* window, vtkEnsembleBuffer* ensemble,
    vtkSPTDepthKeyBuffer* depthKeys, const std::vector<vtkSPTFrame::Volume>& volumes,
    const vtkSPTFrame::Settings& settings, vtkObject* reporter, vtkSPTParallelReduction* reduction)
    : vtkSPTFrame(window, ensemble, depthKeys, volumes,
        WithExchanges(settings, reduction, &this->Exchanges), reporter)
    , Ensemble(ensemble)
    , Reduction(reduction)
    , Samples(size_t(ensemble->GetPassWidth()) * size_t(ensemble->GetPassHeight()))
  {
  }

  /// This rank could not start the accumulation: it draws nothing and still takes part.
  void Fail() { this->Ok = false; }

  /// vtkSPTFrame::DrawRepetitions() with the key exchanges of every group. True: a failure is
  /// known to all ranks at the next estimate or at Finish().
  bool DrawRepetitions(
    int first, int count, int perPass, bool coverage, bool halves = false) override
  {
    const int before = this->Exchanges;
    this->Ok =
      this->Ok && this->vtkSPTFrame::DrawRepetitions(first, count, perPass, coverage, halves);
    // The exchanges the other ranks make: one per group of `passRepetitions` repetitions, and
    // with depth slabs, the first group's slab sums with the coverage. A rank whose drawing
    // failed (before or within its groups) makes those it missed with nothing kept.
    const int passRepetitions = std::max(1, std::min(perPass, count));
    const int groups = (count + passRepetitions - 1) / passRepetitions;
    const int slabs = this->GetDepthSlabs();
    for (; this->Exchanges - before < groups; ++this->Exchanges)
    {
      const size_t layers = slabs > 1
        ? size_t(vtkSPTDepthKeyBuffer::GetCompiledRepetitions(passRepetitions)) * size_t(slabs)
        : size_t(passRepetitions);
      this->Reduction->ReduceKeys(nullptr, this->Samples * layers);
      if (slabs > 1 && coverage && this->Exchanges == before)
      {
        this->Reduction->ReduceSlabs(
          nullptr, this->Samples * size_t(vtkSPTDepthKeyBuffer::SlabTerms * slabs));
      }
    }
    this->SumsPending = true;
    this->CoveragePending = this->CoveragePending || coverage;
    return true;
  }

  /// Move what was drawn since the last move to rank 0; true on every rank when every rank
  /// drew everything (`drawn` on this one).
  bool Finish(bool drawn) override
  {
    this->Ok = this->Ok && drawn;
    if (this->SumsPending || this->CoveragePending)
    {
      this->Ok = this->MoveSums(false) && this->Ok;
    }
    return this->Reduction->AllSucceeded(this->Ok);
  }

protected:
  // Move the halves to rank 0, estimate there, and share; false when any rank failed.
  bool EstimateNoise(
    int halfCount, bool exactCoverage, double target, double& estimate, double& median) override
  {
    this->Ok = this->MoveSums(true) && this->Ok;
    // Rank 0 holds the whole image's halves; every rank restricts its later repetitions to the
    // same tiles, those whose noise rank 0 estimated above the target.
    std::vector<double> tileNoise;
    if (this->Reduction->GetController()->GetLocalProcessId() == 0 && this->Ok)
    {
      tileNoise = this->Ensemble->EstimateTileNoise(halfCount, exactCoverage);
    }
    if (!this->Reduction->ShareTileNoise(this->Ok, tileNoise))
    {
      return false;
    }
    std::vector<bool> active;
    estimate = vtkSPTErrorTarget::ChooseTiles(tileNoise, target, active, median);
    this->Ok = (estimate <= target || this->Ensemble->RestrictToTiles(active)) && this->Ok;
    return true;
  }

private:
  static vtkSPTFrame::Settings WithExchanges(
    vtkSPTFrame::Settings settings, vtkSPTParallelReduction* reduction, int* exchanges)
  {
    settings.AlwaysKeys = true; // the keys are what the ranks combine
    settings.AfterKeys = [reduction, exchanges](vtkSPTDepthKeyBuffer* keys, bool slabsDrawn)
    {
      ++*exchanges;
      const bool reduced = reduction->ReduceKeys(keys);
      return (!slabsDrawn || reduction->ReduceSlabs(keys)) && reduced;
    };
    return settings;
  }

  // Move the sums (and the second half's, and the coverage if drawn since) to rank 0.
  bool MoveSums(bool halves)
  {
    std::vector<vtkTextureObject*> textures{ this->Ensemble->GetSumTexture() };
    if (halves)
    {
      textures.push_back(this->Ensemble->GetSecondHalfTexture());
    }
    if (this->CoveragePending)
    {
      textures.push_back(this->Ensemble->GetCoverageTexture());
    }
    this->SumsPending = false;
    this->CoveragePending = false;
    return this->Reduction->ReduceSums(textures, this->Samples);
  }

  vtkEnsembleBuffer* Ensemble;
  vtkSPTParallelReduction* Reduction;
  size_t Samples;
  int Exchanges = 0;            // key exchanges made (counted by the base's AfterKeys)
  bool Ok = true;               // this rank drew everything so far
  bool SumsPending = false;     // repetitions drawn since the sums last moved
  bool CoveragePending = false; // the coverage drawn since the sums last moved
};
}

/**
 * The parallel render: this rank's pieces of the renderer's SPT volumes, drawn with their
 * mappers' own buffers, tables and accumulation (vtkSPTVolumeMapper::vtkInternals), combined
 * with the other ranks' by reductions (vtkSPTParallelReduction, vtkSPTParallelFrame above).
 */
class vtkPSPTVolumeMapper::vtkInternals
{
public:
  using SPTInternals = vtkSPTVolumeMapper::vtkInternals;
  using FramePlan = SPTInternals::FramePlan;
  using Piece = vtkSPTParallelReduction::Piece;
  using Agreement = vtkSPTParallelReduction::Agreement;

  vtkNew<vtkSPTParallelReduction> Reduction;
  bool WarnedCulling = false; // while the renderer has a frustum culler
  std::string ParallelError;  // reported once, until the ranks agree again
  // Rank 0's: the opaque scene of all ranks, composited when the accumulation started, that
  // the volume is resolved over (RGBA bytes per pixel; empty when no rank draws one).
  std::vector<unsigned char> SceneColor;

  // The state of a mapper of the frame between renders.
  static SPTInternals& Of(vtkSPTVolumeMapper* mapper) { return *mapper->Internals; }

  bool IsRoot() const { return this->Reduction->GetController()->GetLocalProcessId() == 0; }

  // Warn once when a parallel render's renderer may cull this rank's piece.
  void WarnOfCulling(vtkPSPTVolumeMapper* self, vtkRenderer* ren)
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
    if (culls && !this->WarnedCulling)
    {
      vtkWarningWithObjectMacro(self,
        "The renderer culls props outside the view (vtkFrustumCoverageCuller): a rank whose "
        "piece lies outside it would not render, and the others would wait for it. Remove the "
        "renderer's cullers (renderer->GetCullers()->RemoveAllItems()), as ParaView's parallel "
        "rendering does.");
    }
    this->WarnedCulling = culls;
  }

  // This rank's pieces of the shared volumes, combined with the other ranks' by reductions.
  void RenderParallel(vtkSPTVolumeMapper* self, vtkRenderer* ren, const SharedVolumeList& shared)
  {
    this->Reduction->ResetBytes();
    RenderTarget target;
    std::vector<Piece> pieces(shared.size());
    std::vector<Agreement> agreements(shared.size());
    std::string error;
    const bool agreed = this->AgreeOnVolumes(ren, shared, target, pieces, agreements, error);
    if (!agreed && error.empty())
    {
      return; // an image with no pixels on every rank: nothing to draw
    }
    if (!agreed)
    {
      if (this->IsRoot() && error != this->ParallelError)
      {
        vtkErrorWithObjectMacro(self, << error << "; nothing is drawn on any rank.");
      }
      this->ParallelError = error;
      return;
    }
    this->ParallelError.clear();
    this->DrawPieces(self, ren, shared, target, pieces, agreements);
  }

  // The ranks agree on each volume's settings and axes and share its table; false on every
  // rank where they do not (the reason in `error`, empty where the image has no pixels).
  bool AgreeOnVolumes(vtkRenderer* ren, const SharedVolumeList& shared, RenderTarget& target,
    std::vector<Piece>& pieces, std::vector<Agreement>& agreements, std::string& error)
  {
    // The ranks agree on the first volume, whose settings include the number of volumes, then
    // on each later one: every rank makes the same collective calls, or stops at the same one.
    for (size_t v = 0; v < shared.size(); ++v)
    {
      RenderTarget own;
      const auto settings = Describe(
        shared[v].second, ren, shared[v].first, v, shared.size(), v == 0 ? target : own, pieces[v]);
      bool agreed = this->Reduction->Agree(settings, pieces[v], agreements[v], error);
      if (agreed && v == 0 && settings.back().second == 0.0)
      {
        agreed = false;
        error = "Parallel SPT needs image load/store (OpenGL 4.4) on every rank";
      }
      // The volume's table, in shares: every rank takes part (the agreement is the same on
      // all), whether its piece has cells or not.
      agreed = agreed &&
        (!agreements[v].AnyCells ||
          ShareTable(shared[v].second, shared[v].first, agreements[v], this->Reduction, error));
      if (!agreed && v > 0)
      {
        error = "SPT volume " + std::to_string(v + 1) + " of the renderer: " + error;
      }
      if (!agreed)
      {
        return false;
      }
    }
    return true;
  }

  // This rank's settings and piece of the `index`th volume of the frame (of `shared`), for the
  // ranks to agree on; prepares the mesh. The frame's sampling settings are the first volume's
  // (which prepares the ensemble for `target`); a later volume brings its piece and its table.
  static vtkSPTParallelReduction::Settings Describe(vtkSPTVolumeMapper* self, vtkRenderer* ren,
    vtkVolume* vol, size_t index, size_t shared, RenderTarget& target, Piece& piece)
  {
    piece.Ready = self->BeginFrame(ren, target) && vol->GetProperty() &&
      (index > 0 ||
        self->GetEnsemble()->Prepare(
          target.Window, target.Width, target.Height, self->SubpixelLevel));
    DescribeMesh(self, vol, piece);
    if (index > 0)
    {
      const std::string volume = "SPT volume " + std::to_string(index + 1) + "'s ";
      return { { volume + "PreIntegrationScalarResolution", self->PreIntegrationScalarResolution },
        { volume + "PreIntegrationThicknessResolution", self->PreIntegrationThicknessResolution } };
    }
    piece.OpaqueScene = HasOpaqueScene(ren);
    piece.EmptyImage = target.Width <= 0 || target.Height <= 0;
    const bool atomics = target.Window && vtkSPTDepthKeyBuffer::IsSupported(target.Window);
    if (target.Window)
    {
      Of(self).ColorBits = vtkOpenGLLoader::DrawColorBits(); // where the image is resolved
    }
    return { { "RepetitionLevel", self->RepetitionLevel },
      { "RepetitionsPerPass", self->RepetitionsPerPass }, { "SmallCellSize", self->SmallCellSize },
      { "Seed", self->Seed }, { "SubpixelLevel", self->SubpixelLevel },
      { "Estimator", self->Estimator }, { "ExactCoverage", self->ExactCoverage ? 1 : 0 },
      { "DepthSlabs", self->DepthSlabs },
      { "StratifiedSampling", self->StratifiedSampling ? 1 : 0 },
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

  // The mesh of one piece, prepared and described.
  static void DescribeMesh(vtkSPTVolumeMapper* mapper, vtkVolume* vol, Piece& piece)
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

  // The volume's pre-integration table over the agreed axes (the pieces' shared scalar range
  // and longest edge), its scalar pairs integrated in equal shares by the ranks, every rank
  // receiving all. False on every rank, with the reason in `error`, where the ranks' transfer
  // functions differ. A rank that cannot prepare reports why when it prepares its piece.
  // Collective.
  static bool ShareTable(vtkSPTVolumeMapper* self, vtkVolume* vol, const Agreement& agreement,
    vtkSPTParallelReduction* reduction, std::string& error)
  {
    bool pending = false;
    const bool prepared =
      Of(self).Table->Prepare(vol->GetProperty(), agreement.ScalarRange, agreement.MaxEdgeLength,
        self->PreIntegrationScalarResolution, self->PreIntegrationThicknessResolution, pending);
    return reduction->ShareTable(Of(self).Table, prepared, pending, error);
  }

  // Prepare this rank's pieces that have cells, numbered as one process numbers the whole,
  // and draw them with the other ranks'.
  void DrawPieces(vtkSPTVolumeMapper* self, vtkRenderer* ren, const SharedVolumeList& shared,
    const RenderTarget& target, const std::vector<Piece>& pieces,
    const std::vector<Agreement>& agreements)
  {
    // What the frame draws: each rank's pieces that have cells. The volumes' cells are numbered
    // one after another by their counts over all ranks, as one process numbers the whole.
    Agreement frame = agreements[0];
    std::vector<vtkSPTFrame::Volume> volumes;
    std::vector<vtkSPTVolumeMapper*> owners;
    std::vector<vtkSPTVolumeMapper*> all;
    double cellIds = 0.0;
    for (size_t v = 0; v < shared.size(); ++v)
    {
      vtkSPTVolumeMapper* mapper = shared[v].second;
      const Agreement& agreement = agreements[v];
      all.push_back(mapper);
      if (agreement.AnyCells)
      {
        frame.GlobalIds =
          frame.AnyCells ? frame.GlobalIds && agreement.GlobalIds : agreement.GlobalIds;
        frame.AnyCells = true;
      }
      // After the agreement, a rank whose piece fails still takes part, drawing nothing of it.
      // Every piece is normalized and mapped to the table as the whole is.
      vtkSPTFrame::Volume volume;
      if (pieces[v].HasCells &&
        SPTInternals::PrepareVolume(mapper, ren, shared[v].first, target.Window, volume,
          agreement.Bounds, agreement.ScalarRange, agreement.MaxEdgeLength))
      {
        volume.CellIdOffset = static_cast<unsigned int>(cellIds);
        volumes.push_back(volume);
        owners.push_back(mapper);
      }
      cellIds += agreement.Tetrahedra;
    }
    if (!frame.GlobalIds && frame.AnyCells && this->IsRoot() && !Of(self).WarnedNoGlobalIds)
    {
      vtkWarningWithObjectMacro(self,
        "The pieces have no global cell ids (cell data GlobalIds): the random numbers follow "
        "each rank's own cell numbering, so the image is not that of one process.");
      Of(self).WarnedNoGlobalIds = true;
    }
    this->DrawParallel(self, ren, shared.front().first, target, volumes, owners, all, frame);
  }

  // Plan the frame with the other ranks, draw it, combine the ranks' keys and sums, and
  // resolve on rank 0. `volumes` are this rank's pieces that have cells, of `owners`;
  // `all` are the mappers of every shared volume.
  void DrawParallel(vtkSPTVolumeMapper* self, vtkRenderer* ren, vtkVolume* vol,
    const RenderTarget& target, const std::vector<vtkSPTFrame::Volume>& volumes,
    const std::vector<vtkSPTVolumeMapper*>& owners, const std::vector<vtkSPTVolumeMapper*>& all,
    const Agreement& agreement)
  {
    vtkOpenGLClearErrorMacro();
    vtkOpenGLState* ostate = target.Window->GetState();
    vtkSavedGLState savedState(ostate);
    SPTInternals& spt = Of(self);
    // Every rank has the same ensemble size, so the same repetitions per traversal; the keys
    // that the ranks exchange stay within the fixed budget.
    vtkSPTFrame::Settings settings = spt.FrameSettings(
      self, target.Window, agreement.OpaqueScene, agreement.GlobalIds && !volumes.empty());
    const int perPass = SPTInternals::RepetitionsPerTraversal(self->RepetitionsPerPass,
      self->GetEnsemble(), settings.DepthSlabs, SPTInternals::FixedKeyBudget);
    const FramePlan plan =
      spt.Plan(self, vol, perPass, SPTInternals::Signature(ren, all, target), settings,
        [this](SPTInternals::PlanAgreement& planned)
        {
          // The terms in the order of the aggregate, for the reduction.
          int terms[] = { planned.First, planned.Count, planned.PerPass, planned.SameImage,
            planned.Pairs };
          const bool agreed = this->Reduction->AllMinimum(terms, 5);
          planned = { terms[0], terms[1], terms[2], terms[3], terms[4] };
          return agreed;
        });
    ostate->PushFramebufferBindings();
    const bool started = this->StartParallelAccumulation(self, target, settings, plan);
    vtkSPTParallelFrame frame(
      target.Window, self->GetEnsemble(), spt.DepthKeys, volumes, settings, self, this->Reduction);
    if (!started)
    {
      frame.Fail();
    }
    // A failure on any rank is known to all at a shared decision: then no rank resolves.
    const bool drawn = spt.DrawTimed(self, frame, plan);
    ostate->PopFramebufferBindings();
    if (drawn)
    {
      spt.Report(self, all, owners, frame, static_cast<vtkIdType>(this->Reduction->GetBytes()));
      if (this->IsRoot())
      {
        this->ResolveOnRoot(self, target);
      }
    }
    vtkOpenGLCheckErrorMacro("failed after Render");
  }

  // A new accumulation where the plan starts one, with the opaque scene of every rank
  // composited; false where it cannot start. A collective call.
  bool StartParallelAccumulation(vtkSPTVolumeMapper* self, const RenderTarget& target,
    const vtkSPTFrame::Settings& settings, const FramePlan& plan)
  {
    vtkEnsembleBuffer* ensemble = self->GetEnsemble();
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
      (!this->Reduction->CompositeScene(ensemble->GetSceneDepthTexture(), this->SceneColor) ||
        !this->IsRoot()))
    {
      this->SceneColor.clear();
    }
    return started;
  }

  // Rank 0: the opaque geometry of every rank, then the volume resolved over it.
  void ResolveOnRoot(vtkSPTVolumeMapper* self, const RenderTarget& target)
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
  this->Internals->WarnOfCulling(this, ren);
  this->Internals->RenderParallel(this, ren, shared);
  return true;
}

void vtkPSPTVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Controller: " << this->GetController() << "\n";
}
