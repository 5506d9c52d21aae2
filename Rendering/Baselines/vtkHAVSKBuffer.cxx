#include "vtkHAVSKBuffer.h"

#include "vtkObjectFactory.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLLoader.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

#include "vtkFramebufferTextures.h"
#include "vtkHAVSVolumeMapper.h"
#include "vtkSavedGLState.h"
#include "vtkSceneDepthTexture.h"

#include "vtkEnsembleAccumulateFS.h"

#include <sstream>
#include <string>

namespace
{
// Distance of an empty entry: the shaders' EMPTY_DISTANCE.
constexpr float EmptyDistance = 1.0e30f;
}

vtkStandardNewMacro(vtkHAVSKBuffer);

vtkHAVSKBuffer::vtkHAVSKBuffer() = default;

vtkHAVSKBuffer::~vtkHAVSKBuffer() = default;

bool vtkHAVSKBuffer::HasExtension(const char* name)
{
  return vtkOpenGLLoader::HasExtension(name);
}

std::string vtkHAVSKBuffer::GetShaderDefinitions() const
{
  std::ostringstream defines;
  if (this->AccessMode == vtkHAVSVolumeMapper::FRAMEBUFFER_FETCH)
  {
    defines << "#extension GL_EXT_shader_framebuffer_fetch : require\n"
               "#extension GL_ARB_explicit_attrib_location : require\n"
               "#define HAVS_FRAMEBUFFER_FETCH\n";
  }
  else
  {
    defines << "#extension GL_ARB_shader_image_load_store : require\n"
               "#define HAVS_IMAGE\n";
  }
  if (this->AccessMode == vtkHAVSVolumeMapper::FRAGMENT_SHADER_INTERLOCK)
  {
    defines << "#extension GL_ARB_fragment_shader_interlock : require\n"
               "#define HAVS_INTERLOCK\n"
               "layout(pixel_interlock_ordered) in;\n"
               "#define KBUFFER_BEGIN_CRITICAL_SECTION beginInvocationInterlockARB()\n"
               "#define KBUFFER_END_CRITICAL_SECTION endInvocationInterlockARB()\n";
  }
  else
  {
    defines << "#define KBUFFER_BEGIN_CRITICAL_SECTION\n"
               "#define KBUFFER_END_CRITICAL_SECTION\n";
  }
  defines << "#define KBUFFER_SIZE " << this->KBufferSize << "\n"
          << "#define KBUFFER_TARGETS " << this->GetNumberOfTargets() << "\n";
  return defines.str();
}

bool vtkHAVSKBuffer::Prepare(
  vtkOpenGLRenderWindow* renWin, int width, int height, int kbufferSize, int access)
{
  int hasDepth = 0;
  const int depthFormat = vtkSceneDepthTexture::QueryFormat(&hasDepth);
  if (renWin != this->Context || width != this->Width || height != this->Height ||
    kbufferSize != this->KBufferSize || access != this->AccessMode ||
    depthFormat != this->SceneDepth->GetFormat())
  {
    if (this->Context && this->Context != renWin)
    {
      this->ReleaseGraphicsResources(this->Context);
    }
    this->Width = width;
    this->Height = height;
    this->KBufferSize = kbufferSize;
    this->AccessMode = access;
    this->Allocate(renWin, depthFormat);
  }
  return this->Context != nullptr;
}

void vtkHAVSKBuffer::Allocate(vtkOpenGLRenderWindow* renWin, int depthFormat)
{
  const int targets = this->GetNumberOfTargets();
  bool ok = true;
  vtkTextureObject* colors[MaximumTargets];
  for (int t = 0; t < MaximumTargets; ++t)
  {
    this->Targets[t]->ReleaseGraphicsResources(renWin);
    colors[t] = this->Targets[t];
  }
  for (int t = 0; t < targets; ++t)
  {
    ok = ok &&
      vtkFramebufferTextures::AllocateFloat(this->Targets[t], renWin, this->Width, this->Height, 4);
  }
  ok = ok && this->SceneDepth->Allocate(renWin, this->Width, this->Height, depthFormat) &&
    vtkFramebufferTextures::Attach(this->Framebuffer, renWin, colors, targets);

  if (!this->Copy)
  {
    this->Copy.reset(new vtkOpenGLQuadHelper(renWin, nullptr, vtkEnsembleAccumulateFS, ""));
  }
  ok = ok && this->Copy->Program;
  if (!ok)
  {
    vtkErrorMacro("Could not allocate the " << this->Width << "x" << this->Height << " k-buffer ("
                                            << targets << " RGBA32F targets).");
    this->ReleaseGraphicsResources(renWin);
    return;
  }
  this->Context = renWin;
}

void vtkHAVSKBuffer::Clear()
{
  vtkOpenGLState* ostate = this->Context->GetState();
  vtkOpenGLState::ScopedglColorMask colorMask(ostate);
  // The renderer leaves the scissor box on its viewport, which need not cover these targets.
  vtkOpenGLState::ScopedglEnableDisable scissor(ostate, GL_SCISSOR_TEST);
  ostate->vtkglDisable(GL_SCISSOR_TEST);
  ostate->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  this->Framebuffer->Bind(GL_DRAW_FRAMEBUFFER);
  this->Framebuffer->ActivateDrawBuffers(this->GetNumberOfTargets());
  const float color[4] = { 0.0f, 0.0f, 0.0f, 0.0f };
  const float entries[4] = { 0.0f, EmptyDistance, 0.0f, EmptyDistance };
  glClearBufferfv(GL_COLOR, 0, color);
  for (int t = 1; t < this->GetNumberOfTargets(); ++t)
  {
    glClearBufferfv(GL_COLOR, t, entries);
  }
}

void vtkHAVSKBuffer::BeginPass(vtkShaderProgram* program)
{
  vtkOpenGLState* ostate = this->Context->GetState();
  this->Framebuffer->Bind(GL_DRAW_FRAMEBUFFER);
  ostate->vtkglDisable(GL_SCISSOR_TEST);
  ostate->vtkglDisable(GL_BLEND);
  ostate->vtkglViewport(0, 0, this->Width, this->Height);
  const int targets = this->GetNumberOfTargets();
  if (this->AccessMode == vtkHAVSVolumeMapper::FRAMEBUFFER_FETCH)
  {
    this->Framebuffer->ActivateDrawBuffers(targets);
    ostate->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  }
  else
  {
    // The fragments write the targets as images only: no draw buffers. (Masking every color
    // write instead makes llvmpipe skip the fragment shader, image stores and all.)
    this->Framebuffer->DeactivateDrawBuffers();
    for (int t = 0; t < targets; ++t)
    {
      glBindImageTexture(static_cast<GLuint>(t), this->Targets[t]->GetHandle(), 0, GL_FALSE, 0,
        GL_READ_WRITE, GL_RGBA32F);
      program->SetUniformi(("kbufferTarget" + std::to_string(t)).c_str(), t);
    }
  }
  this->SceneDepthActive = program->IsUniformUsed("sceneDepthTexture");
  if (this->SceneDepthActive)
  {
    this->SceneDepth->GetTexture()->Activate();
    program->SetUniformi("sceneDepthTexture", this->SceneDepth->GetTexture()->GetTextureUnit());
  }
}

void vtkHAVSKBuffer::EndPass()
{
  if (this->SceneDepthActive)
  {
    this->SceneDepth->GetTexture()->Deactivate();
    this->SceneDepthActive = false;
  }
  if (this->AccessMode != vtkHAVSVolumeMapper::FRAMEBUFFER_FETCH)
  {
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    for (int t = 0; t < this->GetNumberOfTargets(); ++t)
    {
      glBindImageTexture(static_cast<GLuint>(t), 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    }
  }
}

void vtkHAVSKBuffer::Resolve(int x, int y)
{
  // The composited color is premultiplied: "over" the scene.
  vtkScopedOverBlending over(this->Context->GetState(), x, y, this->Width, this->Height);
  vtkShaderProgram* program = this->Copy->Program;
  this->Context->GetShaderCache()->ReadyShaderProgram(program);
  this->Targets[0]->Activate();
  program->SetUniformi("passTexture", this->Targets[0]->GetTextureUnit());
  this->Copy->Render();
  this->Targets[0]->Deactivate();
}

size_t vtkHAVSKBuffer::GetGPUMemorySize() const
{
  if (!this->Context)
  {
    return 0;
  }
  const size_t pixels = size_t(this->Width) * size_t(this->Height);
  // RGBA32F targets and a depth texture of at most 32 bits.
  return pixels * (16 * size_t(this->GetNumberOfTargets()) + 4);
}

void vtkHAVSKBuffer::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Copy.reset();
  this->Framebuffer->ReleaseGraphicsResources(window);
  for (int t = 0; t < MaximumTargets; ++t)
  {
    this->Targets[t]->ReleaseGraphicsResources(window);
  }
  this->SceneDepth->ReleaseGraphicsResources(window);
  this->Context = nullptr;
  this->Width = this->Height = this->KBufferSize = this->AccessMode = 0;
}

void vtkHAVSKBuffer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Size: " << this->Width << " x " << this->Height << "\n";
  os << indent << "KBufferSize: " << this->KBufferSize << "\n";
  os << indent << "AccessMode: " << this->AccessMode << "\n";
  os << indent << "GPUMemorySize: " << this->GetGPUMemorySize() << "\n";
}
