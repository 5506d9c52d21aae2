/**
 * @class   vtkHAVSFaceBuffers
 * @brief   the unique triangles of a tetrahedral mesh, radix-sorted by distance every frame
 *
 * The object-space half of Hardware-Assisted Visibility Sorting (Callahan, Ikits, Comba and
 * Silva 2005, the paper vtkHAVSVolumeMapper cites):
 * - once per input: the unique triangular faces of the tetrahedra, each marked boundary (a
 *   face of one tetrahedron) or interior (shared by two);
 * - every frame: a key from each face's eye-to-centroid distance (view coordinates, so that a
 *   scaled vtkVolume sorts as it is seen), an LSD radix sort of the faces by that key, nearest
 *   first, and the triangle list in that order. Boundary and interior faces are sorted
 *   together, in one list; nothing else is sorted.
 *
 * Boundary faces are wound so that their normal (right-hand rule) points out of the mesh, and
 * they index copies of their vertices whose scalar is offset by BoundaryScalarOffset. A
 * fragment thus knows from its scalar that it lies on the boundary, and from its facing
 * whether the view ray enters or leaves the mesh there: the k-buffer composites nothing between
 * a fragment where the ray leaves the mesh and one where it enters it again (the gaps of
 * non-convex meshes).
 *
 * Private helper of SPT::RenderingBaselines, used by vtkHAVSVolumeMapper; not wrapped.
 */

#ifndef vtkHAVSFaceBuffers_h
#define vtkHAVSFaceBuffers_h

#include "SPTRenderingBaselinesModule.h" // For export macro
#include "vtkBatchedVertexArray.h"       // For the vertex array
#include "vtkNew.h"                      // For the buffers
#include "vtkObject.h"
#include "vtkTimeStamp.h" // For the caches

#include <cstdint> // For the keys
#include <vector>  // For the CPU arrays

class vtkOpenGLBufferObject;
class vtkOpenGLRenderWindow;
class vtkShaderProgram;
class vtkTetrahedralMesh;
class vtkWindow;

class SPTRENDERINGBASELINES_EXPORT vtkHAVSFaceBuffers : public vtkObject
{
public:
  static vtkHAVSFaceBuffers* New();
  vtkTypeMacro(vtkHAVSFaceBuffers, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Added to the scalar (in [0, 1]) of the vertex copies that boundary faces use.
  static constexpr float BoundaryScalarOffset = 2.0f;

  /// Rebuild the faces when the mesh was rebuilt since the last call (point scalars only).
  void Update(const vtkTetrahedralMesh* mesh);

  ///@{
  /**
   * What Update() built: 3 vertex ids per face, a boundary mark per face, and the vertices
   * (normalized model coordinates, 3 per vertex; and the scalar of each, offset by
   * BoundaryScalarOffset on the copies that boundary faces use).
   */
  vtkIdType GetNumberOfFaces() const { return vtkIdType(this->Boundary.size()); }
  vtkIdType GetNumberOfBoundaryFaces() const { return this->NumberOfBoundaryFaces; }
  const std::vector<unsigned int>& GetFaces() const { return this->Faces; }
  const std::vector<unsigned char>& GetBoundary() const { return this->Boundary; }
  const std::vector<float>& GetVertices() const { return this->Vertices; }
  const std::vector<float>& GetVertexScalars() const { return this->VertexScalars; }
  ///@}

  /**
   * Sort the faces by the distance of their centroids from the eye, nearest first. The
   * matrix (column-major) takes the normalized model coordinates of the vertices to view
   * coordinates; in parallel projection the key is the depth along the view direction.
   */
  void Sort(const float modelToView[16], bool parallelProjection);

  ///@{
  /**
   * The last sort: face ids nearest first, and the CPU time it took in seconds (keys, radix
   * sort and the sorted triangle list).
   */
  const std::vector<unsigned int>& GetOrder() const { return this->Order; }
  double GetLastSortTime() const { return this->LastSortTime; }
  ///@}

  /// A float as an unsigned integer of the same order (negative floats included).
  static uint32_t SortableKey(float value);

  /**
   * Least-significant-digit radix sort of values by keys (8-bit digits, stable); scratch
   * vectors are resized as needed and reused.
   */
  static void RadixSort(std::vector<uint32_t>& keys, std::vector<unsigned int>& values,
    std::vector<uint32_t>& scratchKeys, std::vector<unsigned int>& scratchValues);

  /// Upload the vertices (when they changed) and the triangles in the last sort's order.
  bool Upload(vtkOpenGLRenderWindow* renWin);

  /**
   * Draw the sorted triangles of the last Upload(), with the vertices bound to the program's
   * attributes `vertexMC` and `scalarTF`.
   */
  void Draw(vtkShaderProgram* program);

  size_t GetGPUMemorySize() const;
  void ReleaseGraphicsResources(vtkWindow* window);

protected:
  vtkHAVSFaceBuffers();
  ~vtkHAVSFaceBuffers() override;

private:
  vtkHAVSFaceBuffers(const vtkHAVSFaceBuffers&) = delete;
  void operator=(const vtkHAVSFaceBuffers&) = delete;

  void BuildVertices(const vtkTetrahedralMesh* mesh, const std::vector<unsigned int>& boundaryCopy,
    unsigned int numberOfCopies);

  std::vector<unsigned int> Faces;
  std::vector<unsigned char> Boundary;
  std::vector<float> Centroids;
  std::vector<float> Vertices;
  std::vector<float> VertexScalars;
  vtkIdType NumberOfBoundaryFaces = 0;
  vtkMTimeType MeshBuildTime = 0;
  vtkTimeStamp BuildTime;

  std::vector<uint32_t> Keys;
  std::vector<uint32_t> ScratchKeys;
  std::vector<unsigned int> Order;
  std::vector<unsigned int> ScratchOrder;
  std::vector<unsigned int> SortedTriangles;
  double LastSortTime = 0.0;

  vtkOpenGLRenderWindow* Context = nullptr;
  vtkTimeStamp UploadTime;
  vtkNew<vtkOpenGLBufferObject> PointBuffer;
  vtkNew<vtkOpenGLBufferObject> ScalarBuffer;
  vtkNew<vtkOpenGLBufferObject> IndexBuffer;
  vtkBatchedVertexArray VertexArray;
  size_t VertexBytes = 0;
  size_t IndexBytes = 0;
};

#endif
