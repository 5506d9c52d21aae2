/**
 * @class   vtkSPTVolumeMapper
 * @brief   sorting-free pre-integrated projected tetrahedra (SPT) for unstructured grids
 *
 * vtkSPTVolumeMapper volume renders a vtkUnstructuredGrid (any linear or quadratic 3D cells,
 * split into tetrahedra once per input change) without sorting anything, as described in
 *
 *   N. Sakamoto, T. Kawamura, H. Kuwano and K. Koyamada, "Sorting-free pre-integrated
 *   projected tetrahedra", Proc. Workshop on Ultrascale Visualization (UltraVis), 2009.
 *
 * Every tetrahedron is projected on the GPU and drawn as its outline (one or two triangles).
 * Each fragment finds its ray segment from the cell's face planes, reads the segment's
 * pre-integrated color and opacity from a 3D table indexed by (front scalar, back scalar,
 * thickness), is kept with probability equal to that opacity, and is then written opaque with
 * the depth test. The image is the mean of RepetitionLevel such passes, each with
 * SubpixelLevel^2 samples per pixel; its expected value is exact front-to-back compositing, and
 * its noise falls as 1 / sqrt(RepetitionLevel * SubpixelLevel^2).
 *
 * Beyond the paper, and on by default: several repetitions per traversal (image atomics),
 * stratified thresholds, and two changes to what a repetition adds that keep the expectation
 * exact and remove most of the noise: every segment not behind the repetition's nearest kept
 * one adds its own pre-integrated color and opacity, and one extra traversal per image makes
 * the alpha exact and corrects the color by a control variate. SetSamplingToPaper() gives the
 * paper's method. A user chooses the quality (TargetError, with RepetitionLevel as its cap),
 * the interaction (AutoAdjustRepetitions, ProgressiveRefinement) and SubpixelLevel; the
 * advanced settings choose themselves.
 *
 * The optical model is the one of vtkUnstructuredGridLinearRayIntegrator: the scalar opacity
 * transfer function divided by ScalarOpacityUnitDistance is the attenuation coefficient, and
 * the color transfer function is the emitted color per unit of attenuation. Only the first
 * component's transfer functions are used; a multi-component array is rendered as its
 * magnitude or as one component (SetVectorMode()).
 *
 * Lengths are measured in the data's own coordinates, so ScalarOpacityUnitDistance is a data
 * length and transforming the vtkVolume does not change its opacity (as with
 * vtkUnstructuredGridVolumeRayCastMapper).
 *
 * Opaque geometry drawn before the volume hides it and cuts the segments it passes through.
 * The camera may be anywhere, inside the mesh too: a tetrahedron cut by the near plane
 * contributes its segments from the near plane to their exits, exactly.
 *
 * Several SPT volumes in one renderer composite exactly where they interpenetrate, each
 * with its own input, transfer functions and vtkVolume transform: nothing in a frame depends
 * on order (an atomic minimum of depth keys, then sums), so the first visible SPT volume of
 * the renderer draws them all into one set of buffers, with its own sampling settings
 * (RepetitionLevel, Seed, TargetError, ...), and the others draw nothing themselves. A
 * mapper stands for one volume of such a frame: one that several vtkVolumes draw draws each of
 * them in a frame of its own, composited over the image before it as VTK's other mappers do
 * (a warning says so); give each vtkVolume its own mapper, sharing the input if need be.
 *
 * For the same reason, the ranks of a parallel job draw their own pieces of one data set as
 * they are, combined by reductions (vtkPSPTVolumeMapper::SetController()).
 *
 * @sa
 * vtkProjectedTetrahedraMapper vtkUnstructuredGridVolumeRayCastMapper
 */

#ifndef vtkSPTVolumeMapper_h
#define vtkSPTVolumeMapper_h

#include "SPTRenderingSPTModule.h" // For export macro
#include "vtkNew.h"                // For the frame statistics
#include "vtkSPTFrameStatistics.h" // For the frame statistics
#include "vtkStochasticVolumeMapper.h"

#include <memory>  // For the internals
#include <utility> // For the shared volumes
#include <vector>  // For the shared volumes

class vtkRenderer;
class vtkVolume;
class vtkWindow;

class SPTRENDERINGSPT_EXPORT vtkSPTVolumeMapper : public vtkStochasticVolumeMapper
{
public:
  static vtkSPTVolumeMapper* New();
  vtkTypeMacro(vtkSPTVolumeMapper, vtkStochasticVolumeMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Error target: the error (root mean square of premultiplied RGBA over the volume's
   * footprint, noise and the framebuffer's rounding) at which a render stops adding
   * repetitions, in every tile of 32 x 32 pixels of the image: after each step, the
   * repetitions that follow are drawn only into the tiles still above it. RepetitionLevel
   * becomes its cap. The noise is estimated from the image itself (two independent halves),
   * never from a reference. 0 turns it off. Range 0 to 1, default 0;
   * 0.005 is about 1.3 levels of an 8-bit image.
   */
  vtkSetClampMacro(TargetError, double, 0.0, 1.0);
  vtkGetMacro(TargetError, double);
  ///@}

  /// The error estimated for the image of the last render, as TargetError counts it (its
  /// largest tile's); -1 when none was (TargetError off, fewer than two repetitions, or
  /// nothing drawn).
  vtkGetMacro(EstimatedError, double);

  /// What the last render drew: repetitions, estimated error, depth slabs, the cells drawn as
  /// points or in compute passes, and the bytes a parallel render exchanged. Updated by every
  /// render; owned by the mapper.
  vtkSPTFrameStatistics* GetFrameStatistics();

  /**
   * @name Advanced settings
   * These change how fast the image comes, never what it converges to (each keeps the
   * expectation exact front-to-back compositing), or switch the parts of the method that go
   * beyond the paper. Their defaults choose for themselves from the renderer, the image and
   * the cells' size on the screen; Documentation/advanced-settings.md explains each one.
   */
  ///@{
  /// The sampling of the paper: one repetition per traversal, the survivor estimator, no
  /// stratification, no exact coverage, one depth slab. SetSamplingToDefault() restores the
  /// defaults of all five.
  void SetSamplingToPaper();
  void SetSamplingToDefault();
  ///@}

  ///@{
  /**
   * Repetitions drawn per traversal with image atomics (OpenGL 4.4; 4 bytes per repetition
   * and sample). Fewer are drawn where the keys would pass the device's budget (an eighth of
   * its free memory, 128 MiB to 1 GiB; never fewer than 16), and 1 without image load/store.
   * 1 draws each repetition as its own pass, as in the paper. Range 1 to 256, default 256.
   */
  vtkSetClampMacro(RepetitionsPerPass, int, 1, 256);
  vtkGetMacro(RepetitionsPerPass, int);
  ///@}

  ///@{
  /**
   * Cells about this many pixels across or less are drawn as one point each (a square over
   * the projection), the others as the outline of their projection; both clip their rays by
   * the cell's face planes, so the image is the same. 0 draws every cell as an outline.
   * Range 0 to 64 pixels, default 8.
   */
  vtkSetClampMacro(SmallCellSize, double, 0.0, 64.0);
  vtkGetMacro(SmallCellSize, double);
  ///@}

  enum ComputeTraversalMode
  {
    COMPUTE_TRAVERSAL_OFF = 0,
    COMPUTE_TRAVERSAL_ON = 1,
    COMPUTE_TRAVERSAL_AUTO = 2
  };

  ///@{
  /**
   * Visit the cells drawn as points in compute passes (OpenGL 4.3), which pays on a software
   * rasterizer that bins points on one thread. AUTO (default): on a software rasterizer, for
   * points of about 4 pixels or less that are at least a quarter as many as the samples. ON:
   * every point, on any renderer. OFF: none. The sums are added in fixed point: the image
   * differs from the rasterized one by at most one 8-bit level.
   */
  vtkSetClampMacro(ComputeTraversal, int, COMPUTE_TRAVERSAL_OFF, COMPUTE_TRAVERSAL_AUTO);
  vtkGetMacro(ComputeTraversal, int);
  void ComputeTraversalOn() { this->SetComputeTraversal(COMPUTE_TRAVERSAL_ON); }
  void ComputeTraversalOff() { this->SetComputeTraversal(COMPUTE_TRAVERSAL_OFF); }
  void SetComputeTraversalToAuto() { this->SetComputeTraversal(COMPUTE_TRAVERSAL_AUTO); }
  ///@}

  ///@{
  /// Stratified keep-or-discard thresholds: over an image's repetitions, each fragment visits
  /// the strata of [0, 1) once each, so a segment's kept count is exact to within one and the
  /// error falls faster than 1 / sqrt(RepetitionLevel). Default on.
  vtkSetMacro(StratifiedSampling, vtkTypeBool);
  vtkGetMacro(StratifiedSampling, vtkTypeBool);
  vtkBooleanMacro(StratifiedSampling, vtkTypeBool);
  ///@}

  enum EstimatorType
  {
    SURVIVOR_ESTIMATOR = 0,
    VISIBILITY_ESTIMATOR = 1
  };

  ///@{
  /**
   * What a repetition adds: SURVIVOR_ESTIMATOR (the paper's), the nearest kept segment's
   * color, opaque; VISIBILITY_ESTIMATOR (default), every segment not behind it, with its own
   * pre-integrated color and opacity, for less noise where many faint segments share a pixel.
   * Both are unbiased. The visibility estimator needs image atomics (OpenGL 4.4); without them
   * the mapper uses the survivor estimator.
   */
  vtkSetClampMacro(Estimator, int, SURVIVOR_ESTIMATOR, VISIBILITY_ESTIMATOR);
  vtkGetMacro(Estimator, int);
  void SetEstimatorToSurvivor() { this->SetEstimator(SURVIVOR_ESTIMATOR); }
  void SetEstimatorToVisibility() { this->SetEstimator(VISIBILITY_ESTIMATOR); }
  ///@}

  ///@{
  /// Exact coverage: once per image, add every segment's optical depth, so that the image's
  /// alpha is exact and its color is corrected by a control variate (the expectation stays
  /// exact). 16 bytes per sample. Default on.
  vtkSetMacro(ExactCoverage, vtkTypeBool);
  vtkGetMacro(ExactCoverage, vtkTypeBool);
  vtkBooleanMacro(ExactCoverage, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Depth slabs: the volumes' depth range is split into this many slabs, each with survivors
   * and a control variate of its own, which cuts the noise of a repetition 7 to 23 times in
   * variance for 1.2 to 1.8 times its time. 16 bytes per sample and slab. Range 1 to 8,
   * default 1.
   */
  vtkSetClampMacro(DepthSlabs, int, 1, 8);
  vtkGetMacro(DepthSlabs, int);
  ///@}

  ///@{
  /// With TargetError, let a new image's first step aim with the noise per repetition measured
  /// in the images before it. Off, every image starts from an assumed noise, and the same seed
  /// and view always give the same image. Default on.
  vtkSetMacro(ReuseNoiseEstimate, vtkTypeBool);
  vtkGetMacro(ReuseNoiseEstimate, vtkTypeBool);
  vtkBooleanMacro(ReuseNoiseEstimate, vtkTypeBool);
  ///@}

  /// The bytes this mapper holds on the GPU after the last render: mesh buffers,
  /// pre-integration table, depth keys and ensemble framebuffers.
  vtkIdType GetGPUMemorySize() override;

  void Render(vtkRenderer* ren, vtkVolume* vol) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkSPTVolumeMapper();
  ~vtkSPTVolumeMapper() override;

  int RepetitionsPerPass = 256;
  double SmallCellSize = 8.0;
  int ComputeTraversal = COMPUTE_TRAVERSAL_AUTO;
  vtkTypeBool StratifiedSampling = 1;
  int Estimator = VISIBILITY_ESTIMATOR;
  vtkTypeBool ExactCoverage = 1;
  int DepthSlabs = 1;
  double TargetError = 0.0;
  vtkTypeBool ReuseNoiseEstimate = 1;
  double EstimatedError = -1.0;
  vtkNew<vtkSPTFrameStatistics> FrameStatistics;

  /// The renderer's visible SPT volumes that one frame draws together, each with its mapper.
  using SharedVolumeList = std::vector<std::pair<vtkVolume*, vtkSPTVolumeMapper*>>;

  /// Draw the frame of `shared`, which this mapper leads, across the processes of a parallel
  /// render; false where this process draws it alone (here, always). vtkPSPTVolumeMapper
  /// overrides it.
  virtual bool RenderAcrossRanks(vtkRenderer* ren, const SharedVolumeList& shared);

private:
  vtkSPTVolumeMapper(const vtkSPTVolumeMapper&) = delete;
  void operator=(const vtkSPTVolumeMapper&) = delete;

  // The parallel render draws with this mapper's buffers, table and accumulation.
  friend class vtkPSPTVolumeMapper;
  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif
