#include "vtkSPTParallelFrame.h"

#include "vtkMultiProcessController.h"

#include "vtkEnsembleBuffer.h"
#include "vtkSPTDepthKeyBuffer.h"
#include "vtkSPTParallelReduction.h"

#include <algorithm>

vtkSPTParallelFrame::vtkSPTParallelFrame(vtkOpenGLRenderWindow* window, vtkEnsembleBuffer* ensemble,
  vtkSPTDepthKeyBuffer* depthKeys, const std::vector<vtkSPTFrame::Volume>& volumes,
  const vtkSPTFrame::Settings& settings, vtkObject* reporter, vtkSPTParallelReduction* reduction)
  : Ensemble(ensemble)
  , Reduction(reduction)
  , Frame(window, ensemble, depthKeys, volumes,
      WithExchanges(settings, reduction, &this->Exchanges), reporter)
  , Samples(size_t(ensemble->GetPassWidth()) * size_t(ensemble->GetPassHeight()))
{
}

vtkSPTFrame::Settings vtkSPTParallelFrame::WithExchanges(
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

void vtkSPTParallelFrame::Draw(int first, int count, int perPass, bool coverage, bool halves)
{
  const int before = this->Exchanges;
  this->Ok = this->Ok && this->Frame.DrawRepetitions(first, count, perPass, coverage, halves);
  // The exchanges the other ranks make: one per group of `passRepetitions` repetitions, and with
  // depth slabs, the first group's slab sums with the coverage. A rank whose drawing failed (before
  // or within its groups) makes those it missed with nothing kept.
  const int passRepetitions = std::max(1, std::min(perPass, count));
  const int groups = (count + passRepetitions - 1) / passRepetitions;
  const int slabs = this->Frame.GetDepthSlabs();
  for (; this->Exchanges - before < groups; ++this->Exchanges)
  {
    const size_t layers = slabs > 1
      ? size_t(vtkSPTDepthKeyBuffer::GetCompiledRepetitions(passRepetitions)) * size_t(slabs)
      : size_t(passRepetitions);
    this->Reduction->ReduceNothingKept(this->Samples * layers);
    if (slabs > 1 && coverage && this->Exchanges == before)
    {
      this->Reduction->ReduceNoSlabs(
        this->Samples * size_t(vtkSPTDepthKeyBuffer::SlabTerms * slabs));
    }
  }
  this->SumsPending = true;
  this->CoveragePending = this->CoveragePending || coverage;
}

bool vtkSPTParallelFrame::MoveSums(bool halves)
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

bool vtkSPTParallelFrame::Estimate(
  int halfCount, bool exactCoverage, double target, double& estimate, double& median)
{
  this->Ok = this->MoveSums(true) && this->Ok;
  // Rank 0 holds the whole image's halves; every rank restricts its later repetitions to the
  // same tiles, those whose noise rank 0 estimated above the target.
  const bool root = this->Reduction->GetController()->GetLocalProcessId() == 0;
  std::vector<double> tileNoise;
  if (root && this->Ok)
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

int vtkSPTParallelFrame::DrawToTarget(int first, int count, int perPass, bool coverage,
  bool exactCoverage, double target, vtkSPTErrorTarget::State& state)
{
  // The steps of one process, each decided by the shared estimate alone, so that every rank
  // takes them. A rank whose drawing failed goes on taking part; the ranks learn of it at the
  // next estimate.
  vtkSPTErrorTarget::Steps steps;
  steps.Draw = [this, perPass](int from, int repetitions, bool withCoverage, bool halves)
  {
    this->Draw(from, repetitions, perPass, withCoverage, halves);
    this->Ensemble->GetTiles().AddRepetitions(repetitions);
    return true;
  };
  steps.Estimate = [this, exactCoverage, target](int halfCount, double& estimate, double& median)
  { return this->Estimate(halfCount, exactCoverage, target, estimate, median); };
  return vtkSPTErrorTarget::StepToTarget(steps, first, count, perPass, coverage, target, state);
}

bool vtkSPTParallelFrame::Finish()
{
  if (this->SumsPending || this->CoveragePending)
  {
    this->Ok = this->MoveSums(false) && this->Ok;
  }
  return this->Reduction->AllSucceeded(this->Ok);
}
