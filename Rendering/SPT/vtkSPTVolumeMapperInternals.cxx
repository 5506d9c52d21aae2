// vtkSPTVolumeMapper::vtkInternals, what a frame draws: its settings; its repetitions per
// traversal and depth slabs, as the context, the image size and the depth keys' memory allow;
// how many repetitions, from the time budget, the progressive accumulation and the error
// target's cap; and whether it draws the exact coverage. The parallel render
// (vtkPSPTVolumeMapper) plans with these too, its ranks agreeing on the fewest.
#include "vtkSPTVolumeMapperInternals.h"
#include "vtkSPTVolumeMapper.h"

#include "vtkOpenGLLoader.h"
#include "vtkOpenGLRenderWindow.h"

#include "vtkEnsembleBuffer.h"
#include "vtkSPTComputeTraversal.h"
#include "vtkSPTDepthKeyBuffer.h"

#include <vtksys/SystemInformation.hxx>

#include <algorithm>
#include <sstream>
#include <utility>
#include <vector>

namespace
{
// The host's physical memory in bytes; 0 where unknown.
size_t HostMemoryBytes()
{
  vtksys::SystemInformation host;
  const long long kib = host.GetHostMemoryTotal();
  return kib > 0 ? static_cast<size_t>(kib) * 1024 : 0;
}
}

int vtkSPTVolumeMapper::vtkInternals::RepetitionsPerTraversal(
  int asked, const vtkEnsembleBuffer* ensemble, int slabs, size_t budget)
{
  // A traversal of many repetitions costs little more than one of a single repetition, so at
  // the sizes where memory allows, a frame of 256 repetitions is one pair of traversals
  // instead of sixteen. Depth slabs share the keys' memory.
  const size_t samples =
    std::max<size_t>(1, size_t(ensemble->GetPassWidth()) * size_t(ensemble->GetPassHeight()));
  const size_t perSlab = budget / (4 * samples * size_t(std::max(slabs, 1)));
  const int fits = static_cast<int>(std::min<size_t>(perSlab, 256));
  return std::min(asked, std::max(fits, 16 / std::max(slabs, 1)));
}

size_t vtkSPTVolumeMapper::vtkInternals::DepthKeyBudget(vtkOpenGLRenderWindow* renWin)
{
  // An eighth of the memory the device has free, between the fixed budget and 1 GiB (256
  // repetitions at 1024 x 1024): a software rasterizer's device is the host's memory; a GPU
  // says what it has free where its driver offers a query (NVIDIA's, AMD's); else the fixed
  // budget, which any OpenGL 4.4 device holds.
  if (this->KeyBudget == 0)
  {
    const size_t free = vtkSPTComputeTraversal::IsSoftwareRasterizer(renWin)
      ? HostMemoryBytes()
      : vtkOpenGLLoader::FreeDeviceMemoryBytes();
    const size_t fixed = FixedKeyBudget; // a value: std::max takes references
    this->KeyBudget = std::min(std::max(free / 8, fixed), size_t(1) << 30);
  }
  return this->KeyBudget;
}

int vtkSPTVolumeMapper::vtkInternals::DepthSlabsThatFit(
  int asked, const vtkEnsembleBuffer* ensemble)
{
  // The slabs' sums take 16 bytes per slab and sample, besides the keys: at most 128 MB, so
  // that a large image draws fewer slabs (the same expectation, more noise) rather than fail.
  constexpr size_t budget = size_t(128) << 20;
  const size_t samples =
    std::max<size_t>(1, size_t(ensemble->GetPassWidth()) * size_t(ensemble->GetPassHeight()));
  const size_t perSlab = 4 * size_t(vtkSPTDepthKeyBuffer::SlabTerms) * samples;
  return static_cast<int>(std::max<size_t>(1, std::min<size_t>(size_t(asked), budget / perSlab)));
}

int vtkSPTVolumeMapper::vtkInternals::ChooseTraversal(
  vtkSPTVolumeMapper* self, vtkOpenGLRenderWindow* renWin, vtkSPTFrame::Settings& settings)
{
  // The survivors of several repetitions per traversal, and every repetition of the visibility
  // estimator, are found with image atomics; without them, one survivor per traversal.
  if ((self->RepetitionsPerPass > 1 || self->Estimator != SURVIVOR_ESTIMATOR ||
        self->DepthSlabs > 1) &&
    !vtkSPTDepthKeyBuffer::IsSupported(renWin))
  {
    if (self->Estimator != SURVIVOR_ESTIMATOR && !this->WarnedNoImageAtomics)
    {
      vtkWarningWithObjectMacro(self,
        "The visibility estimator needs image load/store (OpenGL 4.4); drawing with the "
        "survivor estimator.");
      this->WarnedNoImageAtomics = true;
    }
    if (self->DepthSlabs > 1 && !this->WarnedNoSlabs)
    {
      vtkWarningWithObjectMacro(
        self, "Depth slabs need image load/store (OpenGL 4.4); drawing without them.");
      this->WarnedNoSlabs = true;
    }
    settings.VisibilityEstimator = false;
    settings.DepthSlabs = 1;
    return 1;
  }
  // The depth keys are a 3D texture of (repetition, sample): for a larger pass, the depth test
  // finds each repetition's survivor instead, one repetition per traversal pair.
  const vtkEnsembleBuffer* ensemble = self->GetEnsemble();
  const int samples = std::max(ensemble->GetPassWidth(), ensemble->GetPassHeight());
  const int maxSize = vtkOpenGLLoader::Max3DTextureSize();
  const bool keysFit = samples <= maxSize;
  if (!keysFit && !this->WarnedLargeImage)
  {
    ReportLargeImage(self, maxSize);
  }
  this->WarnedLargeImage = !keysFit;
  if (!keysFit && (self->TargetError > 0.0 || self->DepthSlabs > 1))
  {
    return 0;
  }
  settings.DepthSlabs = keysFit ? settings.DepthSlabs : 1;
  return keysFit ? RepetitionsPerTraversal(self->RepetitionsPerPass, ensemble, settings.DepthSlabs,
                     this->DepthKeyBudget(renWin))
                 : 1;
}

void vtkSPTVolumeMapper::vtkInternals::ReportLargeImage(vtkSPTVolumeMapper* self, int maxSize)
{
  const vtkEnsembleBuffer* ensemble = self->GetEnsemble();
  std::ostringstream message;
  message << "The image is " << ensemble->GetPassWidth() << " x " << ensemble->GetPassHeight()
          << " samples, more than this OpenGL's 3D textures hold per side (" << maxSize
          << ", GL_MAX_3D_TEXTURE_SIZE), which the depth keys of several repetitions need";
  if (self->TargetError > 0.0 || self->DepthSlabs > 1)
  {
    const char* setting = self->TargetError > 0.0 ? "TargetError" : "DepthSlabs";
    const char* off = self->TargetError > 0.0 ? "0" : "1";
    vtkErrorWithObjectMacro(self, << message.str() << ". " << setting
                                  << " needs them: nothing is drawn. Render a smaller image "
                                     "(the viewport times SubpixelLevel), or set "
                                  << setting << " to " << off << ".");
  }
  else
  {
    vtkWarningWithObjectMacro(self, << message.str()
                                    << ": drawing one repetition per traversal pair (the "
                                       "same image, more traversals).");
  }
}

vtkSPTVolumeMapper::vtkInternals::FramePlan vtkSPTVolumeMapper::vtkInternals::Plan(
  vtkSPTVolumeMapper* self, vtkVolume* vol, int perPass, std::vector<double> signature,
  vtkSPTFrame::Settings& settings, const AgreeOnPlan& agree)
{
  // When not even one group of repetitions fits, the visibility estimator one repetition at a
  // time (a pair of traversals each, the coverage drawn with the colors; across ranks with
  // keys, which the ranks combine, where one process finds the survivor by depth: the same
  // image). When not even one pair fits, the cheapest frame: the paper's single passes, one
  // traversal each, unbiased too; the exact coverage waits for a later frame.
  FramePlan plan;
  plan.Kind = settings.VisibilityEstimator ? Traversal::Pair : Traversal::Single;
  PlanAgreement terms;
  terms.Count = self->ChooseRepetitions(vol, self->RepetitionLevel, perPass, plan.Kind);
  terms.PerPass = perPass;
  terms.SameImage = self->IsLastSignature(signature) ? 1 : 0;
  terms.Pairs = plan.Kind == Traversal::Single ? 0 : 1;
  int continued = terms.Count;
  terms.First = self->ContinueAccumulation(std::move(signature), continued);
  if (agree && !agree(terms))
  {
    terms.First = terms.Count = 0; // nothing drawn; a parallel frame's last exchange fails too
  }
  plan.First = terms.First;
  plan.Count = plan.First > 0
    ? std::min(terms.Count, self->MaximumProgressiveRepetitions - plan.First)
    : terms.Count;
  plan.PerPass = terms.PerPass;
  plan.SameImage = terms.SameImage != 0;
  plan.Kind = plan.PerPass > 1 ? Traversal::Group
    : terms.Pairs != 0         ? Traversal::Pair
                               : Traversal::Single;
  plan.Cheapest = plan.Kind == Traversal::Single && self->RepetitionsPerPass > 1;
  // The coverage is additive and needs nothing random: any frame of an accumulation may draw
  // it, and a new accumulation starts without it. Depth slabs weight their colors by the
  // slabs' optical depths, which the coverage traversal adds up: drawn for them even without
  // the exact coverage.
  const bool coverageDrawn = plan.First > 0 && this->CoverageDrawn;
  plan.Coverage = (self->ExactCoverage || self->DepthSlabs > 1) && !coverageDrawn && !plan.Cheapest;
  if (plan.Cheapest)
  {
    settings.VisibilityEstimator = false;
    settings.DepthSlabs = 1;
  }
  return plan;
}

vtkSPTFrame::Settings vtkSPTVolumeMapper::vtkInternals::FrameSettings(
  vtkSPTVolumeMapper* self, vtkOpenGLRenderWindow* renWin, bool opaqueScene, bool globalIds)
{
  const vtkEnsembleBuffer* ensemble = self->GetEnsemble();
  vtkSPTFrame::Settings settings;
  settings.VisibilityEstimator = self->Estimator == VISIBILITY_ESTIMATOR;
  settings.DepthSlabs = DepthSlabsThatFit(self->DepthSlabs, ensemble);
  settings.StratifiedSampling = self->StratifiedSampling != 0;
  settings.SmallCellSize = self->SmallCellSize;
  settings.SubpixelLevel = self->SubpixelLevel;
  settings.Seed = self->Seed;
  settings.OpaqueScene = opaqueScene;
  settings.GlobalIds = globalIds;
  const bool everyPoint = self->ComputeTraversal == COMPUTE_TRAVERSAL_ON;
  settings.Compute = self->ComputeTraversal != COMPUTE_TRAVERSAL_OFF &&
      this->Compute->IsWanted(
        renWin, everyPoint, ensemble->GetPassWidth(), ensemble->GetPassHeight())
    ? this->Compute.Get()
    : nullptr;
  settings.ComputeEveryPoint = everyPoint;
  return settings;
}
