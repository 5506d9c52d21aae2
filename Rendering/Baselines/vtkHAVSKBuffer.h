/**
 * @class   vtkHAVSKBuffer
 * @brief   the per-pixel k-buffer of HAVS: textures, framebuffer, read-modify-write access
 *
 * Holds the image-space state of Hardware-Assisted Visibility Sorting (Callahan, Ikits, Comba
 * and Silva 2005) for one viewport: RGBA32F targets, the first with the premultiplied color
 * composited so far, the others with two (scalar, distance) entries each; and the depth of the
 * opaque scene drawn before the volume, one texel per pixel, for the shaders to test against.
 *
 * A fragment reads, changes and writes its pixel's targets. That read-modify-write is correct
 * only if the fragments of one pixel do it one at a time and in the order of their primitives
 * (the sorted order of the faces). The access modes (vtkHAVSVolumeMapper's
 * KBufferSynchronizationType):
 * - FRAGMENT_SHADER_INTERLOCK: image load/store inside a pixel_interlock_ordered critical
 *   section (GL_ARB_fragment_shader_interlock): guaranteed by the extension.
 * - FRAMEBUFFER_FETCH: the targets are color attachments read as inout outputs
 *   (GL_EXT_shader_framebuffer_fetch, the coherent variant): guaranteed by the extension,
 *   which orders the reads and writes of one sample in primitive order, as blending does.
 *   A pass must not read a target that it never changes while it writes another: Mesa's
 *   llvmpipe (22.3 and 25.0 measured) then writes zero to that target instead of keeping
 *   it, whether the shader leaves the output alone or writes back the value it read. The
 *   flush pass with one entry per pixel would be such a pass (it composites nothing, and
 *   Mesa 25 compiles it to one that never changes the color); it is not drawn.
 * - RASTERIZATION_ORDER: image load/store without synchronization. Correct only where the
 *   rasterizer shades the fragments of a pixel one at a time in primitive order, as Mesa's
 *   llvmpipe does (one thread per screen tile runs the tile's binned primitives in submission
 *   order); a race anywhere else. Never chosen automatically.
 *
 * Private helper of SPT::RenderingBaselines, used by vtkHAVSVolumeMapper; not wrapped.
 */

#ifndef vtkHAVSKBuffer_h
#define vtkHAVSKBuffer_h

#include "SPTRenderingBaselinesModule.h" // For export macro
#include "vtkNew.h"                      // For the framebuffers
#include "vtkObject.h"
#include "vtkSceneDepthTexture.h" // For the scene depth

#include <memory> // For the quad helpers
#include <string> // For the shader definitions

class vtkOpenGLFramebufferObject;
class vtkOpenGLQuadHelper;
class vtkOpenGLRenderWindow;
class vtkShaderProgram;
class vtkTextureObject;
class vtkWindow;

class SPTRENDERINGBASELINES_EXPORT vtkHAVSKBuffer : public vtkObject
{
public:
  static vtkHAVSKBuffer* New();
  vtkTypeMacro(vtkHAVSKBuffer, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Whether the context has the OpenGL extension (core profile extension list).
  static bool HasExtension(const char* name);

  /**
   * Size the targets for a viewport of width x height pixels and a k-buffer of kbufferSize
   * (2 to 6) candidates, accessed as given. Reallocates only when one of these changed.
   */
  bool Prepare(vtkOpenGLRenderWindow* renWin, int width, int height, int kbufferSize, int access);

  /// The lines that the shaders' //HAVS::Defines::Dec tag becomes for this size and access.
  std::string GetShaderDefinitions() const;

  /// The scene depth of the viewport at (x, y) of what is bound for reading
  /// (vtkSceneDepthTexture::Capture()).
  void CaptureSceneDepth(int x, int y) { this->SceneDepth->Capture(x, y); }

  /**
   * Bind the targets for a pass of the k-buffer shaders: as draw buffers of the framebuffer,
   * or as image units; set the viewport to the targets and point the program's target and
   * scene depth uniforms at them. The caller pushes and pops the framebuffer bindings around
   * the passes and restores the viewport, scissor test, blending and color mask.
   */
  void BeginPass(vtkShaderProgram* program);

  /// After a pass: make its image writes visible to the next pass and release the bindings.
  void EndPass();

  /**
   * Empty every pixel's entries and color. Called with the caller's framebuffer bindings
   * pushed.
   */
  void Clear();

  /**
   * Blend the composited color premultiplied "over" what is bound for drawing, into the
   * viewport at (x, y).
   */
  void Resolve(int x, int y);

  ///@{
  /**
   * How many targets there are (the color, then entry pairs), and how many (scalar, distance)
   * entries they hold per pixel.
   */
  int GetNumberOfTargets() const { return 1 + this->KBufferSize / 2; }
  int GetNumberOfEntries() const { return this->KBufferSize - 1; }
  ///@}

  /// Bytes held on the GPU.
  size_t GetGPUMemorySize() const;

  void ReleaseGraphicsResources(vtkWindow* window);

protected:
  vtkHAVSKBuffer();
  ~vtkHAVSKBuffer() override;

private:
  vtkHAVSKBuffer(const vtkHAVSKBuffer&) = delete;
  void operator=(const vtkHAVSKBuffer&) = delete;

  void Allocate(vtkOpenGLRenderWindow* renWin, int depthFormat);

  static constexpr int MaximumTargets = 4;

  vtkOpenGLRenderWindow* Context = nullptr;
  int Width = 0;
  int Height = 0;
  int KBufferSize = 0;
  int AccessMode = 0;
  bool SceneDepthActive = false;

  vtkNew<vtkTextureObject> Targets[MaximumTargets];
  vtkNew<vtkSceneDepthTexture> SceneDepth;
  vtkNew<vtkOpenGLFramebufferObject> Framebuffer;
  std::unique_ptr<vtkOpenGLQuadHelper> Copy;
};

#endif
