#include "vtkEnsembleTiles.h"

#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLLoader.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

#include "vtkFramebufferTextures.h"

#include <algorithm>
#include <cmath>

vtkEnsembleTiles::vtkEnsembleTiles() = default;

vtkEnsembleTiles::~vtkEnsembleTiles() = default;

void vtkEnsembleTiles::Resize(int width, int height, int subpixelLevel)
{
  this->Width = width;
  this->Height = height;
  this->SubpixelLevel = std::max(1, subpixelLevel);
  this->Columns = (width + TileSize - 1) / TileSize;
  this->Rows = (height + TileSize - 1) / TileSize;
  this->Reset();
}

void vtkEnsembleTiles::Reset()
{
  const size_t tiles = size_t(this->Columns) * size_t(this->Rows);
  this->Restricted = false;
  this->Active.assign(tiles, true);
  if (this->GetMostMissed() > 0 || this->Missed.size() != tiles)
  {
    this->Missed.assign(tiles, 0.0f);
    this->MissedUploaded = false;
  }
  this->Box[0] = this->Box[1] = 0;
  this->Box[2] = this->Columns;
  this->Box[3] = this->Rows;
}

std::vector<double> vtkEnsembleTiles::MeanPerTile(
  const std::vector<float>& pairs, double scale) const
{
  const size_t tiles = size_t(this->Columns) * size_t(this->Rows);
  std::vector<double> sums(tiles, 0.0);
  std::vector<size_t> counts(tiles, 0);
  for (int y = 0; y < this->Height; ++y)
  {
    for (int x = 0; x < this->Width; ++x)
    {
      const size_t pixel = size_t(y) * size_t(this->Width) + size_t(x);
      if (2 * pixel + 1 < pairs.size() && pairs[2 * pixel + 1] > 0.5f)
      {
        const size_t tile = size_t(y / TileSize) * size_t(this->Columns) + size_t(x / TileSize);
        sums[tile] += pairs[2 * pixel];
        ++counts[tile];
      }
    }
  }
  for (size_t tile = 0; tile < tiles; ++tile)
  {
    sums[tile] = counts[tile] > 0 ? std::sqrt(scale * sums[tile] / double(counts[tile])) : -1.0;
  }
  return sums;
}

bool vtkEnsembleTiles::AllocateStencil(vtkTextureObject* depth)
{
  if (this->StencilAllocated)
  {
    return true;
  }
  // The depth buffer's storage again, with a stencil beside the same 32-bit float depth.
  depth->Activate();
  glTexImage2D(depth->GetTarget(), 0, GL_DEPTH32F_STENCIL8, static_cast<GLsizei>(depth->GetWidth()),
    static_cast<GLsizei>(depth->GetHeight()), 0, GL_DEPTH_STENCIL,
    GL_FLOAT_32_UNSIGNED_INT_24_8_REV, nullptr);
  depth->Deactivate();
  this->StencilAllocated = glGetError() == GL_NO_ERROR;
  return this->StencilAllocated;
}

void vtkEnsembleTiles::DetachStencil(
  vtkOpenGLRenderWindow* context, const std::vector<vtkOpenGLFramebufferObject*>& framebuffers)
{
  if (!this->StencilAllocated)
  {
    return;
  }
  vtkOpenGLState* ostate = context->GetState();
  ostate->PushFramebufferBindings();
  for (vtkOpenGLFramebufferObject* framebuffer : framebuffers)
  {
    if (framebuffer->GetFBOIndex() != 0)
    {
      ostate->vtkBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
      glFramebufferTexture2D(GL_FRAMEBUFFER, GL_STENCIL_ATTACHMENT, GL_TEXTURE_2D, 0, 0);
    }
  }
  ostate->PopFramebufferBindings();
  this->StencilAllocated = false;
  this->Restricted = false;
}

bool vtkEnsembleTiles::Restrict(vtkOpenGLRenderWindow* context, const std::vector<bool>& active,
  vtkTextureObject* depth, const std::vector<vtkOpenGLFramebufferObject*>& framebuffers,
  const char*& error)
{
  if (active.size() != this->Active.size() || framebuffers.empty())
  {
    error = "the tiles do not match the image";
    return false;
  }
  if (!this->AllocateStencil(depth))
  {
    error = "the passes' depth buffer cannot hold a stencil";
    return false;
  }
  vtkOpenGLState* ostate = context->GetState();
  ostate->PushFramebufferBindings();
  bool complete = true;
  for (vtkOpenGLFramebufferObject* framebuffer : framebuffers)
  {
    if (framebuffer->GetFBOIndex() != 0)
    {
      ostate->vtkBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
      glFramebufferTexture2D(
        GL_FRAMEBUFFER, GL_STENCIL_ATTACHMENT, GL_TEXTURE_2D, depth->GetHandle(), 0);
      complete = complete && glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    }
  }
  if (!complete)
  {
    ostate->PopFramebufferBindings();
    error = "a framebuffer with the stencil is not complete";
    return false;
  }
  this->Active = active;
  this->Restricted = true;
  ostate->vtkBindFramebuffer(GL_FRAMEBUFFER, framebuffers.front());
  this->WriteStencil(ostate);
  ostate->PopFramebufferBindings();
  return true;
}

void vtkEnsembleTiles::WriteStencil(vtkOpenGLState* ostate)
{
  // 0, then 1 in each row's runs of active tiles (a cleared scissor box each); the box
  // around them.
  vtkOpenGLState::ScopedglEnableDisable scissor(ostate, GL_SCISSOR_TEST);
  vtkOpenGLState::ScopedglScissor box(ostate);
  ostate->vtkglStencilMask(0xFF);
  ostate->vtkglDisable(GL_SCISSOR_TEST);
  glClearStencil(0);
  ostate->vtkglClear(GL_STENCIL_BUFFER_BIT);
  ostate->vtkglEnable(GL_SCISSOR_TEST);
  glClearStencil(1);
  int low[2] = { this->Columns, this->Rows };
  int high[2] = { 0, 0 };
  const int side = TileSize * this->SubpixelLevel;
  for (int row = 0; row < this->Rows; ++row)
  {
    const size_t first = size_t(row) * size_t(this->Columns);
    for (int column = 0; column < this->Columns;)
    {
      if (!this->Active[first + size_t(column)])
      {
        ++column;
        continue;
      }
      int end = column;
      while (end < this->Columns && this->Active[first + size_t(end)])
      {
        ++end;
      }
      ostate->vtkglScissor(column * side, row * side, (end - column) * side, side);
      ostate->vtkglClear(GL_STENCIL_BUFFER_BIT);
      low[0] = std::min(low[0], column);
      low[1] = std::min(low[1], row);
      high[0] = std::max(high[0], end);
      high[1] = std::max(high[1], row + 1);
      column = end;
    }
  }
  glClearStencil(0);
  for (int axis = 0; axis < 2; ++axis)
  {
    this->Box[axis] = low[axis];
    this->Box[2 + axis] = std::max(0, high[axis] - low[axis]);
  }
}

void vtkEnsembleTiles::AddRepetitions(int count)
{
  if (!this->Restricted)
  {
    return;
  }
  for (size_t tile = 0; tile < this->Active.size(); ++tile)
  {
    if (!this->Active[tile])
    {
      this->Missed[tile] += static_cast<float>(count);
      this->MissedUploaded = false;
    }
  }
}

void vtkEnsembleTiles::ApplyTests(vtkOpenGLRenderWindow* context) const
{
  vtkOpenGLState* ostate = context->GetState();
  if (!this->Restricted)
  {
    ostate->vtkglDisable(GL_STENCIL_TEST);
    ostate->vtkglDisable(GL_SCISSOR_TEST);
    return;
  }
  int box[4];
  this->GetSampleBox(box);
  ostate->vtkglEnable(GL_SCISSOR_TEST);
  ostate->vtkglScissor(box[0], box[1], box[2], box[3]);
  ostate->vtkglEnable(GL_STENCIL_TEST);
  ostate->vtkglStencilFunc(GL_EQUAL, 1, 0xFF);
  ostate->vtkglStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  ostate->vtkglStencilMask(0x00);
}

void vtkEnsembleTiles::GetSampleBox(int box[4]) const
{
  const int side = TileSize * this->SubpixelLevel;
  const int size[2] = { this->Width * this->SubpixelLevel, this->Height * this->SubpixelLevel };
  for (int axis = 0; axis < 2; ++axis)
  {
    box[axis] = std::min(this->Box[axis] * side, size[axis]);
    box[2 + axis] = std::min(this->Box[2 + axis] * side, size[axis] - box[axis]);
  }
}

int vtkEnsembleTiles::GetMostMissed() const
{
  return this->Missed.empty()
    ? 0
    : static_cast<int>(*std::max_element(this->Missed.begin(), this->Missed.end()));
}

bool vtkEnsembleTiles::UploadMissed(vtkOpenGLRenderWindow* context)
{
  if (this->MissedUploaded && this->MissedTexture->GetHandle() != 0)
  {
    return true;
  }
  vtkFramebufferTextures::UseNearestTexels(this->MissedTexture, context);
  const int columns = std::max(1, this->Columns);
  const int rows = std::max(1, this->Rows);
  std::vector<float> values(this->Missed);
  values.resize(size_t(columns) * size_t(rows), 0.0f);
  this->MissedUploaded = this->MissedTexture->Create2DFromRaw(static_cast<unsigned int>(columns),
    static_cast<unsigned int>(rows), 1, VTK_FLOAT, values.data());
  return this->MissedUploaded;
}

void vtkEnsembleTiles::Activate(vtkOpenGLRenderWindow* context, vtkShaderProgram* program)
{
  // The sampler names the texture even where no tile missed a repetition and it is not read.
  const bool uploaded = this->UploadMissed(context);
  this->MissedTexture->Activate();
  program->SetUniformi("restricted", uploaded && this->GetMostMissed() > 0 ? 1 : 0);
  program->SetUniformi("tileSize", TileSize);
  program->SetUniformi("tileMissed", this->MissedTexture->GetTextureUnit());
}

void vtkEnsembleTiles::Deactivate()
{
  this->MissedTexture->Deactivate();
}

void vtkEnsembleTiles::ReleaseGraphicsResources(vtkWindow* window)
{
  this->MissedTexture->ReleaseGraphicsResources(window);
  this->MissedUploaded = false;
  this->StencilAllocated = false;
  this->Restricted = false;
}
