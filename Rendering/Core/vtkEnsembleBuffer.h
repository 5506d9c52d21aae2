/**
 * @class   vtkEnsembleBuffer
 * @brief   the framebuffers of stochastic (ensemble-averaged) rendering
 *
 * Sorting-free stochastic renderers (SPT, PBVR) draw the same scene many times with opaque,
 * randomly kept fragments and average the passes. This class holds what that takes, at
 * SubpixelLevel^2 samples per pixel:
 * - the pass framebuffer: float color and a depth buffer, cleared before each pass;
 * - the sum: a float RGBA texture to which every pass is added (an 8-bit running mean would
 *   lose the result);
 * - the scene depth: the depth of the opaque geometry drawn before the volume, one texel per
 *   pixel, for the fragment shaders to test against;
 * - optionally the coverage: per sample, the optical depth sum(tau_i) of every segment and
 *   the tau-weighted sum of their colors, from one additive traversal (exact, no sampling);
 * and resolves the sum into the mean, blended premultiplied "over" the render window. With
 * the coverage, the mean's alpha is replaced by the exact 1 - exp(-sum(tau_i)), and its color
 * is corrected by the same difference times the segments' mean color (a control variate with
 * a deterministic coefficient: the expectation is unchanged, the alpha noise is gone).
 *
 * Private helper of SPT::RenderingCore, shared by the mappers; not wrapped.
 */

#ifndef vtkEnsembleBuffer_h
#define vtkEnsembleBuffer_h

#include "SPTRenderingCoreModule.h" // For export macro
#include "vtkEnsembleTiles.h"       // For the tiles
#include "vtkNew.h"                 // For the framebuffers
#include "vtkObject.h"
#include "vtkSceneDepthTexture.h" // For the scene depth

#include <memory> // For the quad helpers
#include <vector> // For DrawNoise()

class vtkOpenGLFramebufferObject;
class vtkOpenGLQuadHelper;
class vtkOpenGLRenderWindow;
class vtkShaderProgram;
class vtkTextureObject;
class vtkWindow;

class SPTRENDERINGCORE_EXPORT vtkEnsembleBuffer : public vtkObject
{
public:
  static vtkEnsembleBuffer* New();
  vtkTypeMacro(vtkEnsembleBuffer, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Size the buffers for a viewport of width x height pixels at the given subpixel level.
   * With a sample distance d above 1 the image has ceil(width / d) x ceil(height / d) pixels
   * (of subpixelLevel^2 samples each), which Resolve() interpolates bilinearly to the
   * viewport: the cheaper image of an interactive render. Buffers are reallocated only when
   * a size, the level or the context changes.
   */
  bool Prepare(vtkOpenGLRenderWindow* renWin, int width, int height, int subpixelLevel,
    double sampleDistance = 1.0);

  /// The scene depth of the viewport at (x, y) of what is bound for reading
  /// (vtkSceneDepthTexture::Capture()).
  void CaptureSceneDepth(int x, int y) { this->SceneDepth->Capture(x, y); }

  /**
   * Start a new ensemble: the sum is cleared.
   */
  void ClearSum();

  /**
   * Bind the pass framebuffer, set the viewport to it, set the tests of the tiles drawn (the
   * scissor and stencil tests off when all are; RestrictToTiles()) and clear its color and
   * depth. The caller draws one pass, then calls EndPass(), which adds it to the sum. The caller
   * brackets all passes with vtkOpenGLState::PushFramebufferBindings() /
   * PopFramebufferBindings() and restores the viewport, the scissor test and the stencil test.
   */
  void BeginPass();
  void EndPass(bool secondHalf = false);

  /**
   * Bind the sum itself for drawing, with the viewport set to it and the tiles' tests, for
   * a caller that adds its fragments straight into the sum (additive blending, set by the
   * caller). Bracketed like BeginPass(). The passes' depth buffer is attached too, for a
   * caller that tests against a depth of its own (the depth test is the caller's).
   */
  void BeginSumPass(bool halves = false);

  /**
   * The noise estimate of an ensemble drawn as two independent halves of equal size: with
   * halves on, a second sum holds the second half alone. EndPass(true) adds the pass to both
   * sums; BeginSumPass(true) binds both, the sum as draw buffer 0 and the second half's as
   * draw buffer 1, for shaders that write each fragment's share of the second half there.
   * Call before ClearSum(); false, with an error, when the buffer cannot be allocated.
   */
  bool SetHalves(bool halves);

  /**
   * Per tile of the image (vtkEnsembleTiles), the root mean square noise of the resolved image
   * there (premultiplied RGBA over the pixels of its footprint, alpha above 1/255): a quarter of
   * the mean squared difference between the two halves' images, each of `halfCount` passes less
   * half of those the tile missed, resolved as Resolve() resolves the whole. Reads back one float
   * pair per pixel. Negative for a tile without footprint; empty without halves.
   */
  std::vector<double> EstimateTileNoise(int halfCount, bool exactCoverage);

  /**
   * Draw the passes that follow (BeginPass(), BeginSumPass(), BeginSumBesideDepthPass() and what
   * is drawn after them) only into the tiles where `active` holds, until ClearSum(); then
   * AddRepetitions() counts what each tile holds, and Resolve() and the noise estimate divide
   * each tile's sums by its own count. False, with an error, when the stencil cannot be made.
   */
  bool RestrictToTiles(const std::vector<bool>& active);

  /// The tiles, and which of them the passes draw.
  vtkEnsembleTiles& GetTiles() { return this->Tiles; }

  /**
   * Allocate the coverage buffer (if needed), bind it for drawing with the viewport set to it
   * and the scissor test off, and clear it. The caller draws every segment once with additive
   * blending, writing (tau * color, tau). Bracketed like BeginPass().
   */
  bool BeginCoveragePass();

  /**
   * Bind the coverage buffer for drawing as BeginCoveragePass() does, without clearing it,
   * for a pass that changes what it holds. False if it is not allocated at the pass's size.
   */
  bool BindCoverage();

  /**
   * Bind the sum for drawing, as BeginSumPass() does but without the passes' depth buffer, so
   * that the caller can read it (GetPassDepthTexture()). With `coverage`, the coverage buffer
   * is allocated and cleared as BeginCoveragePass() does and bound as draw buffer 1, for a
   * traversal that draws both. Bracketed like BeginPass(); false, with an error, when the
   * coverage cannot be allocated.
   */
  bool BeginSumBesideDepthPass(bool coverage);

  /// The passes' depth buffer: one 32-bit float per sample, what BeginPass() cleared and the
  /// caller drew since.
  vtkTextureObject* GetPassDepthTexture() { return this->PassDepth; }

  /**
   * Blend the mean of the sum over what is bound for drawing, into the viewport at (x, y):
   * premultiplied RGBA, divided by numberOfPasses (less the repetitions a tile missed) *
   * SubpixelLevel^2; with exactCoverage,
   * corrected by the coverage buffer drawn since the sum was cleared.
   */
  void Resolve(int x, int y, int numberOfPasses, bool exactCoverage = false);

  /**
   * Read the color that the scene drew before the volume, in the viewport at (x, y) of what is
   * bound for reading: RGBA bytes, one pixel after another from the bottom row up.
   */
  std::vector<unsigned char> ReadSceneColor(int x, int y) const;

  /**
   * Replace the opaque scene bound for drawing, in the viewport at (x, y), by `color` (as
   * ReadSceneColor() reads it) and the scene depth texture's depth: the scene that several
   * processes drew, composited, for the volume to be resolved over.
   */
  bool DrawScene(int x, int y, const std::vector<unsigned char>& color);

  /**
   * Write the near plane's depth into the depth buffer bound for drawing wherever the sum
   * covers a pixel, in the viewport at (x, y), and no color: for a compositor that keeps each
   * pixel of the nearest process (IceT's z-buffer mode takes far pixels for empty ones).
   */
  void MarkFootprint(int x, int y);

  ///@{
  /**
   * The scene depth texture and the size of one pass in samples.
   */
  vtkTextureObject* GetSceneDepthTexture() { return this->SceneDepth->GetTexture(); }
  /// The sum of the repetitions and the coverage (float RGBA, one texel per sample); the
  /// coverage is allocated by the first BeginCoveragePass().
  vtkTextureObject* GetSumTexture() { return this->Sum; }
  vtkTextureObject* GetCoverageTexture() { return this->Coverage; }
  /// The second half's sum (SetHalves()); the sum holds both halves.
  vtkTextureObject* GetSecondHalfTexture() { return this->SecondHalf; }
  int GetPassWidth() const { return this->Width * this->SubpixelLevel; }
  int GetPassHeight() const { return this->Height * this->SubpixelLevel; }
  double GetSampleDistance() const { return this->SampleDistance; }
  /// The viewport's pixels per image pixel along x and y: 1 at a sample distance of 1.
  void GetPixelScale(float scale[2]) const;
  ///@}

  /**
   * Bytes held on the GPU by the framebuffers.
   */
  size_t GetGPUMemorySize() const;

  void ReleaseGraphicsResources(vtkWindow* window);

protected:
  vtkEnsembleBuffer();
  ~vtkEnsembleBuffer() override;

private:
  vtkEnsembleBuffer(const vtkEnsembleBuffer&) = delete;
  void operator=(const vtkEnsembleBuffer&) = delete;

  void Allocate(vtkOpenGLRenderWindow* renWin, int depthFormat);
  vtkOpenGLFramebufferObject* SumsFramebuffer(bool secondHalf);
  // The two-channel buffer of the noise estimate, at the image's size.
  bool AllocateNoise();
  // Per pixel, the squared difference of the halves' means and whether it is in the footprint.
  std::vector<float> DrawNoise(vtkShaderProgram* program, int halfCount, bool exactCoverage);

  vtkOpenGLRenderWindow* Context = nullptr;
  int Width = 0; // the image's pixels
  int Height = 0;
  int ViewportWidth = 0;
  int ViewportHeight = 0;
  double SampleDistance = 1.0;
  int SubpixelLevel = 0;

  vtkNew<vtkTextureObject> PassColor;
  vtkNew<vtkTextureObject> PassDepth;
  vtkNew<vtkTextureObject> Sum;
  vtkNew<vtkTextureObject> Coverage;
  vtkNew<vtkTextureObject> SecondHalf;
  vtkNew<vtkTextureObject> Noise;
  bool Halves = false;
  vtkNew<vtkSceneDepthTexture> SceneDepth;
  vtkNew<vtkOpenGLFramebufferObject> PassFramebuffer;
  vtkNew<vtkOpenGLFramebufferObject> SumFramebuffer;
  vtkNew<vtkOpenGLFramebufferObject> CoverageFramebuffer;
  vtkNew<vtkOpenGLFramebufferObject> SumBesideDepthFramebuffer; // the sum, no depth
  vtkNew<vtkOpenGLFramebufferObject> SumAndCoverageFramebuffer; // the sum and the coverage
  vtkNew<vtkOpenGLFramebufferObject> HalvesFramebuffer;         // the sum and the second half's
  unsigned int HalvesSum = 0; // the sum texture that HalvesFramebuffer holds
  vtkNew<vtkOpenGLFramebufferObject> NoiseFramebuffer;
  std::unique_ptr<vtkOpenGLQuadHelper> Accumulate;
  std::unique_ptr<vtkOpenGLQuadHelper> AccumulateBoth; // to the sum and the second half's
  std::unique_ptr<vtkOpenGLQuadHelper> Mean;
  std::unique_ptr<vtkOpenGLQuadHelper> Footprint;
  std::unique_ptr<vtkOpenGLQuadHelper> SceneQuad;
  vtkNew<vtkTextureObject> SceneColor; // the composited scene's color (DrawScene())
  std::unique_ptr<vtkOpenGLQuadHelper> NoiseQuad;
  vtkEnsembleTiles Tiles;
  // The framebuffers whose depth attachment is the passes' depth (and its stencil).
  std::vector<vtkOpenGLFramebufferObject*> DepthFramebuffers();
};

#endif
