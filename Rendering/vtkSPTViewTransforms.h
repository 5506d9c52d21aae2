/**
 * @class   vtkSPTViewTransforms
 * @brief   the transforms of one frame, in units of the mesh's own size
 *
 * The mappers of the module draw meshes whose coordinates vtkSPTMeshBuffers has shifted and
 * scaled to O(1). This class composes, in double, the transforms from those normalized model
 * coordinates to view and clip coordinates for one renderer and volume, with the view
 * coordinates divided by the mesh's scale as well (normalized view coordinates), so that float
 * precision holds on the GPU whatever the magnitude of the data's coordinates. It also keeps
 * the linear part of view -> model, which turns view-space lengths into lengths in the
 * normalized model units in which the opacity is measured.
 *
 * Private helper of the SPT module, shared by its mappers; not wrapped.
 */

#ifndef vtkSPTViewTransforms_h
#define vtkSPTViewTransforms_h

#include "SPTRenderingModule.h" // For export macro

class vtkRenderer;
class vtkSPTMeshBuffers;
class vtkVolume;

class SPTRENDERING_EXPORT vtkSPTViewTransforms
{
public:
  /**
   * Compose the transforms for the active camera of `ren`, the matrix of `vol` and the
   * normalization of `mesh`.
   */
  void Compute(vtkRenderer* ren, vtkVolume* vol, const vtkSPTMeshBuffers* mesh);

  ///@{
  /**
   * Column-major, as glUniformMatrix*fv expects: normalized model -> normalized view, view ->
   * clip, clip -> view, and the linear part of normalized view -> normalized model.
   */
  float MCVC[16];
  float VCDC[16];
  float DCVC[16];
  float VCMCLinear[9];
  ///@}

  ///@{
  /**
   * The same transforms in double, row-major (element [row][column]), for CPU-side use.
   */
  double ModelToView[4][4];
  double ViewToClip[4][4];
  double ViewToModelLinear[3][3];
  ///@}

  /**
   * Normalized view coordinates are view (camera) coordinates divided by ViewScale.
   */
  double ViewScale = 1.0;

  /**
   * Whether the camera projects in parallel (otherwise in perspective, with the eye at the
   * origin of the view coordinates).
   */
  bool ParallelProjection = false;
};

#endif
