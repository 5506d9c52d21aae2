#include "vtkFramebufferTextures.h"

#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLLoader.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkTextureObject.h"

void vtkFramebufferTextures::UseNearestTexels(
  vtkTextureObject* texture, vtkOpenGLRenderWindow* context)
{
  texture->SetContext(context);
  texture->SetMinificationFilter(vtkTextureObject::Nearest);
  texture->SetMagnificationFilter(vtkTextureObject::Nearest);
  texture->SetWrapS(vtkTextureObject::ClampToEdge);
  texture->SetWrapT(vtkTextureObject::ClampToEdge);
}

bool vtkFramebufferTextures::HasSize(vtkTextureObject* texture, int width, int height)
{
  return static_cast<int>(texture->GetWidth()) == width &&
    static_cast<int>(texture->GetHeight()) == height && texture->GetHandle() != 0;
}

bool vtkFramebufferTextures::AllocateFloat(
  vtkTextureObject* texture, vtkOpenGLRenderWindow* context, int width, int height, int components)
{
  UseNearestTexels(texture, context);
  return texture->Allocate2D(width, height, components, VTK_FLOAT);
}

bool vtkFramebufferTextures::Attach(vtkOpenGLFramebufferObject* framebuffer,
  vtkOpenGLRenderWindow* context, std::initializer_list<vtkTextureObject*> colors,
  vtkTextureObject* depth)
{
  return Attach(framebuffer, context, colors.begin(), static_cast<int>(colors.size()), depth);
}

bool vtkFramebufferTextures::Attach(vtkOpenGLFramebufferObject* framebuffer,
  vtkOpenGLRenderWindow* context, vtkTextureObject* const* colors, int numberOfColors,
  vtkTextureObject* depth)
{
  vtkOpenGLState* ostate = context->GetState();
  ostate->PushFramebufferBindings();
  framebuffer->SetContext(context);
  framebuffer->Bind();
  // The object attaches a texture to an attachment point once: a texture allocated anew (a new
  // handle) is attached only after its attachment is removed.
  framebuffer->RemoveColorAttachments(framebuffer->GetNumberOfColorAttachments());
  framebuffer->RemoveDepthAttachment();
  for (int index = 0; index < numberOfColors; ++index)
  {
    framebuffer->AddColorAttachment(static_cast<unsigned int>(index), colors[index]);
  }
  if (depth)
  {
    framebuffer->AddDepthAttachment(depth);
  }
  framebuffer->ActivateDrawBuffers(static_cast<unsigned int>(numberOfColors));
  const bool complete = framebuffer->CheckFrameBufferStatus(GL_FRAMEBUFFER);
  ostate->PopFramebufferBindings();
  return complete;
}
