/**
 * @class   vtkSceneDepthTexture
 * @brief   the depth of the opaque scene, copied for the volume's shaders to test against
 *
 * The mappers draw into framebuffers of their own (the ensemble of SPT and PBVR, the k-buffer
 * of HAVS), but opaque geometry drawn before the volume must still hide it. This class holds a
 * depth texture of one texel per pixel, in the format of the render window's depth buffer
 * (glBlitFramebuffer copies depth only between identical formats), and copies that depth
 * into it at the start of a frame. Without a readable depth buffer it is the far plane.
 *
 * Private helper of SPT::RenderingCore, shared by the mappers' framebuffers; not wrapped.
 */

#ifndef vtkSceneDepthTexture_h
#define vtkSceneDepthTexture_h

#include "SPTRenderingCoreModule.h" // For export macro
#include "vtkNew.h"                 // For the texture and framebuffer
#include "vtkObject.h"

class vtkOpenGLFramebufferObject;
class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkWindow;

class SPTRENDERINGCORE_EXPORT vtkSceneDepthTexture : public vtkObject
{
public:
  static vtkSceneDepthTexture* New();
  vtkTypeMacro(vtkSceneDepthTexture, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * The vtkTextureObject depth format of the framebuffer bound for reading; `hasDepth` says
   * whether it has a depth buffer at all.
   */
  static int QueryFormat(int* hasDepth);

  /**
   * Allocate the texture (width x height, `format`) and its framebuffer in the context.
   * False, with everything released, when that fails.
   */
  bool Allocate(vtkOpenGLRenderWindow* renWin, int width, int height, int format);

  /// The format allocated, -1 before Allocate() or after a release.
  int GetFormat() const { return this->Format; }

  /**
   * Copy the depth of the framebuffer bound for reading, from the viewport whose lower left
   * corner is (x, y), into the texture (the far plane where there is none).
   */
  void Capture(int x, int y);

  vtkTextureObject* GetTexture() { return this->Texture; }

  void ReleaseGraphicsResources(vtkWindow* window);

protected:
  vtkSceneDepthTexture();
  ~vtkSceneDepthTexture() override;

private:
  vtkSceneDepthTexture(const vtkSceneDepthTexture&) = delete;
  void operator=(const vtkSceneDepthTexture&) = delete;

  vtkOpenGLRenderWindow* Context = nullptr;
  int Width = 0;
  int Height = 0;
  int Format = -1;
  vtkNew<vtkTextureObject> Texture;
  vtkNew<vtkOpenGLFramebufferObject> Framebuffer;
};

#endif
