/**
 * @class   vtkStochasticVolumeMapper
 * @brief   abstract base of the module's stochastic (ensemble-averaged) volume mappers
 *
 * vtkStochasticVolumeMapper owns what vtkSPTVolumeMapper and vtkPBVRVolumeMapper share, after
 * KVS's StochasticRendererBase: the number of repetitions averaged into one image (the papers'
 * L_R), the subpixel level of each repetition (L_S), the seed of the random numbers, and the
 * ensemble buffer that the repetitions are summed in and resolved from, and how many
 * repetitions a render draws: the time budget (AutoAdjustRepetitions) and progressive
 * refinement, which adds repetitions to the image of the renders before while nothing changes.
 *
 * @sa
 * vtkTetrahedralVolumeMapper vtkSPTVolumeMapper vtkPBVRVolumeMapper
 */

#ifndef vtkStochasticVolumeMapper_h
#define vtkStochasticVolumeMapper_h

#include "SPTRenderingCoreModule.h" // For export macro
#include "vtkNew.h"                 // For the ensemble
#include "vtkTetrahedralVolumeMapper.h"

#include <memory> // For the schedule
#include <vector> // For the signature

class vtkEnsembleBuffer;
class vtkRenderer;
class vtkVolume;

class SPTRENDERINGCORE_EXPORT vtkStochasticVolumeMapper : public vtkTetrahedralVolumeMapper
{
public:
  vtkTypeMacro(vtkStochasticVolumeMapper, vtkTetrahedralVolumeMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Number of independent repetitions (stochastic passes, or particle sets) averaged into one
   * image (the papers' L_R). The noise falls as 1 / sqrt(RepetitionLevel). Range 1 to 65536,
   * default 32.
   */
  vtkSetClampMacro(RepetitionLevel, int, 1, 65536);
  vtkGetMacro(RepetitionLevel, int);
  ///@}

  ///@{
  /**
   * Supersampling: each repetition is drawn at SubpixelLevel times the width and the height
   * and averaged down (the papers' L_S), which multiplies the samples per pixel by
   * SubpixelLevel^2 for the memory of that many pixels. Range 1 to 8, default 1.
   */
  vtkSetClampMacro(SubpixelLevel, int, 1, 8);
  vtkGetMacro(SubpixelLevel, int);
  ///@}

  ///@{
  /**
   * Seed of the random numbers. The same seed, input and camera give the same image; change
   * it for an independent image. Default 0.
   */
  vtkSetMacro(Seed, unsigned int);
  vtkGetMacro(Seed, unsigned int);
  ///@}

  ///@{
  /**
   * Progressive refinement: while the camera, the viewport, the input, the transfer functions,
   * the settings and the props of the renderer stay unchanged, each render adds
   * RepetitionLevel repetitions to the image shown before, up to
   * MaximumProgressiveRepetitions in all; any change starts again. Default off, maximum 4096
   * (range 1 to 2^20).
   */
  vtkSetMacro(ProgressiveRefinement, vtkTypeBool);
  vtkGetMacro(ProgressiveRefinement, vtkTypeBool);
  vtkBooleanMacro(ProgressiveRefinement, vtkTypeBool);
  vtkSetClampMacro(MaximumProgressiveRepetitions, int, 1, 1 << 20);
  vtkGetMacro(MaximumProgressiveRepetitions, int);
  ///@}

  ///@{
  /**
   * Fit the render time: when the volume's allocated render time (from the render window's
   * desired update rate, as during interaction in a vtkRenderWindowInteractor or ParaView's
   * interactive renders) is shorter than RepetitionLevel repetitions take, draw only as many
   * as fit, timed from the previous renders, and at least one. Still renders (the default,
   * tiny desired update rate) draw the full RepetitionLevel. Default on.
   */
  vtkSetMacro(AutoAdjustRepetitions, vtkTypeBool);
  vtkGetMacro(AutoAdjustRepetitions, vtkTypeBool);
  vtkBooleanMacro(AutoAdjustRepetitions, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Fit the render time with fewer pixels: where even one repetition takes longer than the
   * allocated render time (with AutoAdjustRepetitions), draw the image with its pixels
   * ImageSampleDistance viewport pixels apart, interpolated to the viewport, as
   * vtkUnstructuredGridVolumeRayCastMapper does; still renders draw every pixel. The distance
   * is chosen from the renders before (1 to MaximumImageSampleDistance). Default on.
   */
  vtkSetMacro(AutoAdjustSampleDistances, vtkTypeBool);
  vtkGetMacro(AutoAdjustSampleDistances, vtkTypeBool);
  vtkBooleanMacro(AutoAdjustSampleDistances, vtkTypeBool);
  ///@}

  ///@{
  /**
   * The distance between the image's pixels, in viewport pixels: the last render's where
   * AutoAdjustSampleDistances chooses it, else set here (default 1, every pixel; 1 to 16).
   * The ranks of a parallel render (vtkPSPTVolumeMapper) draw every pixel.
   */
  vtkSetClampMacro(ImageSampleDistance, float, 1.0f, 16.0f);
  vtkGetMacro(ImageSampleDistance, float);
  /// The largest distance AutoAdjustSampleDistances chooses (default 4; 1 to 16).
  vtkSetClampMacro(MaximumImageSampleDistance, float, 1.0f, 16.0f);
  vtkGetMacro(MaximumImageSampleDistance, float);
  ///@}

  ///@{
  /**
   * The repetitions averaged into the image of the last render (fewer than RepetitionLevel
   * when the time budget cut them, more with progressive refinement), and the measured time
   * of one repetition in seconds (0 before the first measurement).
   */
  vtkGetMacro(LastRepetitionCount, int);
  vtkGetMacro(TimePerRepetition, double);
  ///@}

  /**
   * Release every GPU resource this mapper holds for the window.
   */
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkStochasticVolumeMapper();
  ~vtkStochasticVolumeMapper() override;

  /// The framebuffers the repetitions are summed in and resolved from.
  vtkEnsembleBuffer* GetEnsemble() const { return this->Ensemble; }

  /// How a render draws its repetitions.
  enum class Traversal
  {
    Group,  ///< several repetitions per traversal
    Pair,   ///< one repetition per pair of traversals, finding its survivor and adding colors
    Single, ///< one repetition per traversal: the cheapest frame
  };

  /**
   * How many of `level` repetitions the time allotted to the volume fits (all of them without
   * AutoAdjustRepetitions). `perPass` is the repetitions one traversal draws; when not even
   * one traversal of them fits, it drops to 1. On entry `kind` is the best way this mapper
   * draws one repetition at a time (Pair or Single); on return it is the way chosen: Group
   * while perPass is above 1, Pair where a pair fits (or has not been timed yet), else Single.
   */
  int ChooseRepetitions(vtkVolume* vol, int level, int& perPass, Traversal& kind) const;

  /**
   * The sample distance of this render's image (ImageSampleDistance): with
   * AutoAdjustSampleDistances, the smallest that lets the best frame of one repetition, timed
   * in the renders before, fit the volume's allocated render time; 1 in still renders.
   */
  double ChooseSampleDistance(vtkVolume* vol);

  /**
   * Where this render's repetitions start: after those accumulated, when refining
   * progressively and `signature` (everything that changes the expected image) is that of the
   * accumulated image; else 0. `count` is capped at MaximumProgressiveRepetitions in all.
   */
  int ContinueAccumulation(std::vector<double> signature, int& count);
  /// Whether `signature` is that of the last render's image.
  bool IsLastSignature(const std::vector<double>& signature) const;
  /// A new image: nothing accumulated.
  void ResetAccumulation();
  /// Nothing accumulated, and the next render starts anew whatever its signature.
  void ForgetAccumulation();
  int GetAccumulatedRepetitions() const;

  /**
   * Everything of the renderer that changes the expected image besides the mapper's own:
   * the viewport and the props' redraw times (opaque geometry bounds the volume).
   */
  static void AppendSceneSignature(
    vtkRenderer* ren, const int viewport[4], std::vector<double>& signature);

  ///@{
  /**
   * Time the repetitions for the budget: the GPU time by timer query or, where another time
   * query is running (they do not nest), the wall time until the GPU has finished them. Only
   * with AutoAdjustRepetitions; StopTiming() returns -1 otherwise.
   */
  void StartTiming();
  double StopTiming();
  ///@}

  /**
   * Count `drawn` repetitions, drawn `perPass` per traversal in the way `kind` in `seconds`
   * (negative: not timed), into the accumulated image and the budget.
   */
  void AddRepetitions(int drawn, int perPass, Traversal kind, double seconds);

  int RepetitionLevel = 32;
  int SubpixelLevel = 1;
  unsigned int Seed = 0;
  vtkTypeBool ProgressiveRefinement = 0;
  int MaximumProgressiveRepetitions = 4096;
  vtkTypeBool AutoAdjustRepetitions = 1;
  vtkTypeBool AutoAdjustSampleDistances = 1;
  float ImageSampleDistance = 1.0f;
  float MaximumImageSampleDistance = 4.0f;
  int LastRepetitionCount = 0;
  double TimePerRepetition = 0.0;

private:
  vtkStochasticVolumeMapper(const vtkStochasticVolumeMapper&) = delete;
  void operator=(const vtkStochasticVolumeMapper&) = delete;

  vtkNew<vtkEnsembleBuffer> Ensemble;
  class vtkSchedule;
  std::unique_ptr<vtkSchedule> Schedule;
};

#endif
