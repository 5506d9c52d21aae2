/**
 * @class   vtkSPTParallelFrame
 * @brief   one rank's part of an SPT image drawn by several ranks
 *
 * Draws this rank's piece as vtkSPTFrame does, and makes the exchanges that combine it with
 * the other ranks' (vtkSPTParallelReduction): the depth keys after each key traversal, and
 * the sums, which move to rank 0 whenever the frame needs the whole image's (rank 0 holds the
 * global sums, the others nothing, between steps and between frames, so that a progressive
 * render adds to them).
 *
 * With an error target, the steps are those of vtkSPTFrame::DrawToTarget(): two halves of
 * repetitions, then the halves' sums move to rank 0, which estimates the noise of the whole
 * image; every rank follows that estimate, so every rank draws the same repetitions and makes
 * the same exchanges. A rank whose drawing fails goes on taking part in every exchange with
 * nothing kept and nothing added, and the ranks learn of it at the next shared decision: no
 * rank waits for another.
 *
 * Private helper of the SPT module; not wrapped.
 */

#ifndef vtkSPTParallelFrame_h
#define vtkSPTParallelFrame_h

#include "SPTRenderingParallelModule.h" // For export macro
#include "vtkSPTFrame.h"                // For the frame

#include <cstddef> // For size_t
#include <vector>  // For the volumes

class vtkEnsembleBuffer;
class vtkSPTParallelReduction;

class SPTRENDERINGPARALLEL_EXPORT vtkSPTParallelFrame
{
public:
  /// As vtkSPTFrame's; `settings.AfterKeys` is replaced by the key exchange.
  vtkSPTParallelFrame(vtkOpenGLRenderWindow* window, vtkEnsembleBuffer* ensemble,
    vtkSPTDepthKeyBuffer* depthKeys, const std::vector<vtkSPTFrame::Volume>& volumes,
    const vtkSPTFrame::Settings& settings, vtkObject* reporter, vtkSPTParallelReduction* reduction);
  vtkSPTParallelFrame(const vtkSPTParallelFrame&) = delete;
  vtkSPTParallelFrame& operator=(const vtkSPTParallelFrame&) = delete;

  /// This rank could not start the accumulation: it draws nothing and still takes part.
  void Fail() { this->Ok = false; }

  /**
   * Draw repetitions [first, first + count) as vtkSPTFrame::DrawRepetitions() does, with the
   * key exchanges of every group (made with nothing kept if this rank's drawing failed).
   * Collective.
   */
  void Draw(int first, int count, int perPass, bool coverage, bool halves);

  /**
   * vtkSPTFrame::DrawToTarget() across the ranks: the same steps, each followed by the noise
   * estimate of the whole image on rank 0, which every rank follows. Returns how many
   * repetitions were drawn, or -1 on every rank when any rank failed. Collective.
   */
  int DrawToTarget(int first, int count, int perPass, bool coverage, bool exactCoverage,
    double target, vtkSPTErrorTarget::State& state);

  /**
   * Move what was drawn since the last move to rank 0; true on every rank when every rank
   * drew everything. Collective.
   */
  bool Finish();

  /// How many tetrahedra of a volume the traversals draw as points.
  vtkIdType GetPointCellCount(size_t volume) const { return this->Frame.GetPointCellCount(volume); }
  vtkIdType GetComputedCellCount(size_t volume) const
  {
    return this->Frame.GetComputedCellCount(volume);
  }
  /// The depth slabs the frame draws.
  int GetDepthSlabs() const { return this->Frame.GetDepthSlabs(); }

private:
  static vtkSPTFrame::Settings WithExchanges(
    vtkSPTFrame::Settings settings, vtkSPTParallelReduction* reduction, int* exchanges);
  // Move the sums (and the second half's, and the coverage if drawn since) to rank 0.
  bool MoveSums(bool halves);
  // Move the halves to rank 0, estimate there, and share; false when any rank failed.
  bool Estimate(int halfCount, bool exactCoverage, double target, double& estimate, double& median);

  vtkEnsembleBuffer* Ensemble;
  vtkSPTParallelReduction* Reduction;
  int Exchanges = 0; // key exchanges made
  vtkSPTFrame Frame;
  size_t Samples;
  bool Ok = true;               // this rank drew everything so far
  bool SumsPending = false;     // repetitions drawn since the sums last moved
  bool CoveragePending = false; // the coverage drawn since the sums last moved
};

#endif
