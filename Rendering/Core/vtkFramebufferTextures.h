/**
 * @class   vtkFramebufferTextures
 * @brief   the textures that the mappers draw into: allocated for a size, read by nearest
 *          texel, attached to a framebuffer object
 *
 * The framebuffers of the mappers (the ensemble of SPT and PBVR, the k-buffer of HAVS, the
 * scene depth) are textures of one texel per pixel or sample, (re)allocated whenever the
 * viewport, the context or a setting changes, and attached as a set to a framebuffer object.
 * These functions are that life cycle's steps, once for all of them.
 *
 * Private helper of the module's mappers; not wrapped.
 */

#ifndef vtkFramebufferTextures_h
#define vtkFramebufferTextures_h

#include "SPTRenderingCoreModule.h" // For export macro

#include <initializer_list> // For Attach()

class vtkOpenGLFramebufferObject;
class vtkOpenGLRenderWindow;
class vtkTextureObject;

class SPTRENDERINGCORE_EXPORT vtkFramebufferTextures
{
public:
  vtkFramebufferTextures() = delete;

  /**
   * Nearest-texel filtering and clamping to the edge, in the context: how the mappers'
   * framebuffer textures are read (one texel per pixel or sample).
   */
  static void UseNearestTexels(vtkTextureObject* texture, vtkOpenGLRenderWindow* context);

  /// Whether the texture is allocated, at width x height texels.
  static bool HasSize(vtkTextureObject* texture, int width, int height);

  /**
   * Allocate the texture in the context as width x height texels of `components` 32-bit
   * floats, read by nearest texel (UseNearestTexels()). False when that fails.
   */
  static bool AllocateFloat(vtkTextureObject* texture, vtkOpenGLRenderWindow* context, int width,
    int height, int components);

  /**
   * Make `colors` the color attachments 0, 1, ... of the framebuffer in the context and
   * `depth`, if any, its depth attachment, in place of those it had (so that a texture
   * allocated anew is attached anew), with as many draw buffers active as colors. The
   * framebuffer bindings are restored. Whether the framebuffer is complete.
   */
  static bool Attach(vtkOpenGLFramebufferObject* framebuffer, vtkOpenGLRenderWindow* context,
    std::initializer_list<vtkTextureObject*> colors, vtkTextureObject* depth = nullptr);
  static bool Attach(vtkOpenGLFramebufferObject* framebuffer, vtkOpenGLRenderWindow* context,
    vtkTextureObject* const* colors, int numberOfColors, vtkTextureObject* depth = nullptr);
};

#endif
