/**
 * @class   vtkSPTErrorTarget
 * @brief   the steps of SPT's error target: how many repetitions an image draws next
 *
 * vtkSPTVolumeMapper::SetTargetError() draws repetitions in two independent halves, whose
 * difference estimates the noise of each tile of the image, until the estimate meets the
 * target in every tile; after each step, the repetitions that follow are drawn only into the
 * tiles still above it (vtkEnsembleTiles). This class decides each step from the noise
 * measured so far (or assumed, for a mapper's first image), whoever draws it: one process
 * (vtkSPTFrame) or the ranks of a parallel render, which share each estimate.
 *
 * Private helper of the SPT modules; not wrapped.
 */

#ifndef vtkSPTErrorTarget_h
#define vtkSPTErrorTarget_h

#include "SPTRenderingSPTModule.h" // For export macro

#include <functional> // For the steps
#include <vector>     // For the tiles

class SPTRENDERINGSPT_EXPORT vtkSPTErrorTarget
{
public:
  /// Progress towards an error target over the renders of one image.
  struct State
  {
    int HalfCount = 0;      // repetitions in each half
    bool Balanced = true;   // the halves are of equal size
    double Estimate = -1.0; // the last noise estimate; negative: none
    /// The noise of one repetition, from the last estimate of this image or of an image
    /// before it (it survives Restart()); negative: none yet.
    double NoisePerRepetition = -1.0;
    /// The same for the image's median tile, from the first estimate of an image (where every
    /// tile holds the same repetitions); negative: none yet.
    double TypicalNoisePerRepetition = -1.0;
    /// The repetitions per half of this image's first step; 0: not chosen yet.
    int FirstHalf = 0;

    /// A new image: nothing drawn. Its first step aims with the noise per repetition of the
    /// images before it, or repeats the last image's first step where everything that shapes
    /// the image is as it was (`sameImage`), so that the same render gives the same image.
    void Restart(bool sameImage)
    {
      *this = State{ 0, true, -1.0, this->NoisePerRepetition, this->TypicalNoisePerRepetition,
        sameImage ? this->FirstHalf : 0 };
    }
  };

  /// How an error target's steps draw and estimate; each returns false on failure.
  struct Steps
  {
    /// Draw repetitions [first, first + count), as two halves when `halves`.
    std::function<bool(int first, int count, bool coverage, bool halves)> Draw;
    /// The noise of the image whose halves hold `halfCount` repetitions each: its largest tile's
    /// and its median tile's (ChooseTiles()); the repetitions that follow go to the tiles still
    /// above the target.
    std::function<bool(int halfCount, double& estimate, double& median)> Estimate;
  };

  /**
   * The steps of an error target, whoever draws them (one process, or ranks that share each
   * estimate). Each step draws as many as the noise per repetition predicts for a quarter below
   * the target in variance, until the estimate meets the target or count is drawn; the first
   * step of an image takes that noise from the images before it: the median tile's where the
   * largest tile's asks for many more repetitions (the later steps draw only the tiles above
   * the target), else the largest's; the first image's assumes a
   * pessimistic one, in at most one group (at least one per half). Where only one repetition fits,
   * it is drawn alone and the halves are no longer balanced (no estimate). Returns how many were
   * drawn, or -1 on failure.
   */
  static int StepToTarget(const Steps& steps, int first, int count, int perPass, bool coverage,
    double target, State& state);

  /**
   * From the noise of each tile of an image (negative for a tile that shows nothing), the tiles
   * that later repetitions are drawn into (`active`): those above the target. Returns the
   * largest tile's noise, the image's estimate: the target holds for every tile once it holds
   * for the image; and in `median` the median tile's. Negative when no tile shows anything.
   */
  static double ChooseTiles(
    const std::vector<double>& tileNoise, double target, std::vector<bool>& active, double& median);

private:
  /// The repetitions per half of a new image's first step, from the noise of the images before.
  static int FirstHalfOfImage(const State& state, double target, int most);
  /// StepToTarget's steps once the first one's size is chosen: pairs of halves, or one alone.
  static int StepInPairs(
    const Steps& steps, int first, int count, bool coverage, double target, State& state);
};

#endif
