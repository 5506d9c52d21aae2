/**
 * @class   vtkHAVSVolumeMapper
 * @brief   sorted baseline: hardware-assisted visibility sorting (HAVS) of unstructured grids
 *
 * vtkHAVSVolumeMapper volume renders a vtkUnstructuredGrid with point scalars (any linear or
 * quadratic 3D cells, split into tetrahedra once per input change) as described in
 *
 *   S. P. Callahan, M. Ikits, J. L. D. Comba and C. T. Silva, "Hardware-assisted visibility
 *   sorting for unstructured volume rendering", IEEE Transactions on Visualization and
 *   Computer Graphics 11(3), 2005.
 *
 * It is the sorted baseline against which the sorting-free vtkSPTVolumeMapper is measured, and
 * shares its pre-integration table, optical model and input handling:
 * - object space, once per input: the unique triangular faces of the tetrahedra, each marked
 *   boundary or interior;
 * - every frame, on the CPU: a key from each face's eye-to-centroid distance and a radix sort
 *   of the faces by that key; the faces are drawn nearest first (GetLastSortTime());
 * - image space, on the GPU: a k-buffer of KBufferSize fragments per pixel, each a (scalar,
 *   distance) pair. A fragment is inserted into its pixel's buffer; when the buffer is full,
 *   the two nearest entries bound a ray segment whose pre-integrated color and opacity are
 *   composited front to back, and the nearer is dropped. A flush pass composites what is left.
 *   A pixel stops changing once it is opaque (early ray termination).
 * - Rays that leave a non-convex mesh and enter it again cross a gap that contributes
 *   nothing: boundary faces face out of the mesh, so a fragment knows whether its ray leaves
 *   or enters the mesh there, and a segment from a fragment where the ray leaves the mesh to
 *   one where it enters it again is not composited. No length threshold is involved.
 *
 * The k-buffer approximates sorting: fragments that arrive more than KBufferSize - 1 places out
 * of order are composited out of order. That error, and the one of sorting faces by their
 * centroids, is what this mapper shows next to SPT.
 *
 * Each fragment reads, changes and writes its pixel's k-buffer. See
 * SetKBufferSynchronization() for how that read-modify-write is kept in primitive order.
 *
 * Opaque geometry drawn before the volume hides what lies behind it (the segment that reaches
 * into it ends at the last face in front of it). The camera may be anywhere: where the near
 * plane cuts the mesh, the cut (computed on the CPU from the tetrahedra that straddle the near
 * plane, in frames where it cuts the mesh's bounds) enters the k-buffer first, as faces where
 * the rays enter the mesh, so the segment from the near plane to the first face is composited
 * too (vtkHAVSNearCap). Cell scalars are not supported (HAVS interpolates point scalars over
 * faces).
 *
 * @sa
 * vtkSPTVolumeMapper vtkProjectedTetrahedraMapper vtkUnstructuredGridVolumeRayCastMapper
 */

#ifndef vtkHAVSVolumeMapper_h
#define vtkHAVSVolumeMapper_h

#include "SPTRenderingBaselinesModule.h" // For export macro
#include "vtkTetrahedralVolumeMapper.h"

#include <memory> // For the internals

class vtkRenderer;
class vtkVolume;
class vtkWindow;

class SPTRENDERINGBASELINES_EXPORT vtkHAVSVolumeMapper : public vtkTetrahedralVolumeMapper
{
public:
  static vtkHAVSVolumeMapper* New();
  vtkTypeMacro(vtkHAVSVolumeMapper, vtkTetrahedralVolumeMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Fragments the k-buffer sorts per pixel: KBufferSize - 1 stored entries and the incoming
   * fragment. Range 2 to 6, default 6 (the paper's k = 2 and k = 6 are its two settings).
   */
  vtkSetClampMacro(KBufferSize, int, 2, 6);
  vtkGetMacro(KBufferSize, int);
  ///@}

  enum KBufferSynchronizationType
  {
    AUTOMATIC = 0,
    FRAGMENT_SHADER_INTERLOCK = 1,
    FRAMEBUFFER_FETCH = 2,
    RASTERIZATION_ORDER = 3
  };

  ///@{
  /**
   * How the k-buffer's read-modify-write is kept in primitive order: FRAGMENT_SHADER_INTERLOCK
   * (GL_ARB_fragment_shader_interlock), FRAMEBUFFER_FETCH (GL_EXT_shader_framebuffer_fetch),
   * RASTERIZATION_ORDER (none: correct only where one pixel's fragments are shaded in order,
   * as on llvmpipe; never chosen automatically) or AUTOMATIC (default: the first of the two
   * extensions the context has, an error without either). See GetKBufferSynchronizationInUse().
   */
  vtkSetClampMacro(KBufferSynchronization, int, AUTOMATIC, RASTERIZATION_ORDER);
  vtkGetMacro(KBufferSynchronization, int);
  void SetKBufferSynchronizationToAutomatic() { this->SetKBufferSynchronization(AUTOMATIC); }
  void SetKBufferSynchronizationToFragmentShaderInterlock()
  {
    this->SetKBufferSynchronization(FRAGMENT_SHADER_INTERLOCK);
  }
  void SetKBufferSynchronizationToFramebufferFetch()
  {
    this->SetKBufferSynchronization(FRAMEBUFFER_FETCH);
  }
  void SetKBufferSynchronizationToRasterizationOrder()
  {
    this->SetKBufferSynchronization(RASTERIZATION_ORDER);
  }
  int GetKBufferSynchronizationInUse();
  ///@}

  ///@{
  /**
   * What the last render drew: the tetrahedra's unique faces and how many of those are on the
   * boundary, and the bytes this mapper holds on the GPU (vertices, sorted faces,
   * pre-integration table and k-buffer).
   */
  vtkIdType GetNumberOfFaces();
  vtkIdType GetNumberOfBoundaryFaces();
  vtkIdType GetGPUMemorySize() override;
  ///@}

  ///@{
  /**
   * The time split of the last render, in seconds: the CPU sort (face keys, radix sort and
   * the sorted triangle list), and the GPU time of the k-buffer passes (faces, flush and the
   * blend into the window; an OpenGL GL_TIME_ELAPSED query, -1 when the context could not
   * time it).
   */
  vtkGetMacro(LastSortTime, double);
  vtkGetMacro(LastGPUTime, double);
  ///@}

  /// Render the volume. Called by vtkVolume; not meant to be called directly.
  void Render(vtkRenderer* ren, vtkVolume* vol) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkHAVSVolumeMapper();
  ~vtkHAVSVolumeMapper() override;

  int KBufferSize = 6;
  int KBufferSynchronization = AUTOMATIC;
  double LastSortTime = 0.0;
  double LastGPUTime = 0.0;

private:
  vtkHAVSVolumeMapper(const vtkHAVSVolumeMapper&) = delete;
  void operator=(const vtkHAVSVolumeMapper&) = delete;

  bool PrepareInput(vtkRenderer* ren, vtkVolume* vol);
  void DrawKBuffer(const RenderTarget& target, int access);

  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif
