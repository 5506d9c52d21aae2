/**
 * @class   vtkSPTMeshBuffers
 * @brief   a prepared tetrahedral mesh on the GPU, as SPT's shaders draw and read it
 *
 * Uploads a vtkTetrahedralMesh into vertex and index buffers (points, point scalars, four point
 * ids per tetrahedron), which a draw binds to the attributes `vertexMC` and `scalarTF`, and
 * exposes the same buffers as buffer textures for the fragment stage, which reads whole cells
 * (the tetrahedra cut by a clipping plane, and cell scalars). A draw of millions of tetrahedra is
 * split into batches that stay within GL's limits.
 *
 * The tetrahedra are uploaded in classes of size: by their longest edge, a factor of sqrt(2)
 * apart, smallest first, each class in the mesh's order (which keeps the locality of the
 * input's numbering). The cells whose mean projection fills too little of the square of their
 * longest edge (needles and slivers) come after all the others, in classes of their own. So
 * the well-shaped cells no longer than a length are a leading range, which a frame draws as
 * points, and the rest one more range (vtkSPTFrame); each draw touches only its cells.
 * GetMeshIndexTexture() keeps each uploaded cell's index in the mesh, for its random numbers.
 *
 * Private helper of vtkSPTVolumeMapper; not wrapped.
 */

#ifndef vtkSPTMeshBuffers_h
#define vtkSPTMeshBuffers_h

#include "SPTRenderingSPTModule.h" // For export macro
#include "vtkBatchedVertexArray.h" // For the vertex array
#include "vtkNew.h"                // For the buffers
#include "vtkObject.h"
#include "vtkSmartPointer.h"    // For the buffers
#include "vtkTetrahedralMesh.h" // For GetMesh()
#include "vtkTextureObject.h"   // For GetScalarTexture()
#include "vtkTimeStamp.h"       // For the upload time

#include <vector> // For the classes of size

class vtkOpenGLBufferObject;
class vtkOpenGLRenderWindow;
class vtkShaderProgram;
class vtkWindow;

class SPTRENDERINGSPT_EXPORT vtkSPTMeshBuffers : public vtkObject
{
public:
  static vtkSPTMeshBuffers* New();
  vtkTypeMacro(vtkSPTMeshBuffers, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Upload the mesh to the context's buffers, unless this mesh, as built, is there already.
  /// False, with an error, when the context cannot hold it.
  bool Upload(vtkOpenGLRenderWindow* renWin, vtkTetrahedralMesh* mesh);

  /// The mesh last uploaded (null before the first Upload()).
  vtkTetrahedralMesh* GetMesh() const { return this->Mesh; }

  /// Bind the vertex arrays to the attributes `vertexMC` (and `scalarTF` for point scalars) of
  /// the program, and the tetrahedron indices; the cell scalars, if any, are a buffer texture.
  void Bind(vtkShaderProgram* program);
  void Unbind();

  /// The same buffers as buffer textures, for shaders that read a whole cell: the four point
  /// ids of each tetrahedron (RGBA32UI), the points (RGB32F) and the scalars (R32F, per point
  /// or, with cell scalars, per tetrahedron). Null before a successful Upload().
  vtkTextureObject* GetTetrahedronTexture() { return this->TetrahedronTexture; }
  vtkTextureObject* GetPointTexture() { return this->PointTexture; }
  vtkTextureObject* GetScalarTexture() { return this->ScalarTexture; }
  /// The tetrahedra's ids for the random numbers (R32UI), when the mesh numbers them by
  /// global ids (vtkTetrahedralMesh::GetRandomIds()); else null.
  vtkTextureObject* GetRandomIdTexture() { return this->RandomIdTexture; }
  /// Each uploaded tetrahedron's index in the mesh (R32UI).
  vtkTextureObject* GetMeshIndexTexture() { return this->MeshIndexTexture; }
  /// How many of the leading uploaded tetrahedra, whole classes of size of the cells shaped
  /// for points, have no edge longer than `length` (normalized units); zero for a negative
  /// length.
  vtkIdType CountSmallCells(double length) const;

  /// Draw tetrahedra [first, first + count) as GL_LINES_ADJACENCY. The program's
  /// `primitiveOffset` uniform is set so that gl_PrimitiveIDIn + primitiveOffset is the
  /// tetrahedron's index.
  void Draw(vtkShaderProgram* program, vtkIdType first, vtkIdType count);
  /// Draw tetrahedra [first, first + count) as one GL_POINTS vertex each, with no vertex
  /// attributes: the vertex stage reads the cell through the buffer textures, and gl_VertexID
  /// is the tetrahedron's index.
  void DrawPoints(vtkShaderProgram* program, vtkIdType first, vtkIdType count);

  size_t GetGPUMemorySize() const { return this->UploadedBytes; }
  void ReleaseGraphicsResources(vtkWindow* window);

protected:
  vtkSPTMeshBuffers();
  ~vtkSPTMeshBuffers() override;

private:
  vtkSPTMeshBuffers(const vtkSPTMeshBuffers&) = delete;
  void operator=(const vtkSPTMeshBuffers&) = delete;

  // The order of the upload: the mesh's tetrahedra by class of size (and the classes).
  std::vector<unsigned int> ClassifyBySize(const vtkTetrahedralMesh* mesh);
  // The tetrahedra (with their cell scalars) in classes of size, and their indices in the mesh.
  bool UploadTetrahedra(vtkOpenGLRenderWindow* renWin, const std::vector<unsigned int>& order);

  // The random ids' buffer texture, or none when the mesh has none.
  bool UploadRandomIds(vtkOpenGLRenderWindow* renWin, const std::vector<unsigned int>& order);

  vtkSmartPointer<vtkTetrahedralMesh> Mesh;
  vtkMTimeType UploadedBuild = 0;
  vtkOpenGLRenderWindow* Context = nullptr;

  vtkNew<vtkOpenGLBufferObject> PointBuffer;
  vtkNew<vtkOpenGLBufferObject> ScalarBuffer;
  vtkNew<vtkOpenGLBufferObject> IndexBuffer;
  vtkNew<vtkOpenGLBufferObject> RandomIdBuffer;
  vtkNew<vtkOpenGLBufferObject> MeshIndexBuffer;
  vtkBatchedVertexArray VertexArray;
  vtkBatchedVertexArray PointVertexArray; // no attributes: the points read buffer textures
  vtkSmartPointer<vtkTextureObject> ScalarTexture;
  vtkSmartPointer<vtkTextureObject> TetrahedronTexture;
  vtkSmartPointer<vtkTextureObject> PointTexture;
  vtkSmartPointer<vtkTextureObject> RandomIdTexture;
  vtkSmartPointer<vtkTextureObject> MeshIndexTexture;
  // Per class of size of the cells shaped for points, smallest first: its longest edge, and
  // where its cells end.
  std::vector<float> ClassLongestEdges;
  std::vector<vtkIdType> ClassEnds;
  size_t UploadedBytes = 0;
};

#endif
