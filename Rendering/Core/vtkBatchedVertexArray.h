/**
 * @class   vtkBatchedVertexArray
 * @brief   a vertex array bound to a program's attributes, and draws split into batches
 *
 * The module's mappers draw millions of primitives from a few buffers. This helper keeps one
 * vertex array: Bind() describes the attributes again only when the program changed (a
 * vtkOpenGLVertexArrayObject forgets its layout on ShaderProgramChanged()), and binds the
 * index buffer, if any. DrawElements() and DrawArrays() split a draw into batches of at most
 * a given number of primitives, so that counts stay far below GLsizei's range; DrawElements()
 * runs a callback before each batch (for a uniform that names its first primitive).
 *
 * Private helper of the module's mappers; not wrapped.
 */

#ifndef vtkBatchedVertexArray_h
#define vtkBatchedVertexArray_h

#include "SPTRenderingCoreModule.h" // For export macro
#include "vtkNew.h"                 // For the vertex array
#include "vtkType.h"                // For vtkIdType

#include <functional>       // For the batch callback
#include <initializer_list> // For the attributes

class vtkOpenGLBufferObject;
class vtkOpenGLVertexArrayObject;
class vtkShaderProgram;

class SPTRENDERINGCORE_EXPORT vtkBatchedVertexArray
{
public:
  vtkBatchedVertexArray();
  ~vtkBatchedVertexArray();
  vtkBatchedVertexArray(const vtkBatchedVertexArray&) = delete;
  vtkBatchedVertexArray& operator=(const vtkBatchedVertexArray&) = delete;

  /// One vertex attribute of the program, read from a buffer.
  struct Attribute
  {
    const char* Name;
    vtkOpenGLBufferObject* Buffer;
    int Stride;     // bytes from one vertex to the next
    int DataType;   // VTK_FLOAT, VTK_UNSIGNED_SHORT, ...
    int Components; // values per vertex
    bool Normalize; // integer values map to [0, 1]
  };

  /**
   * Bind the vertex array (and `indices`, if not null) for the program. The attributes are
   * described again only when the program is not the one bound last.
   */
  void Bind(vtkShaderProgram* program, std::initializer_list<Attribute> attributes,
    vtkOpenGLBufferObject* indices = nullptr);
  void Release();

  /// Describe the attributes again at the next Bind() (after the buffers were uploaded anew).
  void ForgetLayout() { this->BoundProgram = nullptr; }

  /// Forget the layout and the GPU object (the buffers are their owner's).
  void ReleaseGraphicsResources();

  /// Called before each batch with the index of its first primitive.
  using BatchCallback = std::function<void(vtkIdType)>;

  /**
   * Draw primitives [first, first + count) of the bound index buffer, each of
   * `indicesPerPrimitive` 32-bit indices, as `mode` (GL_TRIANGLES, GL_LINES_ADJACENCY, ...),
   * at most `maxPerBatch` primitives a call.
   */
  static void DrawElements(unsigned int mode, int indicesPerPrimitive, vtkIdType first,
    vtkIdType count, vtkIdType maxPerBatch, const BatchCallback& beforeBatch = nullptr);

  /// Draw vertices [first, first + count) as `mode`, at most `maxPerBatch` a call.
  static void DrawArrays(
    unsigned int mode, vtkIdType first, vtkIdType count, vtkIdType maxPerBatch);

private:
  vtkNew<vtkOpenGLVertexArrayObject> VertexArray;
  vtkShaderProgram* BoundProgram = nullptr;
  vtkOpenGLBufferObject* Indices = nullptr;
};

#endif
