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
 * exact and remove most of the noise. Every segment not behind the repetition's nearest kept
 * one adds its own pre-integrated color and opacity (VISIBILITY_ESTIMATOR), and one extra
 * traversal per image makes the alpha exact and corrects the color by a control variate
 * (ExactCoverage). SetEstimatorToSurvivor(), ExactCoverageOff(), StratifiedSamplingOff() and
 * SetRepetitionsPerPass(1) give the paper's method.
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
 * they are (any shape, interleaved, with overlapping bounds), with no redistribution and no
 * compositing in visibility order (vtkPSPTVolumeMapper::SetController(), in
 * SPT::RenderingParallel): their depth keys are combined by a
 * global minimum and their sums by a global sum, and rank 0 resolves the image of the whole.
 *
 * @sa
 * vtkProjectedTetrahedraMapper vtkUnstructuredGridVolumeRayCastMapper
 */

#ifndef vtkSPTVolumeMapper_h
#define vtkSPTVolumeMapper_h

#include "SPTRenderingSPTModule.h" // For export macro
#include "vtkStochasticVolumeMapper.h"

#include <memory>  // For the internals
#include <utility> // For the shared volumes
#include <vector>  // For the shared volumes

class vtkMultiProcessController;
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
   * Repetitions drawn per traversal of the geometry. 1 draws each repetition as its own pass,
   * as in the paper (with the survivor estimator, as does a render of one repetition; the
   * visibility estimator always takes a key traversal and a color traversal). N > 1 makes N
   * keep-or-discard decisions per fragment and finds each repetition's nearest survivor with image
   * atomics (two traversals for N repetitions), which gives the same image as N single passes with
   * the same random numbers, for 4 x N bytes per sample of GPU memory (4 x RepetitionLevel when
   * that is smaller). A fragment's work grows with its opacity times N (only the repetitions that
   * keep it are visited) and with log2(N) (the visibility estimator counts the survivors behind it
   * by binary search), so one traversal of many repetitions costs little more than one of a few.
   * Where the keys would pass 128 MiB (256 repetitions at 256 x 256 take 64 MiB), fewer are
   * drawn per traversal, but never fewer than 16. Needs OpenGL 4.4 (image load/store, clear
   * texture); without it the mapper falls back to 1 and to the survivor estimator. The keys
   * are a 3D texture of (repetition, sample): an image of more samples per side than the
   * context's 3D textures hold (GL_MAX_3D_TEXTURE_SIZE, 2048 on llvmpipe) draws with 1 (the
   * same image, a warning says so), and with TargetError, which needs the keys, is an error. With
   * AutoAdjustRepetitions, the time allotted is spent in whole traversals of RepetitionsPerPass
   * repetitions while one fits; else, with the visibility estimator, in repetitions drawn one
   * per pair of traversals (the depth test finds the survivor, with exact coverage, unless a
   * compute pass takes most of the cells, see ComputeTraversal) while one fits; else in the
   * cheapest frame there is: the paper's single passes (one traversal per repetition, the survivor
   * estimator, no exact coverage; unbiased too). Range 1 to 256, default 256.
   */
  vtkSetClampMacro(RepetitionsPerPass, int, 1, 256);
  vtkGetMacro(RepetitionsPerPass, int);
  ///@}

  ///@{
  /**
   * How tetrahedra are drawn. The cells about SmallCellSize pixels across or less (by classes
   * of their longest edge, a factor of sqrt(2) apart, at the depth of the mesh's centre) are
   * drawn as one point each, a square over the projection; the others as the outline of their
   * projection, one or two triangles, by a geometry shader. Needles and slivers (cells whose
   * mean projection fills less than 0.15 of the square of their longest edge) are never
   * points. The fragments of both clip their own view rays by the cell's four face planes, so
   * the image is the same either way (the two may differ only for samples on a shared edge).
   * A point is one primitive with no geometry stage, but its square also covers samples that
   * miss the cell, so it pays where cells are small and well shaped on the screen: on
   * llvmpipe at 256 x 256, 0.7 of the time on a 200,000-cell TetGen mesh, about 1.0 on the
   * Oxygen Post. Points are used only where the mesh's bounds lie wholly in front of the near
   * plane. 0 draws every cell as an outline. Range 0 to 64 pixels, default 8.
   */
  vtkSetClampMacro(SmallCellSize, double, 0.0, 64.0);
  vtkGetMacro(SmallCellSize, double);
  ///@}

  /**
   * How many tetrahedra the last render drew as points (see SmallCellSize).
   */
  vtkGetMacro(LastPointCellCount, vtkIdType);

  enum ComputeTraversalMode
  {
    COMPUTE_TRAVERSAL_OFF = 0,
    COMPUTE_TRAVERSAL_ON = 1,
    COMPUTE_TRAVERSAL_AUTO = 2
  };

  ///@{
  /**
   * Visit cells drawn as points (see SmallCellSize) in compute passes in the keys and color
   * traversals of a group, where the context has compute shaders (OpenGL 4.3): a work group's
   * invocations find one cell each, then share out the (cell, sample) pairs of their cells'
   * squares evenly and run the points' fragment work on each. The keys are the
   * same; what the fragments add by blending (the exact coverage's terms, the colors) is added
   * in fixed point (2^-16 per term), so the image differs from the points' by at most an 8-bit
   * level and stays the same from run to run. It pays on a software rasterizer such as
   * llvmpipe, which sets up and bins points one at a time on the application's thread, where
   * the points are many and small: at 256 x 256, 0.65 to 0.86 of the frame on a TetGen mesh of
   * 1 million cells, 0.89 to 0.93 on the Oxygen Post. A GPU rasterizes points in hardware.
   * - COMPUTE_TRAVERSAL_AUTO (default): where the OpenGL renderer is a software rasterizer
   *   (Mesa's llvmpipe or softpipe, SwiftShader), the points about 4 pixels across or less,
   *   where they are at least a quarter as many as the image's samples (a compute traversal
   *   has a cost per sample, and a sample's work grows with the group's repetitions).
   * - COMPUTE_TRAVERSAL_ON: every cell drawn as a point, on any renderer.
   * - COMPUTE_TRAVERSAL_OFF: none.
   * Where a driver offers compute shaders but does not build these programs, the mapper warns
   * once with the compiler's message and rasterizes those cells in that context. Its sums are
   * a 3D texture of (term, sample): an image of more samples per side than the context's 3D
   * textures hold rasterizes every cell.
   */
  vtkSetClampMacro(ComputeTraversal, int, COMPUTE_TRAVERSAL_OFF, COMPUTE_TRAVERSAL_AUTO);
  vtkGetMacro(ComputeTraversal, int);
  void ComputeTraversalOn() { this->SetComputeTraversal(COMPUTE_TRAVERSAL_ON); }
  void ComputeTraversalOff() { this->SetComputeTraversal(COMPUTE_TRAVERSAL_OFF); }
  void SetComputeTraversalToAuto() { this->SetComputeTraversal(COMPUTE_TRAVERSAL_AUTO); }
  ///@}

  /**
   * How many tetrahedra the last render's traversals visited in a compute pass (see
   * ComputeTraversal), or 0 where the render drew no keys (one repetition finds its survivor
   * by the depth test), the context has no compute shaders, or the small cells are too few.
   */
  vtkGetMacro(LastComputedCellCount, vtkIdType);

  ///@{
  /**
   * Stratified keep-or-discard thresholds: within the RepetitionLevel repetitions of an image,
   * each fragment's thresholds visit the RepetitionLevel strata of [0, 1) once each, in an
   * order of its own, instead of being independent. The expectation is the same; a segment's
   * kept count is exact to within one, so the error falls faster than 1 / sqrt(RepetitionLevel).
   * Default on.
   */
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
   * What a repetition adds to the image. Both find each repetition's nearest kept segment per
   * sample, with nothing sorted, and both have exact front-to-back compositing as their
   * expected value:
   * - SURVIVOR_ESTIMATOR (the paper's): the survivor's color, written opaque; every other
   *   segment adds nothing. One traversal per repetition when RepetitionsPerPass is 1.
   * - VISIBILITY_ESTIMATOR (default): every segment not behind the survivor adds its
   *   pre-integrated premultiplied color and opacity (the depth-based accumulation of
   *   Enderton et al., "Stochastic transparency", I3D 2010, without its alpha correction, so
   *   the mean stays unbiased). Its noise is lower wherever many thin, faint segments share a
   *   pixel. It always finds the survivors with image atomics (OpenGL 4.4); without them the
   *   mapper falls back to the survivor estimator.
   */
  vtkSetClampMacro(Estimator, int, SURVIVOR_ESTIMATOR, VISIBILITY_ESTIMATOR);
  vtkGetMacro(Estimator, int);
  void SetEstimatorToSurvivor() { this->SetEstimator(SURVIVOR_ESTIMATOR); }
  void SetEstimatorToVisibility() { this->SetEstimator(VISIBILITY_ESTIMATOR); }
  ///@}

  ///@{
  /**
   * Exact coverage: once per image (not per repetition), the first key traversal also adds
   * up every segment's optical depth tau = -ln(1 - alpha) and its tau-weighted color, per
   * sample, with nothing random and nothing sorted (the paper's single passes take one more
   * traversal for it). The image's alpha is then the exact coverage
   * 1 - exp(-sum(tau)) instead of its estimate, and the color is corrected by the difference
   * times the segments' tau-weighted mean color: a control variate whose coefficient does not
   * depend on the random numbers, so the expectation stays exact front-to-back compositing.
   * What noise is left comes from the color differences between a pixel's segments. Costs
   * 16 bytes per sample. Default on.
   */
  vtkSetMacro(ExactCoverage, vtkTypeBool);
  vtkGetMacro(ExactCoverage, vtkTypeBool);
  vtkBooleanMacro(ExactCoverage, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Depth slabs (1 to 8): the depth range of the volumes' bounds, as the camera sees it, is
   * split into this many equal slabs, which split each ray between its segments (a segment
   * belongs to the slab that holds its front). Each slab has survivors of its own; its
   * segments add what they composite behind the exact transmittance of the slabs in front of
   * them, and each slab has a control variate of its own (its tau-weighted mean color), both
   * from sums that the image's first key traversal adds up with the coverage. The expectation
   * stays exact front-to-back compositing, for any split; what is left of the noise is the
   * color differences within each slab. 8 slabs cut the variance of a repetition 7 to 23
   * times on the test scenes (see Documentation/results.md), for 1.2 to 1.8 times the frame:
   * a fragment visits only its own slab's survivors, but more fragments are visible (each
   * slab's front), the color traversal skips fewer of them, and the key traversals keep
   * this many times the keys (RepetitionsPerPass is divided accordingly). They pay where
   * several repetitions are wanted and the cells are small on the screen; on a mesh of large
   * cells that one repetition renders well enough, they cost more than they save. The slabs'
   * sums take 16 bytes per sample and slab, at most 128 MB: a larger image draws fewer slabs.
   * The image's first key traversal draws the coverage even with ExactCoverage off. With
   * slabs, even one repetition at a time is drawn with keys; only the cheapest frame of a time
   * budget (the paper's single passes) draws no slabs. Default 1: none.
   */
  vtkSetClampMacro(DepthSlabs, int, 1, 8);
  vtkGetMacro(DepthSlabs, int);
  ///@}

  ///@{
  /**
   * Error target: the error of the image shown (root mean square of premultiplied RGBA over
   * the image's footprint) at which a render stops adding repetitions; RepetitionLevel becomes
   * a cap. The error is the noise and the rounding of the image to the bits per channel of the
   * framebuffer it is drawn into (a level over sqrt(12), 0.00113 for 8 bits, none for floating
   * point), which add in variance: the noise is allowed what the rounding leaves of the
   * target, and a target not above the rounding draws RepetitionLevel repetitions, with a
   * warning. The noise is estimated from the image itself, never from a reference: the
   * repetitions are drawn as two independent halves of equal size, and the mean of both has
   * a quarter of the variance of their difference. The first image's first step draws as many
   * as an assumed noise per repetition (0.0275, a little above the largest the benchmark's
   * meshes measure) predicts for the target, in at most one traversal pair (16 + 16 at a
   * target of 0.005); a new image after it, as many as the noise per repetition measured
   * before predicts (ReuseNoiseEstimate). Then each step draws as
   * many as the estimate predicts for a noise a quarter below the target in variance (the
   * noise falling as one over the square root of the repetitions; each step costs a traversal
   * pair, so a step that falls just short is the costlier mistake), until the estimate is at most
   * the target, RepetitionLevel is reached or, with AutoAdjustRepetitions, the time allotted is
   * spent. With ProgressiveRefinement, a render of an image that already meets the target adds
   * nothing. 0 (the default) turns it off. Range 0 to 1; 0.005 is about 1.3 levels of an 8-bit
   * image (one level is 1/255).
   */
  vtkSetClampMacro(TargetError, double, 0.0, 1.0);
  vtkGetMacro(TargetError, double);
  ///@}

  ///@{
  /**
   * With TargetError, let a new image's first step aim at the target with the noise per
   * repetition measured in the images before it (the noise changes little from one view to
   * the next; a shortfall costs one more step). A render of the same image as the last one
   * (nothing that shapes it changed) repeats that image's steps, so it gives the same image.
   * The cost: an image then depends on what was drawn before it, so the same seed and view
   * can stop at other repetition counts in another window or after other views. Off, every
   * image starts as a first image does (from the assumed noise per repetition), and the same
   * seed and view always give the same image. Default on.
   */
  vtkSetMacro(ReuseNoiseEstimate, vtkTypeBool);
  vtkGetMacro(ReuseNoiseEstimate, vtkTypeBool);
  vtkBooleanMacro(ReuseNoiseEstimate, vtkTypeBool);
  ///@}

  /**
   * The error estimated for the image of the last render, as TargetError counts it (its noise
   * and its rounding); -1 when none was (TargetError off, fewer than two repetitions, or
   * nothing drawn).
   */
  vtkGetMacro(EstimatedError, double);

  ///@{
  /**
   * Deprecated here: the controller of a parallel render is vtkPSPTVolumeMapper's
   * (SPT::RenderingParallel), which vtkSPTVolumeMapper::New() makes wherever that module is
   * loaded. On a mapper that is not one, setting a controller is an error and none is kept.
   */
  virtual void SetController(vtkMultiProcessController* controller);
  virtual vtkMultiProcessController* GetController();
  ///@}

  /**
   * The bytes this mapper holds on the GPU after the last render: mesh buffers,
   * pre-integration table, depth keys and ensemble framebuffers.
   */
  vtkIdType GetGPUMemorySize() override;

  /**
   * Render the volume. Called by vtkVolume; not meant to be called directly.
   */
  void Render(vtkRenderer* ren, vtkVolume* vol) override;

  /**
   * Release every GPU resource this mapper holds for the window.
   */
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkSPTVolumeMapper();
  ~vtkSPTVolumeMapper() override;

  int RepetitionsPerPass = 256;
  double SmallCellSize = 8.0;
  vtkIdType LastPointCellCount = 0;
  int ComputeTraversal = COMPUTE_TRAVERSAL_AUTO;
  vtkIdType LastComputedCellCount = 0;
  vtkTypeBool StratifiedSampling = 1;
  int Estimator = VISIBILITY_ESTIMATOR;
  vtkTypeBool ExactCoverage = 1;
  int DepthSlabs = 1;
  double TargetError = 0.0;
  vtkTypeBool ReuseNoiseEstimate = 1;
  double EstimatedError = -1.0;

  /// The renderer's visible SPT volumes that one frame draws together, each with its mapper.
  using SharedVolumeList = std::vector<std::pair<vtkVolume*, vtkSPTVolumeMapper*>>;

  /**
   * Draw the frame of `shared`, which this mapper leads, across the processes of a parallel
   * render; false where this process draws it alone (here, always). vtkPSPTVolumeMapper
   * overrides it.
   */
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
