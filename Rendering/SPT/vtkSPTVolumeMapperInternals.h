/**
 * @class   vtkSPTVolumeMapper::vtkInternals
 * @brief   the state of vtkSPTVolumeMapper between renders, and the steps of a render
 *
 * Private to the SPT modules: vtkSPTVolumeMapper.cxx draws one process's frame with it, and
 * vtkPSPTVolumeMapper.cxx (SPT::RenderingParallel) the frame of a parallel render. Not
 * wrapped, not installed.
 */

#ifndef vtkSPTVolumeMapperInternals_h
#define vtkSPTVolumeMapperInternals_h

#include "vtkSPTVolumeMapper.h"

#include "vtkNew.h"

#include "vtkEnsembleBuffer.h"
#include "vtkPreIntegrationTable.h"
#include "vtkSPTComputeTraversal.h"
#include "vtkSPTDepthKeyBuffer.h"
#include "vtkSPTFrame.h"
#include "vtkSPTMeshBuffers.h"
#include "vtkVolumeViewMatrices.h"

#include <functional> // For the ranks' agreement
#include <string>     // For the errors
#include <utility>    // For the shared volumes
#include <vector>     // For the volumes

class vtkSPTVolumeMapper::vtkInternals
{
public:
  vtkNew<vtkSPTMeshBuffers> Buffers;
  vtkNew<vtkPreIntegrationTable> Table;
  vtkNew<vtkSPTDepthKeyBuffer> DepthKeys;
  vtkNew<vtkSPTComputeTraversal> Compute; // the keys traversal of the points (ComputeTraversal)
  vtkVolumeViewMatrices Matrices;
  bool WarnedNoGlobalIds = false;
  bool WarnedSharedMapper = false; // while several volumes of the renderer draw this mapper

  vtkSPTErrorTarget::State Target; // progress towards TargetError
  // Bits per channel of the framebuffer the image is resolved into (0: floating point), read
  // when the render starts.
  int ColorBits = 8;
  bool WarnedTargetBelowRounding = false; // while TargetError is not above the rounding
  bool WarnedNoImageAtomics = false;
  bool WarnedNoSlabs = false;
  bool WarnedLargeImage = false; // while the pass is too large for the depth keys
  bool CoverageDrawn = false;    // the coverage buffer belongs to the accumulated sum
  // The visible SPT volumes of the renderer, each with its mapper, in the renderer's order;
  // vol alone when it is not among them, or when `selfProps` (set to the number of the
  // renderer's visible volumes that draw `self`) is more than one. A mapper that several
  // volumes draw is left out of the others' frames.
  static SharedVolumeList SharedVolumes(
    vtkRenderer* ren, vtkVolume* vol, vtkSPTVolumeMapper* self, int& selfProps);
  // Bring a volume's mesh, table and matrices up to date and onto the GPU as `out`. The mesh
  // is normalized on its own, or with `sharedBounds` and `sharedRange` as the whole of the
  // ranks' pieces is, whose longest edge is then `sharedEdge` (normalized units).
  static bool PrepareVolume(vtkSPTVolumeMapper* mapper, vtkRenderer* ren, vtkVolume* vol,
    vtkOpenGLRenderWindow* window, vtkSPTFrame::Volume& out, const double* sharedBounds = nullptr,
    const double* sharedRange = nullptr, double sharedEdge = 0.0);
  static std::vector<double> Signature(
    vtkRenderer* ren, const std::vector<vtkSPTVolumeMapper*>& mappers, const RenderTarget& target);
  // What the mappers of a frame report of its render (GetFrameStatistics()): the image's
  // repetitions and error, the bytes the ranks exchanged, and the cells of the volumes of
  // `owners` (those this process drew, in the frame's order) drawn as points and computed;
  // none for the others of `all`.
  void Report(vtkSPTVolumeMapper* self, const std::vector<vtkSPTVolumeMapper*>& all,
    const std::vector<vtkSPTVolumeMapper*>& owners, const vtkSPTFrame& frame,
    vtkIdType parallelBytes = 0) const;
  // Prepare every shared volume that can be drawn; false when none can.
  static bool CollectVolumes(vtkRenderer* ren, const SharedVolumeList& shared, RenderTarget& target,
    std::vector<vtkSPTFrame::Volume>& volumes, std::vector<vtkSPTVolumeMapper*>& mappers);

  // What a frame draws (vtkSPTVolumeMapperInternals.cxx).
  // Repetitions per traversal: as many as asked while the depth keys (4 bytes per sample and
  // repetition) stay within `budget` bytes, and never fewer than 16, or than asked if fewer.
  static int RepetitionsPerTraversal(
    int asked, const vtkEnsembleBuffer* ensemble, int slabs, size_t budget);
  // The depth keys' budget that any device holds, and that the ranks of a parallel render
  // exchange at most per traversal.
  static constexpr size_t FixedKeyBudget = size_t(128) << 20;
  // The depth keys' budget of one process: what the device can spare (at least the fixed
  // budget, at most 1 GiB), found once per mapper.
  size_t DepthKeyBudget(vtkOpenGLRenderWindow* renWin);
  size_t KeyBudget = 0;
  // The depth slabs, of `asked`, whose sums fit the memory allotted to them.
  static int DepthSlabsThatFit(int asked, const vtkEnsembleBuffer* ensemble);
  // Repetitions per traversal that the context and the image size allow, and the estimator
  // and depth slabs with them (in `settings`); 0 (with an error) when the frame cannot be drawn.
  int ChooseTraversal(
    vtkSPTVolumeMapper* self, vtkOpenGLRenderWindow* renWin, vtkSPTFrame::Settings& settings);
  // The error or warning for an image of more samples per side than the 3D textures hold.
  static void ReportLargeImage(vtkSPTVolumeMapper* self, int maxSize);

  // What one frame draws.
  struct FramePlan
  {
    int First = 0;   // repetitions already accumulated
    int Count = 0;   // repetitions to add
    int PerPass = 1; // repetitions per traversal
    vtkStochasticVolumeMapper::Traversal Kind = vtkStochasticVolumeMapper::Traversal::Group;
    bool Cheapest = false;  // the paper's single passes, when nothing else fits the budget
    bool Coverage = false;  // draw the exact coverage in this frame
    bool SameImage = false; // all that shapes the image is as in the last render
  };
  // What the ranks of a parallel render agree on before a frame, each the least of any rank's:
  // a rank's image continues only if all continue it, and every rank draws the fewest
  // repetitions, and the fewest per traversal, that any rank's time budget allows.
  struct PlanAgreement
  {
    int First = 0;     // repetitions accumulated (0: a new accumulation)
    int Count = 0;     // repetitions the time budget allows
    int PerPass = 1;   // repetitions per traversal
    int SameImage = 0; // 1: all that shapes the image is as in the last render
    int Pairs = 0;     // 1: a repetition at a time is a pair of traversals, 0: a single pass
  };
  // Makes `agreement` the ranks' on every rank; false, on every rank, where they cannot agree.
  using AgreeOnPlan = std::function<bool(PlanAgreement& agreement)>;
  // The frame's plan, with `perPass` repetitions per traversal at most: the repetitions that
  // fit the time allotted, added to what is accumulated when refining progressively, agreed
  // through `agree` where it is given (a collective call then). The cheapest frame draws with
  // the survivor estimator and no depth slabs, which `settings` then says.
  FramePlan Plan(vtkSPTVolumeMapper* self, vtkVolume* vol, int perPass,
    std::vector<double> signature, vtkSPTFrame::Settings& settings,
    const AgreeOnPlan& agree = nullptr);
  // A new accumulation: the scene depth, the halves of the error target, a cleared sum.
  bool StartAccumulation(
    vtkSPTVolumeMapper* self, const RenderTarget& target, bool halves, bool sameImage);
  // The root mean square error of rounding the image to ColorBits bits per channel.
  double RoundingError() const;
  // The noise that TargetError leaves once the rounding has taken its share (the two add in
  // variance); 0, with a warning, when the rounding alone takes all of it.
  double NoiseTarget(vtkSPTVolumeMapper* self);
  // The image's estimated error for GetEstimatedError(): its noise and its rounding; -1 when
  // the noise is not estimated.
  double ImageError(vtkSPTVolumeMapper* self) const;
  // The frame's settings from the mapper's, with the estimator and depth slabs asked (as many
  // slabs as fit their memory): ChooseTraversal() and Plan() fall back from them.
  vtkSPTFrame::Settings FrameSettings(
    vtkSPTVolumeMapper* self, vtkOpenGLRenderWindow* renWin, bool opaqueScene, bool globalIds);
  // One process's frame of the volumes that `self` leads: plan, draw and resolve it.
  void DrawFrame(vtkSPTVolumeMapper* self, vtkRenderer* ren, vtkVolume* vol,
    const RenderTarget& target, const std::vector<vtkSPTFrame::Volume>& volumes,
    const std::vector<vtkSPTVolumeMapper*>& mappers);
  // Draw the plan's repetitions into `frame` (one process's, or a parallel frame, whose
  // Finish() all ranks make) and measure them for the budget; false, with the accumulation
  // forgotten, where any drawing failed.
  bool DrawTimed(vtkSPTVolumeMapper* self, vtkSPTFrame& frame, const FramePlan& plan);
};

#endif
