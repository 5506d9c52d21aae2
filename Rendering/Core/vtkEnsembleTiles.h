/**
 * @class   vtkEnsembleTiles
 * @brief   the tiles of an ensemble's image that later repetitions are drawn into
 *
 * An error target stops drawing a part of the image once the noise there meets the target
 * (OSPRay's variance threshold): the image is cut into square tiles of TileSize x TileSize
 * pixels, each tile's noise is estimated from the halves, and the repetitions that follow are
 * drawn only into the tiles still above the target. This class holds that restriction for a
 * vtkEnsembleBuffer:
 * - the stencil of the passes' depth buffer, 1 in the tiles drawn and 0 elsewhere, tested
 *   (equal to 1, never written) by every pass drawn while the restriction holds, and the scissor
 *   box around those tiles: the rasterizer skips the other samples before they are shaded;
 * - per tile, the repetitions it missed, as a texture of one texel per tile for the shaders that
 *   divide the sums by their count (the mean and the noise estimate).
 * The passes' depth buffer gains its stencil (32-bit float depth and 8-bit stencil) only when a
 * restriction is first made: the renders without one keep their depth buffer as it is.
 *
 * Private helper of vtkEnsembleBuffer; not wrapped.
 */

#ifndef vtkEnsembleTiles_h
#define vtkEnsembleTiles_h

#include "SPTRenderingCoreModule.h" // For export macro
#include "vtkNew.h"                 // For the texture

#include <vector> // For the tiles

class vtkOpenGLFramebufferObject;
class vtkOpenGLRenderWindow;
class vtkOpenGLState;
class vtkShaderProgram;
class vtkTextureObject;
class vtkWindow;

class SPTRENDERINGCORE_EXPORT vtkEnsembleTiles
{
public:
  /// The side of a tile, in pixels of the image.
  static constexpr int TileSize = 32;

  vtkEnsembleTiles();
  ~vtkEnsembleTiles();
  vtkEnsembleTiles(const vtkEnsembleTiles&) = delete;
  vtkEnsembleTiles& operator=(const vtkEnsembleTiles&) = delete;

  /// The image's size (pixels) and the samples per pixel along an axis; the whole image is drawn.
  void Resize(int width, int height, int subpixelLevel);
  /// The whole image is drawn, and no tile has missed a repetition.
  void Reset();

  /**
   * Per tile (row after row from the bottom), the root mean square of `values` over the
   * tile's pixels where `inside` holds (pairs per pixel of the image: value, inside flag), times
   * `scale`; negative for a tile without such a pixel.
   */
  std::vector<double> MeanPerTile(const std::vector<float>& pairs, double scale) const;

  /**
   * Restrict the passes that follow to the tiles where `active` holds, for the framebuffers
   * given (those whose depth attachment is `depth`): their stencil is attached and written.
   * False, with the reason in `error`, when it cannot be.
   */
  bool Restrict(vtkOpenGLRenderWindow* context, const std::vector<bool>& active,
    vtkTextureObject* depth, const std::vector<vtkOpenGLFramebufferObject*>& framebuffers,
    const char*& error);

  /// Before the depth buffer is allocated anew: the stencil attachments are removed.
  void DetachStencil(
    vtkOpenGLRenderWindow* context, const std::vector<vtkOpenGLFramebufferObject*>& framebuffers);

  /// `count` repetitions were drawn into the restriction: the other tiles missed them.
  void AddRepetitions(int count);

  /// The passes' tests of the restriction (stencil and scissor), in the bound framebuffer; none
  /// without one.
  void ApplyTests(vtkOpenGLRenderWindow* context) const;

  /// The samples of the pass (x, y, width, height) that the restricted tiles cover.
  void GetSampleBox(int box[4]) const;

  /// The most repetitions a tile missed.
  int GetMostMissed() const;

  /**
   * Set the uniforms `restricted`, `tileSize` and `tileMissed` (a sampler, active until
   * Deactivate()) of a program that divides by per-tile counts.
   */
  void Activate(vtkOpenGLRenderWindow* context, vtkShaderProgram* program);
  void Deactivate();

  void ReleaseGraphicsResources(vtkWindow* window);

private:
  bool UploadMissed(vtkOpenGLRenderWindow* context);
  bool AllocateStencil(vtkTextureObject* depth);
  // The active tiles into the stencil of the bound framebuffer, and their box.
  void WriteStencil(vtkOpenGLState* ostate);

  int Width = 0;
  int Height = 0;
  int SubpixelLevel = 1;
  int Columns = 0;
  int Rows = 0;
  bool Restricted = false;
  bool StencilAllocated = false; // the depth buffer has a stencil
  bool MissedUploaded = true;    // the texture holds Missed
  std::vector<bool> Active;      // per tile
  std::vector<float> Missed;     // per tile: repetitions not drawn there
  int Box[4] = { 0, 0, 0, 0 };   // the active tiles' box, in tiles
  vtkNew<vtkTextureObject> MissedTexture;
};

#endif
