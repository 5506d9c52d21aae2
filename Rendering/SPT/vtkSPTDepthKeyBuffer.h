/**
 * @class   vtkSPTDepthKeyBuffer
 * @brief   per-repetition depth keys, for drawing several stochastic repetitions in one pass
 *
 * One pass of SPT keeps, per pixel, the nearest fragment that survived its random test. To
 * draw N repetitions with one traversal of the geometry, each fragment makes N independent
 * keep-or-discard decisions, and the nearest survivor of each repetition is found with an
 * atomic minimum on a depth key in layer r of this buffer (an r32ui 3D image: pixel x pixel x
 * repetition). A second traversal then adds each fragment's color once for every layer whose
 * minimum it holds. Two traversals for N repetitions instead of N, and the result is the same
 * image as N single passes with the same random numbers.
 *
 * With depth slabs (vtkSPTVolumeMapper::SetDepthSlabs()), each sample has one run of layers
 * per slab, slab after slab, and a second r32ui image holds per sample and slab the
 * SlabTerms sums of its segments' optical depth tau and tau-weighted color (tau, tau r,
 * tau g, tau b), in fixed point (GetSlabFixedOne() per unit), which DrawSlabsMeanColor()
 * turns into what the color traversals weight and correct a slab's segments with.
 *
 * Private helper of the SPT module; not wrapped.
 */

#ifndef vtkSPTDepthKeyBuffer_h
#define vtkSPTDepthKeyBuffer_h

#include "SPTRenderingSPTModule.h" // For export macro
#include "vtkNew.h"                // For the texture
#include "vtkObject.h"

#include <memory> // For the quad
#include <string> // For the slabs' defines
#include <vector> // For Read()

class vtkOpenGLQuadHelper;
class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkWindow;

class SPTRENDERINGSPT_EXPORT vtkSPTDepthKeyBuffer : public vtkObject
{
public:
  static vtkSPTDepthKeyBuffer* New();
  vtkTypeMacro(vtkSPTDepthKeyBuffer, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Whether the context has what this takes: image load/store and clear-texture (OpenGL 4.4,
  /// or the ARB extensions).
  static bool IsSupported(vtkOpenGLRenderWindow* renWin);

  /**
   * Size the buffer: width x height samples, one layer per repetition of a pass and depth
   * slab. The texture holds GetCompiledRepetitions(layers) layers per slab, and reallocates only
   * when that, the size or the context changes; the slabs' optical depths only when the size,
   * the slabs or the context change, so that they last for the frames of one image. Returns
   * false (with an error) when a texture cannot be allocated.
   */
  bool Prepare(vtkOpenGLRenderWindow* renWin, int width, int height, int layers, int slabs = 1);

  /// The fixed-point unit of the slabs' optical depths: their sums are the same in any order.
  static constexpr unsigned int GetSlabFixedOne() { return 1u << 16; }

  /// The sums per slab and sample: tau and the three of tau times color.
  static constexpr int SlabTerms = 4;

  ///@{
  /// Set every slab's sums to zero, and bind them as image unit `unit` (with Prepare()'s
  /// slabs > 1).
  void ClearSlabs();
  void BindSlabImage(int unit);

  ///@}

  /**
   * The repetitions a shader is compiled for when it draws `repetitions` at once: the next
   * power of two. The shaders loop over the count they are given (a uniform) and size only
   * their arrays by the compiled one, so that a handful of programs serve every count. A
   * program per count would stall every frame whose count is new (each is compiled on first
   * use), and the error target and the time budget choose counts freely.
   */
  static int GetCompiledRepetitions(int repetitions);

  /// Set the keys of the samples of `footprint` (x, y, width, height) to "nothing kept" (the
  /// largest key), every layer.
  void Clear(const int footprint[4]);

  /// Bind the keys as image unit `unit` for the fragment shaders, and make the writes of the
  /// previous traversal visible to the next one.
  void BindImage(int unit);
  static void UnbindImage(int unit);
  static void Barrier();

  /// Make `texture` an r32ui 3D texture of layers x width x height texels in the context, as
  /// the keys, the slabs' sums and the compute traversal's sums are; false if it cannot be
  /// allocated. BindIntegerImage() binds one as image unit `unit` for reading and writing.
  static bool CreateIntegerImage(
    vtkTextureObject* texture, vtkOpenGLRenderWindow* renWin, int layers, int width, int height);
  static void BindIntegerImage(vtkTextureObject* texture, int unit);

  /**
   * One full-screen pass over the keys bound as image unit `unit`, between a group's keys
   * traversal and its color traversal, for the first `repetitions` layers:
   * - with `sortKeys`, sort each sample's keys in increasing order, layers [0, secondHalfFrom)
   *   and [secondHalfFrom, repetitions) apart (of each slab) (a color traversal that only counts
   * the survivors behind a fragment then needs log2(repetitions) loads, not one per layer);
   * - write into the bound framebuffer's depth, per sample, a depth no nearer than the nearest
   *   survivor of each layer (the far plane where one kept nothing); with slabs, of each
   *   layer of the last slab that holds segments, as the slabs' controls bound as image unit
   *   `slabsUnit` tell (DrawSlabsMeanColor()). A traversal that tests against it skips the
   *   fragments behind all the survivors before shading them. The caller sets the depth test
   *   and mask, or disables the test when it wants no depth.
   * False if the shader does not compile.
   */
  bool PrepareSurvivors(
    int unit, int slabsUnit, int repetitions, int secondHalfFrom, bool sortKeys);

  /**
   * One full-screen pass (vtkSPTSlabsMeanFS.glsl) over the slabs' sums bound as image unit
   * `unit`: it turns them into the slabs' controls, in place, and writes into the bound
   * framebuffer the mean color of the slabs' control variate per sample. `defines` are the
   * slabs' shader defines. The caller sets the blending. False if the shader does not compile.
   */
  bool DrawSlabsMeanColor(int unit, const std::string& defines);

  ///@{
  /// Read the keys of the layers in use back to the host (sample by sample, each sample's
  /// layers in order; with slabs, all allocated layers), and write keys of the same size back;
  /// for reductions across processes.
  std::vector<unsigned int> Read();
  void Write(const std::vector<unsigned int>& keys);
  /// The same for the slabs' sums (sample by sample, each sample's slabs and terms in order).
  std::vector<unsigned int> ReadSlabs();
  void WriteSlabs(const std::vector<unsigned int>& sums);
  ///@}

  /// Bytes held on the GPU (the allocated layers).
  size_t GetGPUMemorySize() const;

  void ReleaseGraphicsResources(vtkWindow* window);

protected:
  vtkSPTDepthKeyBuffer();
  ~vtkSPTDepthKeyBuffer() override;

private:
  vtkSPTDepthKeyBuffer(const vtkSPTDepthKeyBuffer&) = delete;
  void operator=(const vtkSPTDepthKeyBuffer&) = delete;

  vtkOpenGLRenderWindow* Context = nullptr;
  int Width = 0;
  int Height = 0;
  int Layers = 0;          // in use: the group's repetitions (all allocated ones with slabs)
  int AllocatedLayers = 0; // held: GetCompiledRepetitions(repetitions) per slab
  int Slabs = 1;
  vtkNew<vtkTextureObject> Keys;
  vtkNew<vtkTextureObject> SlabDepths; // (SlabTerms * slab + term, sample): sums, controls
  int SlabWidth = 0;
  int SlabHeight = 0;
  int SlabCount = 0; // of the allocated SlabDepths
  std::unique_ptr<vtkOpenGLQuadHelper> SlabsMean;
  std::string SlabsMeanDefines;                      // what SlabsMean is compiled with
  std::unique_ptr<vtkOpenGLQuadHelper> Survivors[2]; // by sortKeys
  int SurvivorsRepetitions[2] = { 0, 0 };            // what each is compiled for
  int SurvivorsSlabs[2] = { 1, 1 };
  bool PrepareSlabs(vtkOpenGLRenderWindow* renWin, int width, int height, int slabs);
};

#endif
