/**
 * @class   vtkHAVSNearCap
 * @brief   where the near plane cuts a tetrahedral mesh, the cross-section as entry faces
 *
 * With the camera inside a mesh, or with the near plane cutting it, a view ray starts inside
 * a tetrahedron: the first face it meets is where it leaves that tetrahedron, and the segment
 * from the near plane to that face would be missing from HAVS's k-buffer, which composites
 * only between the faces it receives. This helper builds, every frame the near plane cuts the
 * mesh's bounds, the polygons where the near plane cuts each tetrahedron (a triangle or a
 * quadrilateral, with the scalar interpolated along the cut edges) as boundary faces wound
 * to face the eye. Their fragments enter the k-buffer as points where the ray enters the mesh,
 * at the near plane, so the first segment is composited exactly like every other one.
 *
 * The cut points are computed per edge from its two vertices in a fixed order, so the
 * polygons of neighbouring tetrahedra share their edges exactly and cover every pixel once.
 * They lie on the near plane: draw them with GL_DEPTH_CLAMP so that none is clipped.
 *
 * Private helper of SPT::RenderingBaselines, used by vtkHAVSVolumeMapper; not wrapped.
 */

#ifndef vtkHAVSNearCap_h
#define vtkHAVSNearCap_h

#include "SPTRenderingBaselinesModule.h" // For export macro
#include "vtkBatchedVertexArray.h"       // For the vertex array
#include "vtkNew.h"                      // For the buffers

#include <vector> // For the CPU arrays

class vtkOpenGLBufferObject;
class vtkShaderProgram;
class vtkTetrahedralMesh;

class SPTRENDERINGBASELINES_EXPORT vtkHAVSNearCap
{
public:
  vtkHAVSNearCap();
  ~vtkHAVSNearCap();
  vtkHAVSNearCap(const vtkHAVSNearCap&) = delete;
  vtkHAVSNearCap& operator=(const vtkHAVSNearCap&) = delete;

  /**
   * Cut the mesh by the near plane of `modelToClip` (row-major, normalized model coordinates
   * to clip coordinates). `points` and `scalars` are the mesh's vertices (3 floats each) and
   * their scalars in [0, 1]; the cap's scalars are offset by `boundaryOffset`. The triangles
   * wind counterclockwise on the screen when `counterClockwise`, else clockwise. Returns the
   * number of triangles. Worth calling only where the near plane cuts the mesh's bounds
   * (vtkVolumeViewMatrices::NearPlaneCutsBounds).
   */
  vtkIdType Build(const vtkTetrahedralMesh* mesh, const std::vector<float>& points,
    const std::vector<float>& scalars, const double modelToClip[4][4], float boundaryOffset,
    bool counterClockwise);

  vtkIdType GetNumberOfTriangles() const { return vtkIdType(this->Scalars.size() / 3); }

  /**
   * Upload the triangles of the last Build() and draw them with the program's attributes
   * `vertexMC` and `scalarTF`. Returns false when the upload failed.
   */
  bool Draw(vtkShaderProgram* program);

  size_t GetGPUMemorySize() const { return this->UploadedBytes; }
  void ReleaseGraphicsResources();

private:
  void CutTetrahedron(const unsigned int ids[4], const double distance[4], bool counterClockwise);
  void AddCutPoint(unsigned int a, unsigned int b, double da, double db, float cut[4]) const;

  const std::vector<float>* Points = nullptr;
  const std::vector<float>* PointScalars = nullptr;
  float BoundaryOffset = 0.0f;
  const double (*ModelToClip)[4] = nullptr;
  std::vector<float> Vertices; // 3 per vertex, 3 vertices per triangle
  std::vector<float> Scalars;
  vtkNew<vtkOpenGLBufferObject> VertexBuffer;
  vtkNew<vtkOpenGLBufferObject> ScalarBuffer;
  vtkBatchedVertexArray VertexArray;
  size_t UploadedBytes = 0;
};

#endif
