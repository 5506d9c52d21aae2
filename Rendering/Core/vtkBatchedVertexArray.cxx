#include "vtkBatchedVertexArray.h"

#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLLoader.h"
#include "vtkOpenGLVertexArrayObject.h"
#include "vtkShaderProgram.h"

#include <algorithm>
#include <cstdint>

vtkBatchedVertexArray::vtkBatchedVertexArray() = default;

vtkBatchedVertexArray::~vtkBatchedVertexArray() = default;

void vtkBatchedVertexArray::Bind(vtkShaderProgram* program,
  std::initializer_list<Attribute> attributes, vtkOpenGLBufferObject* indices)
{
  const bool programChanged = program != this->BoundProgram;
  if (programChanged)
  {
    this->VertexArray->ShaderProgramChanged(); // releases the array: call before Bind()
  }
  this->VertexArray->Bind();
  if (programChanged)
  {
    for (const Attribute& attribute : attributes)
    {
      this->VertexArray->AddAttributeArray(program, attribute.Buffer, attribute.Name, 0,
        attribute.Stride, attribute.DataType, attribute.Components, attribute.Normalize);
    }
    this->BoundProgram = program;
  }
  this->Indices = indices;
  if (indices)
  {
    indices->Bind();
  }
}

void vtkBatchedVertexArray::Release()
{
  if (this->Indices)
  {
    this->Indices->Release();
    this->Indices = nullptr;
  }
  this->VertexArray->Release();
}

void vtkBatchedVertexArray::ReleaseGraphicsResources()
{
  this->VertexArray->ReleaseGraphicsResources();
  this->BoundProgram = nullptr;
  this->Indices = nullptr;
}

void vtkBatchedVertexArray::DrawElements(unsigned int mode, int indicesPerPrimitive,
  vtkIdType first, vtkIdType count, vtkIdType maxPerBatch, const BatchCallback& beforeBatch)
{
  const vtkIdType end = first + count;
  for (vtkIdType begin = first; begin < end; begin += maxPerBatch)
  {
    const vtkIdType batch = std::min(maxPerBatch, end - begin);
    if (beforeBatch)
    {
      beforeBatch(begin);
    }
    const uintptr_t offset = sizeof(unsigned int) * indicesPerPrimitive * begin;
    glDrawElements(mode, static_cast<GLsizei>(indicesPerPrimitive * batch), GL_UNSIGNED_INT,
      reinterpret_cast<const void*>(offset));
  }
}

void vtkBatchedVertexArray::DrawArrays(
  unsigned int mode, vtkIdType first, vtkIdType count, vtkIdType maxPerBatch)
{
  const vtkIdType end = first + count;
  for (vtkIdType begin = first; begin < end; begin += maxPerBatch)
  {
    glDrawArrays(
      mode, static_cast<GLint>(begin), static_cast<GLsizei>(std::min(maxPerBatch, end - begin)));
  }
}
