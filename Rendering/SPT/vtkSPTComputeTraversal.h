/**
 * @class   vtkSPTComputeTraversal
 * @brief   SPT's traversals of the small cells as compute passes
 *
 * The cells that SPT draws as points cover a few samples each. On a software rasterizer such
 * as llvmpipe, setting up and binning one point per cell runs on the application's thread and
 * is most of a traversal of a large mesh; a compute pass does the same work per (cell, sample)
 * on every core (vtkSPTTetrahedraCS.glsl). Its depth keys are atomic minima and its sums fixed
 * point (FixedPointOne per unit), both the same in any order: an image is the same from one
 * run to the next, and differs from the points' image only by the fixed point's rounding.
 *
 * This object holds the compiled programs (VTK 9.2's vtkShaderProgram has no compute stage:
 * they are built through OpenGL and set their uniforms through vtkShaderProgram's setters)
 * and the fixed-point sums.
 *
 * Private helper of the SPT module; not wrapped.
 */

#ifndef vtkSPTComputeTraversal_h
#define vtkSPTComputeTraversal_h

#include "SPTRenderingSPTModule.h" // For export macro
#include "vtkNew.h"                // For the sums' texture
#include "vtkObject.h"
#include "vtkSmartPointer.h" // For the programs

#include <map>    // For the programs
#include <memory> // For the quad
#include <string> // For the sources

class vtkOpenGLQuadHelper;
class vtkOpenGLRenderWindow;
class vtkShaderProgram;
class vtkTextureObject;
class vtkWindow;

class SPTRENDERINGSPT_EXPORT vtkSPTComputeTraversal : public vtkObject
{
public:
  static vtkSPTComputeTraversal* New();
  vtkTypeMacro(vtkSPTComputeTraversal, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * One unit of the sums' fixed point: 2^16, so that a sample's sums within +-32,768 fit in
   * 32 bits as signed integers (the optical depth of about 2,000 nearly opaque segments; the
   * colors of a group's repetitions, at most the group's size times the sum of the opacities
   * along the ray; a depth slab's control variate may subtract), with a rounding of 2^-17 per
   * term.
   */
  static constexpr double FixedPointOne = 65536.0;

  /// The invocations per work group of the programs (SPT_COMPUTE_GROUP_SIZE).
  static constexpr int GroupSize = 64;

  /// Whether the context has compute shaders (OpenGL 4.3, or the ARB extension).
  static bool IsSupported(vtkOpenGLRenderWindow* renWin);

  /// Whether the context's renderer is a software rasterizer (Mesa's llvmpipe or softpipe,
  /// SwiftShader), where compute passes pay for small cells.
  static bool IsSoftwareRasterizer(vtkOpenGLRenderWindow* renWin);

  /**
   * Whether frames in this context compute their small cells: on any renderer with
   * `onAnyRenderer` (a mapper's COMPUTE_TRAVERSAL_ON), else only on a software rasterizer
   * (COMPUTE_TRAVERSAL_AUTO); never without compute shaders, nor after a program failed to
   * build in the context, nor for a pass of `width` x `height` samples larger than the
   * context's 3D textures, which hold the sums (GL_MAX_3D_TEXTURE_SIZE). The context is asked
   * once, not every frame.
   */
  bool IsWanted(vtkOpenGLRenderWindow* renWin, bool onAnyRenderer, int width, int height);

  /// The program built from this compute shader source, compiled once per source and context;
  /// nullptr (with the compiler's log as a warning) if it does not build, and from then on
  /// IsWanted() is false in this context: the caller rasterizes those cells instead.
  vtkShaderProgram* GetProgram(vtkOpenGLRenderWindow* renWin, const std::string& source);

  /// Bind `program` (one of GetProgram()'s), after VTK's shader cache has released its own:
  /// uniforms set next go to it.
  static void Use(vtkOpenGLRenderWindow* renWin, vtkShaderProgram* program);

  /// Run the bound `program` over the cells [first, first + count) (it sets firstCell and
  /// cellCount), and make its writes visible to what reads them next. The caller sets the
  /// other uniforms and binds the textures and images it reads.
  static void Dispatch(vtkShaderProgram* program, vtkIdType first, vtkIdType count);

  /// Size the fixed-point sums for width x height samples (eight per sample: two targets of
  /// four terms) and set them to zero. False (with an error) if the texture cannot be
  /// allocated.
  bool PrepareSums(vtkOpenGLRenderWindow* renWin, int width, int height);

  /// Bind the sums as image unit `unit` for the compute pass (vtkSPTDepthKeyBuffer::UnbindImage()
  /// releases it).
  void BindSumsImage(int unit);

  /// Add the sums into the bound framebuffer's first target, and with `secondTarget` the second
  /// four into its second, one fragment per sample (the caller sets additive blending and turns
  /// the depth test off). False if the shader does not compile.
  bool AddSums(vtkOpenGLRenderWindow* renWin, bool secondTarget);

  /// Bytes held on the GPU.
  size_t GetGPUMemorySize() const;

  void ReleaseGraphicsResources(vtkWindow* window);

protected:
  vtkSPTComputeTraversal();
  ~vtkSPTComputeTraversal() override;

private:
  vtkSPTComputeTraversal(const vtkSPTComputeTraversal&) = delete;
  void operator=(const vtkSPTComputeTraversal&) = delete;

  // Release what was built in `window` (programs, sums), keeping what IsWanted() learned of the
  // context it queried last.
  void ReleaseContextResources(vtkWindow* window);

  vtkOpenGLRenderWindow* Context = nullptr;
  vtkOpenGLRenderWindow* QueriedContext = nullptr; // the context the next three describe
  bool Supported = false;
  bool Software = false;
  int MaxSize = 0; // texels per side of a 3D texture
  bool BuildFailed = false;
  std::map<std::string, vtkSmartPointer<vtkShaderProgram>> Programs;
  int Width = 0;
  int Height = 0;
  vtkNew<vtkTextureObject> Sums;
  std::unique_ptr<vtkOpenGLQuadHelper> AddSumsQuads[2]; // by secondTarget
};

#endif
