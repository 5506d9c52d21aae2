#include "vtkEnsembleBuffer.h"

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
#include "vtkSavedGLState.h"
#include "vtkSceneDepthTexture.h"

#include "vtkEnsembleAccumulateFS.h"
#include "vtkEnsembleFootprintFS.h"
#include "vtkEnsembleNoiseFS.h"
#include "vtkEnsembleResolveFS.h"
#include "vtkEnsembleSceneFS.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace
{
// The program of `quad`, a quad over the viewport that draws `fragmentShader`, made on first
// use, ready to draw; null when it does not compile.
vtkShaderProgram* ReadyQuad(std::unique_ptr<vtkOpenGLQuadHelper>& quad,
  vtkOpenGLRenderWindow* context, const char* fragmentShader)
{
  if (!quad)
  {
    quad.reset(new vtkOpenGLQuadHelper(context, nullptr, fragmentShader, ""));
  }
  if (quad->Program)
  {
    context->GetShaderCache()->ReadyShaderProgram(quad->Program);
  }
  return quad->Program;
}

// A quad that replaces the depth bound for drawing in the viewport at (x, y), and its color
// with `color`: the depth test passes everywhere, without blending.
void SetReplacingState(vtkOpenGLState* ostate, int x, int y, int width, int height, bool color)
{
  const GLboolean colorMask = color ? GL_TRUE : GL_FALSE;
  ostate->vtkglViewport(x, y, width, height);
  ostate->vtkglEnable(GL_DEPTH_TEST);
  ostate->vtkglDepthFunc(GL_ALWAYS);
  ostate->vtkglDepthMask(GL_TRUE);
  ostate->vtkglColorMask(colorMask, colorMask, colorMask, colorMask);
  ostate->vtkglDisable(GL_BLEND);
}
}

vtkStandardNewMacro(vtkEnsembleBuffer);

vtkEnsembleBuffer::vtkEnsembleBuffer() = default;

vtkEnsembleBuffer::~vtkEnsembleBuffer() = default;

bool vtkEnsembleBuffer::Prepare(
  vtkOpenGLRenderWindow* renWin, int width, int height, int subpixelLevel, double sampleDistance)
{
  int hasDepth = 0;
  const int depthFormat = vtkSceneDepthTexture::QueryFormat(&hasDepth);
  sampleDistance = std::max(1.0, sampleDistance);
  const int imageWidth = sampleDistance > 1.0 ? int(std::ceil(width / sampleDistance)) : width;
  const int imageHeight = sampleDistance > 1.0 ? int(std::ceil(height / sampleDistance)) : height;
  this->SampleDistance = sampleDistance;
  if (renWin != this->Context || imageWidth != this->Width || imageHeight != this->Height ||
    width != this->ViewportWidth || height != this->ViewportHeight ||
    subpixelLevel != this->SubpixelLevel || depthFormat != this->SceneDepth->GetFormat())
  {
    if (this->Context && this->Context != renWin)
    {
      this->ReleaseGraphicsResources(this->Context);
    }
    if (this->Context == renWin)
    {
      this->Tiles.DetachStencil(renWin, this->DepthFramebuffers());
    }
    this->Width = imageWidth;
    this->Height = imageHeight;
    this->ViewportWidth = width;
    this->ViewportHeight = height;
    this->SubpixelLevel = subpixelLevel;
    this->Tiles.Resize(imageWidth, imageHeight, subpixelLevel);
    this->Allocate(renWin, depthFormat);
  }
  return this->Context != nullptr;
}

void vtkEnsembleBuffer::GetPixelScale(float scale[2]) const
{
  scale[0] = this->Width > 0 ? float(this->ViewportWidth) / float(this->Width) : 1.0f;
  scale[1] = this->Height > 0 ? float(this->ViewportHeight) / float(this->Height) : 1.0f;
}

void vtkEnsembleBuffer::Allocate(vtkOpenGLRenderWindow* renWin, int depthFormat)
{
  const int w = this->GetPassWidth();
  const int h = this->GetPassHeight();
  vtkFramebufferTextures::UseNearestTexels(this->PassDepth, renWin);
  bool ok = vtkFramebufferTextures::AllocateFloat(this->PassColor, renWin, w, h, 4) &&
    this->PassDepth->AllocateDepth(w, h, vtkTextureObject::Float32) &&
    vtkFramebufferTextures::AllocateFloat(this->Sum, renWin, w, h, 4) &&
    this->SceneDepth->Allocate(renWin, this->ViewportWidth, this->ViewportHeight, depthFormat);
  // The passes' depth is free while the sums are drawn: SPT's color traversal tests against it.
  ok = ok &&
    vtkFramebufferTextures::Attach(
      this->PassFramebuffer, renWin, { this->PassColor }, this->PassDepth) &&
    vtkFramebufferTextures::Attach(this->SumFramebuffer, renWin, { this->Sum }, this->PassDepth);

  if (!this->Accumulate)
  {
    // Adding a pass to the sum, or to both sums: a second output only where one is bound.
    std::string one = vtkEnsembleAccumulateFS;
    std::string both = vtkEnsembleAccumulateFS;
    vtkShaderProgram::Substitute(one, "//Volume::Defines::Dec", "");
    vtkShaderProgram::Substitute(both, "//Volume::Defines::Dec", "#define ENSEMBLE_SECOND_HALF");
    this->Accumulate.reset(new vtkOpenGLQuadHelper(renWin, nullptr, one.c_str(), ""));
    this->AccumulateBoth.reset(new vtkOpenGLQuadHelper(renWin, nullptr, both.c_str(), ""));
    this->Mean.reset(new vtkOpenGLQuadHelper(renWin, nullptr, vtkEnsembleResolveFS, ""));
  }
  ok = ok && this->Accumulate->Program && this->AccumulateBoth->Program && this->Mean->Program;
  if (!ok)
  {
    vtkErrorMacro(
      "Could not allocate the " << w << "x" << h << " float framebuffers of the ensemble.");
    this->ReleaseGraphicsResources(renWin);
    return;
  }
  this->Context = renWin;
}

std::vector<vtkOpenGLFramebufferObject*> vtkEnsembleBuffer::DepthFramebuffers()
{
  return { this->PassFramebuffer, this->SumFramebuffer, this->HalvesFramebuffer };
}

bool vtkEnsembleBuffer::RestrictToTiles(const std::vector<bool>& active)
{
  const char* error = "";
  if (!this->Tiles.Restrict(
        this->Context, active, this->PassDepth, this->DepthFramebuffers(), error))
  {
    vtkErrorMacro("Could not restrict the ensemble to some tiles: " << error << ".");
    return false;
  }
  return true;
}

void vtkEnsembleBuffer::ClearSum()
{
  this->Tiles.Reset();
  vtkOpenGLState* ostate = this->Context->GetState();
  vtkSavedGLState saved(ostate);
  // The renderer leaves the scissor box on its viewport, which need not cover these buffers.
  ostate->vtkglDisable(GL_SCISSOR_TEST);
  ostate->PushDrawFramebufferBinding();
  this->SumsFramebuffer(this->Halves)->Bind(GL_DRAW_FRAMEBUFFER);
  ostate->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  ostate->vtkglClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  ostate->vtkglClear(GL_COLOR_BUFFER_BIT);
  ostate->PopDrawFramebufferBinding();
}

void vtkEnsembleBuffer::BeginPass()
{
  vtkOpenGLState* ostate = this->Context->GetState();
  this->PassFramebuffer->Bind(GL_DRAW_FRAMEBUFFER);
  this->PassFramebuffer->ActivateDrawBuffers(1);
  this->Tiles.ApplyTests(this->Context); // the caller restores them after the last pass
  ostate->vtkglViewport(0, 0, this->GetPassWidth(), this->GetPassHeight());
  ostate->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  ostate->vtkglDepthMask(GL_TRUE);
  ostate->vtkglClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  ostate->vtkglClearDepth(1.0);
  ostate->vtkglClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

void vtkEnsembleBuffer::BeginSumPass(bool halves)
{
  vtkOpenGLState* ostate = this->Context->GetState();
  this->SumsFramebuffer(halves)->Bind(GL_DRAW_FRAMEBUFFER);
  this->Tiles.ApplyTests(this->Context); // the caller restores them after the last pass
  ostate->vtkglViewport(0, 0, this->GetPassWidth(), this->GetPassHeight());
}

void vtkEnsembleBuffer::EndPass(bool secondHalf)
{
  vtkOpenGLState* ostate = this->Context->GetState();
  vtkOpenGLState::ScopedglEnableDisable blend(ostate, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable depthTest(ostate, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunction(ostate);
  this->SumsFramebuffer(secondHalf)->Bind(GL_DRAW_FRAMEBUFFER);
  ostate->vtkglEnable(GL_BLEND);
  ostate->vtkglDisable(GL_DEPTH_TEST);
  ostate->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ONE);
  vtkOpenGLQuadHelper* accumulate =
    secondHalf && this->Halves ? this->AccumulateBoth.get() : this->Accumulate.get();
  this->Context->GetShaderCache()->ReadyShaderProgram(accumulate->Program);
  this->PassColor->Activate();
  accumulate->Program->SetUniformi("passTexture", this->PassColor->GetTextureUnit());
  accumulate->Render();
  this->PassColor->Deactivate();
}

vtkOpenGLFramebufferObject* vtkEnsembleBuffer::SumsFramebuffer(bool secondHalf)
{
  // Draw buffers are state of a framebuffer object: one object per set of sums.
  return secondHalf && this->Halves ? this->HalvesFramebuffer.Get() : this->SumFramebuffer.Get();
}

bool vtkEnsembleBuffer::SetHalves(bool halves)
{
  this->Halves = false;
  if (!halves)
  {
    if (this->HalvesSum)
    {
      this->HalvesFramebuffer->ReleaseGraphicsResources(this->Context);
      this->SecondHalf->ReleaseGraphicsResources(this->Context);
      this->HalvesSum = 0;
    }
    return true;
  }
  const int w = this->GetPassWidth();
  const int h = this->GetPassHeight();
  if (vtkFramebufferTextures::HasSize(this->SecondHalf, w, h) &&
    this->HalvesSum == this->Sum->GetHandle())
  {
    this->Halves = true;
    return true;
  }
  const bool ok = vtkFramebufferTextures::AllocateFloat(this->SecondHalf, this->Context, w, h, 4) &&
    vtkFramebufferTextures::Attach(
      this->HalvesFramebuffer, this->Context, { this->Sum, this->SecondHalf }, this->PassDepth);
  if (!ok)
  {
    vtkErrorMacro(
      "Could not allocate the " << w << "x" << h << " sum of the second half of the ensemble.");
    this->SecondHalf->ReleaseGraphicsResources(this->Context);
    this->HalvesFramebuffer->ReleaseGraphicsResources(this->Context);
    return false;
  }
  this->HalvesSum = this->Sum->GetHandle();
  this->Halves = true;
  return true;
}

bool vtkEnsembleBuffer::AllocateNoise()
{
  if (vtkFramebufferTextures::HasSize(this->Noise, this->Width, this->Height))
  {
    return true;
  }
  const bool ok = vtkFramebufferTextures::AllocateFloat(
                    this->Noise, this->Context, this->Width, this->Height, 2) &&
    vtkFramebufferTextures::Attach(this->NoiseFramebuffer, this->Context, { this->Noise });
  if (!ok)
  {
    vtkErrorMacro("Could not allocate the " << this->Width << "x" << this->Height
                                            << " buffer of the noise estimate.");
    this->Noise->ReleaseGraphicsResources(this->Context);
  }
  return ok;
}

std::vector<float> vtkEnsembleBuffer::DrawNoise(
  vtkShaderProgram* program, int halfCount, bool exactCoverage)
{
  vtkOpenGLState* ostate = this->Context->GetState();
  vtkSavedGLState saved(ostate);
  ostate->PushFramebufferBindings();
  this->NoiseFramebuffer->Bind();
  this->NoiseFramebuffer->ActivateDrawBuffers(1);
  ostate->vtkglDisable(GL_BLEND);
  ostate->vtkglDisable(GL_DEPTH_TEST);
  ostate->vtkglDisable(GL_SCISSOR_TEST);
  ostate->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  ostate->vtkglViewport(0, 0, this->Width, this->Height);
  this->Sum->Activate();
  this->SecondHalf->Activate();
  vtkTextureObject* coverage = exactCoverage ? this->Coverage.Get() : this->Sum.Get();
  coverage->Activate();
  program->SetUniformi("sumTexture", this->Sum->GetTextureUnit());
  program->SetUniformi("secondHalfTexture", this->SecondHalf->GetTextureUnit());
  program->SetUniformi("coverageTexture", coverage->GetTextureUnit());
  program->SetUniformi("exactCoverage", exactCoverage ? 1 : 0);
  program->SetUniformi("subpixelLevel", this->SubpixelLevel);
  program->SetUniformf("halfCount", float(halfCount));
  this->Tiles.Activate(this->Context, program);
  this->NoiseQuad->Render();
  this->Tiles.Deactivate();
  coverage->Deactivate();
  this->SecondHalf->Deactivate();
  this->Sum->Deactivate();

  std::vector<float> values(size_t(2) * size_t(this->Width) * size_t(this->Height));
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  ostate->vtkglPixelStorei(GL_PACK_ALIGNMENT, 1); // through VTK's state cache, which it keeps
  glReadPixels(0, 0, this->Width, this->Height, GL_RG, GL_FLOAT, values.data());
  ostate->PopFramebufferBindings();
  return values;
}

std::vector<double> vtkEnsembleBuffer::EstimateTileNoise(int halfCount, bool exactCoverage)
{
  if (!this->Halves || halfCount < 1 || !this->AllocateNoise())
  {
    return {};
  }
  vtkShaderProgram* program = ReadyQuad(this->NoiseQuad, this->Context, vtkEnsembleNoiseFS);
  if (!program)
  {
    vtkErrorMacro("Could not compile the shader of the noise estimate.");
    return {};
  }
  exactCoverage = exactCoverage && this->Coverage->GetHandle() != 0;
  // Per pixel: the squared difference of the halves' means over the four channels, and whether
  // it is in the footprint. The mean of the halves has a quarter of the variance of their
  // difference, and the mean over the channels a quarter of their sum.
  return this->Tiles.MeanPerTile(this->DrawNoise(program, halfCount, exactCoverage), 1.0 / 16.0);
}

bool vtkEnsembleBuffer::BeginCoveragePass()
{
  vtkOpenGLState* ostate = this->Context->GetState();
  const int w = this->GetPassWidth();
  const int h = this->GetPassHeight();
  if (!vtkFramebufferTextures::HasSize(this->Coverage, w, h))
  {
    const bool ok = vtkFramebufferTextures::AllocateFloat(this->Coverage, this->Context, w, h, 4) &&
      vtkFramebufferTextures::Attach(this->CoverageFramebuffer, this->Context, { this->Coverage });
    if (!ok)
    {
      vtkErrorMacro("Could not allocate the " << w << "x" << h << " coverage buffer.");
      this->Coverage->ReleaseGraphicsResources(this->Context);
      return false;
    }
  }
  this->BindCoverage();
  vtkOpenGLState::ScopedglClearColor clearColor(ostate);
  ostate->vtkglClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  ostate->vtkglClear(GL_COLOR_BUFFER_BIT);
  return true;
}

bool vtkEnsembleBuffer::BindCoverage()
{
  const int w = this->GetPassWidth();
  const int h = this->GetPassHeight();
  if (!vtkFramebufferTextures::HasSize(this->Coverage, w, h))
  {
    return false;
  }
  vtkOpenGLState* ostate = this->Context->GetState();
  this->CoverageFramebuffer->Bind(GL_DRAW_FRAMEBUFFER);
  this->CoverageFramebuffer->ActivateDrawBuffers(1);
  ostate->vtkglDisable(GL_SCISSOR_TEST); // the caller restores it
  ostate->vtkglViewport(0, 0, w, h);
  ostate->vtkglColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  return true;
}

bool vtkEnsembleBuffer::BeginSumBesideDepthPass(bool coverage)
{
  if (coverage && !this->BeginCoveragePass())
  {
    return false;
  }
  vtkOpenGLState* ostate = this->Context->GetState();
  // Draw buffers are state of a framebuffer object: one object for each set, never changed
  // (VTK's state cache compares only the buffers asked for, so it would not shrink a set of
  // two to one). Attaching a texture that is attached already does nothing.
  vtkOpenGLFramebufferObject* framebuffer =
    coverage ? this->SumAndCoverageFramebuffer : this->SumBesideDepthFramebuffer;
  ostate->PushFramebufferBindings();
  framebuffer->SetContext(this->Context);
  framebuffer->Bind();
  framebuffer->AddColorAttachment(0, this->Sum);
  if (coverage)
  {
    framebuffer->AddColorAttachment(1, this->Coverage);
  }
  framebuffer->ActivateDrawBuffers(coverage ? 2 : 1);
  ostate->PopFramebufferBindings();
  framebuffer->Bind(GL_DRAW_FRAMEBUFFER);
  this->Tiles.ApplyTests(this->Context); // the caller restores them after the last pass
  ostate->vtkglViewport(0, 0, this->GetPassWidth(), this->GetPassHeight());
  return true;
}

void vtkEnsembleBuffer::Resolve(int x, int y, int numberOfPasses, bool exactCoverage)
{
  exactCoverage = exactCoverage && this->Coverage->GetHandle() != 0;
  // The mean is premultiplied: "over" the scene.
  vtkScopedOverBlending over(
    this->Context->GetState(), x, y, this->ViewportWidth, this->ViewportHeight);
  vtkShaderProgram* program = this->Mean->Program;
  this->Context->GetShaderCache()->ReadyShaderProgram(program);
  this->Sum->Activate();
  program->SetUniformi("sumTexture", this->Sum->GetTextureUnit());
  program->SetUniformi("subpixelLevel", this->SubpixelLevel);
  program->SetUniformi("interpolate",
    this->Width != this->ViewportWidth || this->Height != this->ViewportHeight ? 1 : 0);
  program->SetUniformf("inversePassCount", 1.0f / float(numberOfPasses));
  program->SetUniformf("passCount", float(numberOfPasses));
  this->Tiles.Activate(this->Context, program);
  program->SetUniformi("exactCoverage", exactCoverage ? 1 : 0);
  if (exactCoverage)
  {
    this->Coverage->Activate();
  }
  // The sampler must name a unit even when it is not read.
  program->SetUniformi("coverageTexture",
    exactCoverage ? this->Coverage->GetTextureUnit() : this->Sum->GetTextureUnit());
  this->Mean->Render();
  if (exactCoverage)
  {
    this->Coverage->Deactivate();
  }
  this->Tiles.Deactivate();
  this->Sum->Deactivate();
}

void vtkEnsembleBuffer::MarkFootprint(int x, int y)
{
  vtkShaderProgram* program = ReadyQuad(this->Footprint, this->Context, vtkEnsembleFootprintFS);
  if (!program)
  {
    return;
  }
  vtkOpenGLState* ostate = this->Context->GetState();
  vtkSavedGLState saved(ostate);
  SetReplacingState(ostate, x, y, this->ViewportWidth, this->ViewportHeight, false);
  this->Sum->Activate();
  program->SetUniformi("sumTexture", this->Sum->GetTextureUnit());
  program->SetUniformi("subpixelLevel", this->SubpixelLevel);
  this->Footprint->Render();
  this->Sum->Deactivate();
}

std::vector<unsigned char> vtkEnsembleBuffer::ReadSceneColor(int x, int y) const
{
  std::vector<unsigned char> color(size_t(this->ViewportWidth) * size_t(this->ViewportHeight) * 4);
  if (!this->Context)
  {
    return color;
  }
  vtkOpenGLState* ostate = this->Context->GetState();
  ostate->vtkglPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(
    x, y, this->ViewportWidth, this->ViewportHeight, GL_RGBA, GL_UNSIGNED_BYTE, color.data());
  return color;
}

bool vtkEnsembleBuffer::DrawScene(int x, int y, const std::vector<unsigned char>& color)
{
  if (color.size() != size_t(this->ViewportWidth) * size_t(this->ViewportHeight) * 4)
  {
    return false;
  }
  vtkShaderProgram* program = ReadyQuad(this->SceneQuad, this->Context, vtkEnsembleSceneFS);
  if (!program)
  {
    return false;
  }
  if (!vtkFramebufferTextures::HasSize(this->SceneColor, this->ViewportWidth, this->ViewportHeight))
  {
    vtkFramebufferTextures::UseNearestTexels(this->SceneColor, this->Context);
    if (!this->SceneColor->Allocate2D(
          this->ViewportWidth, this->ViewportHeight, 4, VTK_UNSIGNED_CHAR))
    {
      return false;
    }
  }
  vtkOpenGLState* ostate = this->Context->GetState();
  this->SceneColor->Activate();
  ostate->vtkglPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexSubImage2D(this->SceneColor->GetTarget(), 0, 0, 0, this->ViewportWidth, this->ViewportHeight,
    GL_RGBA, GL_UNSIGNED_BYTE, color.data());
  vtkTextureObject* depth = this->SceneDepth->GetTexture();
  depth->Activate();
  vtkSavedGLState saved(ostate);
  SetReplacingState(ostate, x, y, this->ViewportWidth, this->ViewportHeight, true);
  ostate->vtkglDisable(GL_SCISSOR_TEST);
  program->SetUniformi("sceneColorTexture", this->SceneColor->GetTextureUnit());
  program->SetUniformi("sceneDepthTexture", depth->GetTextureUnit());
  this->SceneQuad->Render();
  depth->Deactivate();
  this->SceneColor->Deactivate();
  return true;
}

size_t vtkEnsembleBuffer::GetGPUMemorySize() const
{
  if (!this->Context)
  {
    return 0;
  }
  const size_t samples = size_t(this->GetPassWidth()) * size_t(this->GetPassHeight());
  const size_t pixels = size_t(this->ViewportWidth) * size_t(this->ViewportHeight);
  // Two RGBA32F color buffers and a 32-bit depth buffer per sample, 32-bit depth per pixel of
  // the viewport, and the RGBA32F coverage when it is used; the composited scene's RGBA8 when
  // it is drawn; the noise estimate's RG32F per pixel of the image.
  const size_t coverage = this->Coverage->GetHandle() ? 16 : 0;
  const size_t secondHalf = this->SecondHalf->GetHandle() ? 16 : 0;
  const size_t noise = this->Noise->GetHandle() ? 8 : 0;
  const size_t sceneColor = this->SceneColor->GetHandle() ? 4 : 0;
  const size_t imagePixels = size_t(this->Width) * size_t(this->Height);
  return samples * (16 + 16 + 4 + coverage + secondHalf) + pixels * (4 + sceneColor) +
    imagePixels * noise;
}

void vtkEnsembleBuffer::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Accumulate.reset();
  this->Footprint.reset();
  this->SceneQuad.reset();
  this->AccumulateBoth.reset();
  this->Mean.reset();
  this->NoiseQuad.reset();
  this->Halves = false;
  this->HalvesSum = 0;
  for (vtkOpenGLFramebufferObject* framebuffer :
    { this->PassFramebuffer.Get(), this->SumFramebuffer.Get(), this->CoverageFramebuffer.Get(),
      this->SumBesideDepthFramebuffer.Get(), this->SumAndCoverageFramebuffer.Get(),
      this->HalvesFramebuffer.Get(), this->NoiseFramebuffer.Get() })
  {
    framebuffer->ReleaseGraphicsResources(window);
  }
  for (vtkTextureObject* texture : { this->PassColor.Get(), this->PassDepth.Get(), this->Sum.Get(),
         this->Coverage.Get(), this->SecondHalf.Get(), this->Noise.Get(), this->SceneColor.Get() })
  {
    texture->ReleaseGraphicsResources(window);
  }
  this->SceneDepth->ReleaseGraphicsResources(window);
  this->Tiles.ReleaseGraphicsResources(window);
  this->Context = nullptr;
  this->Width = this->Height = this->ViewportWidth = this->ViewportHeight = 0;
  this->SubpixelLevel = 0;
  this->SampleDistance = 1.0;
}

void vtkEnsembleBuffer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Size: " << this->Width << " x " << this->Height << "\n";
  os << indent << "Viewport: " << this->ViewportWidth << " x " << this->ViewportHeight << "\n";
  os << indent << "SampleDistance: " << this->SampleDistance << "\n";
  os << indent << "SubpixelLevel: " << this->SubpixelLevel << "\n";
  os << indent << "GPUMemorySize: " << this->GetGPUMemorySize() << "\n";
}
