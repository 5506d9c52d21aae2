#include "vtkSceneDepthTexture.h"

#include "vtkFramebufferTextures.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLLoader.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkTextureObject.h"

vtkStandardNewMacro(vtkSceneDepthTexture);

vtkSceneDepthTexture::vtkSceneDepthTexture() = default;

vtkSceneDepthTexture::~vtkSceneDepthTexture() = default;

int vtkSceneDepthTexture::QueryFormat(int* hasDepth)
{
  GLint readFramebuffer = 0;
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &readFramebuffer);
  if (glCheckFramebufferStatus(GL_READ_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
  {
    // Nothing to read depth from: an incomplete framebuffer, or no default framebuffer at
    // all (a context without a surface, as vtkHeadlessEGLRenderWindow's, outside VTK's own).
    *hasDepth = 0;
    return vtkTextureObject::Float32;
  }
  const GLenum attachment = readFramebuffer ? GL_DEPTH_ATTACHMENT : GL_DEPTH;
  GLint objectType = GL_NONE;
  glGetFramebufferAttachmentParameteriv(
    GL_READ_FRAMEBUFFER, attachment, GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &objectType);
  *hasDepth = objectType != GL_NONE;
  if (!*hasDepth)
  {
    return vtkTextureObject::Float32;
  }
  GLint componentType = GL_FLOAT;
  GLint bits = 32;
  glGetFramebufferAttachmentParameteriv(
    GL_READ_FRAMEBUFFER, attachment, GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE, &componentType);
  glGetFramebufferAttachmentParameteriv(
    GL_READ_FRAMEBUFFER, attachment, GL_FRAMEBUFFER_ATTACHMENT_DEPTH_SIZE, &bits);
  if (componentType == GL_FLOAT)
  {
    return vtkTextureObject::Float32;
  }
  return bits <= 16 ? vtkTextureObject::Fixed16
                    : (bits <= 24 ? vtkTextureObject::Fixed24 : vtkTextureObject::Fixed32);
}

bool vtkSceneDepthTexture::Allocate(
  vtkOpenGLRenderWindow* renWin, int width, int height, int format)
{
  vtkFramebufferTextures::UseNearestTexels(this->Texture, renWin);
  if (!this->Texture->AllocateDepth(width, height, format) ||
    !vtkFramebufferTextures::Attach(this->Framebuffer, renWin, {}, this->Texture))
  {
    this->ReleaseGraphicsResources(renWin);
    return false;
  }
  this->Context = renWin;
  this->Width = width;
  this->Height = height;
  this->Format = format;
  return true;
}

void vtkSceneDepthTexture::Capture(int x, int y)
{
  vtkOpenGLState* ostate = this->Context->GetState();
  int hasDepth = 0;
  QueryFormat(&hasDepth);
  vtkOpenGLState::ScopedglEnableDisable scissor(ostate, GL_SCISSOR_TEST);
  vtkOpenGLState::ScopedglDepthMask depthMask(ostate);
  ostate->vtkglDisable(GL_SCISSOR_TEST);
  ostate->PushDrawFramebufferBinding();
  this->Framebuffer->Bind(GL_DRAW_FRAMEBUFFER);
  if (hasDepth)
  {
    ostate->vtkglBlitFramebuffer(x, y, x + this->Width, y + this->Height, 0, 0, this->Width,
      this->Height, GL_DEPTH_BUFFER_BIT, GL_NEAREST);
  }
  if (!hasDepth || glGetError() != GL_NO_ERROR)
  {
    ostate->vtkglDepthMask(GL_TRUE);
    ostate->vtkglClearDepth(1.0);
    ostate->vtkglClear(GL_DEPTH_BUFFER_BIT);
  }
  ostate->PopDrawFramebufferBinding();
}

void vtkSceneDepthTexture::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Framebuffer->ReleaseGraphicsResources(window);
  this->Texture->ReleaseGraphicsResources(window);
  this->Context = nullptr;
  this->Width = this->Height = 0;
  this->Format = -1;
}

void vtkSceneDepthTexture::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Size: " << this->Width << " x " << this->Height << "\n";
  os << indent << "Format: " << this->Format << "\n";
}
