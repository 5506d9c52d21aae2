/**
 * @file    vtkVolumeViewMatrices.h
 * @brief   the matrices of one frame in the normalized units of a mesh; shared, not wrapped
 *
 * The mappers hand the GPU coordinates in units of the mesh's own size (vtkTetrahedralMesh
 * shifts and scales the points to O(1)), and compose every matrix in double on the CPU, so
 * that float precision holds whatever the magnitude of the data's coordinates.
 */

#ifndef vtkVolumeViewMatrices_h
#define vtkVolumeViewMatrices_h

#include "SPTRenderingCoreModule.h" // For export macro

#include <string> // For ClippingPlaneDefine()
#include <vector> // For AppendSignature()

class vtkPlaneCollection;
class vtkRenderer;
class vtkShaderProgram;
class vtkTetrahedralMesh;
class vtkVolume;

struct SPTRENDERINGCORE_EXPORT vtkVolumeViewMatrices
{
  /// Normalized model -> normalized view, column-major (as glUniformMatrix4fv expects).
  float MCVC[16];
  /// Normalized view -> clip, and its inverse.
  float VCDC[16];
  float DCVC[16];
  /// The linear part of view -> model: turns view-space segments into lengths in the
  /// normalized model units of the mesh (column-major 3x3).
  float VCMCLinear[9];
  /// The same transforms in double, row-major (element [row][column]), for CPU-side use.
  double ModelToView[4][4];
  double ViewToClip[4][4];
  double ModelToViewLinear[3][3];
  double ViewToModelLinear[3][3];
  /// Normalized view coordinates are view (camera) coordinates divided by ViewScale.
  double ViewScale = 1.0;
  /// Whether the camera projects in parallel.
  bool ParallelProjection = false;
  /// Whether the near plane cuts the mesh's bounding box (or some of it lies behind the eye), as
  /// with the camera inside or close to the mesh: then some tetrahedra may be cut by it. Side
  /// planes, as in a view zoomed into the mesh, only clip what the outlines cover.
  bool NearPlaneCutsBounds = false;
  /// Normalized device coordinates that bound the projection of the mesh's bounds, within the
  /// view: xmin, xmax, ymin, ymax (the whole view, -1 to 1, where the near plane cuts them).
  double ScreenBounds[4] = { -1.0, 1.0, -1.0, 1.0 };
  /// An upper bound of the x and y extents, in normalized device coordinates, of the
  /// projection of a segment of unit length (normalized model units) that lies within the
  /// mesh's bounds; zero when the near plane cuts the bounds (no bound then).
  double NDCPerLength[2] = { 0.0, 0.0 };
  /// The same for a segment across the view at the depth of the bounds' centre: the typical
  /// extent rather than a bound (zero when the near plane cuts the bounds).
  double TypicalNDCPerLength[2] = { 0.0, 0.0 };
  /// The distances along the view direction (camera units, in front of the eye positive) of
  /// the mesh's bounds' nearest and farthest corners, and of the near and far planes.
  double BoundsDistance[2] = { 0.0, 0.0 };
  double ClippingDistance[2] = { 0.0, 1.0 };
  /// Whether model -> view mirrors space (negative determinant), which swaps the facing of
  /// triangles on the screen.
  bool Mirrored = false;

  /// The most clipping planes a mapper honours (as VTK's polygonal mappers).
  static constexpr int MaximumClippingPlanes = 6;
  /// The mapper's clipping planes in normalized view coordinates, each a unit normal and an
  /// offset: a point x is kept where dot(plane, (x, 1)) >= 0, the side of the vtkPlane that its
  /// normal points to, as VTK's mappers keep.
  int ClippingPlaneCount = 0;
  float ClippingPlanes[MaximumClippingPlanes][4] = {};

  /**
   * The matrices of the renderer's active camera for the volume's matrix and the mesh's
   * normalization.
   */
  void Compute(vtkRenderer* ren, vtkVolume* vol, const vtkTetrahedralMesh* mesh);

  /**
   * ClippingPlanes from planes in world coordinates (after Compute(), whose view scale they
   * share); false, with nothing set, for more than MaximumClippingPlanes of them.
   */
  bool ComputeClippingPlanes(vtkRenderer* ren, vtkPlaneCollection* planes);

  /**
   * The shaders' clipping planes: the uniforms `clippingPlanes` (vec4[6]) and
   * `clippingPlaneCount`, where the program uses them.
   */
  void SetClippingPlaneUniforms(vtkShaderProgram* program) const;

  /// The uniforms MCVCMatrix, VCDCMatrix and VCMCLinear, and the clipping planes.
  void SetUniforms(vtkShaderProgram* program) const;

  /// "#define <prefix>_CLIPPING_PLANES\n" where there are clipping planes, else nothing.
  std::string ClippingPlaneDefine(const std::string& prefix) const;

  /**
   * Appends what of this frame changes the image: MCVC, VCDC and the clipping planes as they
   * are now (a vtkPlane changed in place, as an interactive widget changes it, changes no
   * MTime of the mapper or of its plane collection).
   */
  void AppendSignature(std::vector<double>& signature) const;

  /// The largest singular value of a matrix: the most it stretches a length.
  static double LargestSingularValue(const double matrix[3][3]);
};

#endif
