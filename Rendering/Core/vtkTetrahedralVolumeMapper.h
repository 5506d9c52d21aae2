/**
 * @class   vtkTetrahedralVolumeMapper
 * @brief   abstract base of the module's mappers of unstructured grids split into tetrahedra
 *
 * vtkTetrahedralVolumeMapper owns what vtkSPTVolumeMapper, vtkHAVSVolumeMapper and
 * vtkPBVRVolumeMapper share: how a multi-component scalar array becomes one scalar, the
 * resolution of the pre-integration table, the input prepared as tetrahedra on the CPU (once
 * per change of the input or of the scalar selection), and the checks a frame starts with:
 * an OpenGL render window with pixels in the viewport, a volume property that can be rendered,
 * and finite matrices. Errors are reported once per build of the mesh, so that a scene drawn
 * again and again does not repeat them.
 *
 * @sa
 * vtkStochasticVolumeMapper vtkUnstructuredGridVolumeMapper
 */

#ifndef vtkTetrahedralVolumeMapper_h
#define vtkTetrahedralVolumeMapper_h

#include "SPTRenderingCoreModule.h" // For export macro
#include "vtkNew.h"                 // For the mesh
#include "vtkUnstructuredGridVolumeMapper.h"

class vtkOpenGLRenderWindow;
class vtkRenderer;
class vtkTetrahedralMesh;
class vtkVolume;
class vtkWindow;
struct vtkVolumeViewMatrices;

class SPTRENDERINGCORE_EXPORT vtkTetrahedralVolumeMapper : public vtkUnstructuredGridVolumeMapper
{
public:
  vtkTypeMacro(vtkTetrahedralVolumeMapper, vtkUnstructuredGridVolumeMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Samples of the pre-integration table along each scalar axis (front and back). Range 8 to
   * 1024, default 128. Used by the mappers that pre-integrate (SPT and HAVS-like); PBVR samples
   * the transfer functions per particle instead. Integrating the table takes time that grows
   * with the cube of this resolution and with the thickness resolution (about 0.25 s at the
   * defaults, on two cores); a table of more than 1 GiB, or of more than 100 times the
   * default's integration time, is refused with an error (512 x 512 x 64 is accepted).
   */
  vtkSetClampMacro(PreIntegrationScalarResolution, int, 8, 1024);
  vtkGetMacro(PreIntegrationScalarResolution, int);
  ///@}

  ///@{
  /**
   * Samples of the pre-integration table along the thickness axis, from zero to the longest
   * edge of the mesh (spaced by the square root of the thickness). Range 4 to 1024,
   * default 64. Used by the mappers that pre-integrate.
   */
  vtkSetClampMacro(PreIntegrationThicknessResolution, int, 4, 1024);
  vtkGetMacro(PreIntegrationThicknessResolution, int);
  ///@}

  enum VectorModeType
  {
    MAGNITUDE = 0,
    COMPONENT = 1
  };

  ///@{
  /**
   * How a multi-component scalar array becomes one scalar: its MAGNITUDE (default) or one
   * COMPONENT, chosen by VectorComponent (default 0). Single-component arrays are used as is.
   */
  vtkSetClampMacro(VectorMode, int, MAGNITUDE, COMPONENT);
  vtkGetMacro(VectorMode, int);
  void SetVectorModeToMagnitude() { this->SetVectorMode(MAGNITUDE); }
  void SetVectorModeToComponent() { this->SetVectorMode(COMPONENT); }
  vtkSetClampMacro(VectorComponent, int, 0, VTK_INT_MAX);
  vtkGetMacro(VectorComponent, int);
  ///@}

  ///@{
  /**
   * What the last render drew: tetrahedra, and cells left out (non-finite coordinates or
   * scalars).
   */
  vtkIdType GetNumberOfTetrahedra();
  vtkIdType GetNumberOfSkippedCells();
  ///@}

  /**
   * The bytes this mapper holds on the GPU.
   */
  virtual vtkIdType GetGPUMemorySize() = 0;

  /**
   * Release every GPU resource this mapper holds for the window.
   */
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkTetrahedralVolumeMapper();
  ~vtkTetrahedralVolumeMapper() override;

  /// What a frame draws into: the OpenGL window and the renderer's tiled viewport.
  struct RenderTarget
  {
    vtkOpenGLRenderWindow* Window = nullptr;
    int Width = 0;
    int Height = 0;
    int X = 0;
    int Y = 0;
  };

  /**
   * The renderer's OpenGL window and viewport. False, with an error, when the window is not an
   * OpenGL one or its context is older than OpenGL 3.2 (the error names the version found and
   * what to do, once per context); false without one when the viewport has no pixels. The
   * window's context is current on return. If this mapper last drew into another window, what
   * it holds there is released first: a mapper keeps its GPU resources in one context at a time.
   */
  bool BeginFrame(vtkRenderer* ren, RenderTarget& target);

  /**
   * Update the input and rebuild the mesh if it changed, with the scalar selection and the
   * vector mode; then check the volume's property. True when there are tetrahedra to draw.
   * `cellScalars` says whether the mapper renders cell scalars.
   */
  bool PrepareMesh(vtkVolume* vol, bool cellScalars);

  /**
   * Compute the frame's matrices and the mapper's clipping planes in them; false, with an
   * error, when they are not finite (a camera or a volume transform with NaN or Inf in it, as
   * ResetCamera() makes for such bounds) or there are more clipping planes than the shaders
   * take (vtkVolumeViewMatrices::MaximumClippingPlanes).
   */
  bool ComputeMatrices(vtkRenderer* ren, vtkVolume* vol, vtkVolumeViewMatrices& matrices);

  /**
   * Whether opaque geometry may have been drawn into the renderer's depth buffer before the
   * volume: a visible 3D prop other than a volume with opaque geometry, or a depth buffer
   * preserved from an earlier renderer. Without it, the shaders leave out the scene depth.
   */
  static bool HasOpaqueScene(vtkRenderer* ren);

  /// The input as tetrahedra, as the last PrepareMesh() built it.
  vtkTetrahedralMesh* GetMesh() const { return this->Mesh; }
  /// The context this mapper's GPU resources live in (null before the first frame).
  vtkOpenGLRenderWindow* GetContext() const { return this->Context; }

  int PreIntegrationScalarResolution = 128;
  int PreIntegrationThicknessResolution = 64;
  int VectorMode = MAGNITUDE;
  int VectorComponent = 0;

private:
  vtkTetrahedralVolumeMapper(const vtkTetrahedralVolumeMapper&) = delete;
  void operator=(const vtkTetrahedralVolumeMapper&) = delete;

  vtkNew<vtkTetrahedralMesh> Mesh;
  vtkOpenGLRenderWindow* Context = nullptr;
  vtkMTimeType ReportedMeshError = 0;
  vtkMTimeType ReportedSkippedCells = 0;
  vtkMTimeType ReportedContextError = 0;

  /// False, with the error above, when the window's context is older than OpenGL 3.2.
  bool CheckContext(vtkOpenGLRenderWindow* window);
};

#endif
