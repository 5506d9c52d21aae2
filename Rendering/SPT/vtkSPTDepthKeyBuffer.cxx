#include "vtkSPTDepthKeyBuffer.h"

#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLLoader.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

#include "vtkSPTDepthSlabs.h"
#include "vtkSPTSlabsMeanFS.h"
#include "vtkSPTSurvivorsFS.h"

#include <algorithm>
#include <initializer_list>
#include <string>

vtkStandardNewMacro(vtkSPTDepthKeyBuffer);

vtkSPTDepthKeyBuffer::vtkSPTDepthKeyBuffer() = default;

vtkSPTDepthKeyBuffer::~vtkSPTDepthKeyBuffer() = default;

bool vtkSPTDepthKeyBuffer::IsSupported(vtkOpenGLRenderWindow* renWin)
{
  if (!renWin)
  {
    return false;
  }
  renWin->MakeCurrent();
  const bool imageLoadStore = vtkOpenGLLoader::HasVersion(4, 2) ||
    vtkOpenGLLoader::HasExtension("GL_ARB_shader_image_load_store");
  const bool clearTexture =
    vtkOpenGLLoader::HasVersion(4, 4) || vtkOpenGLLoader::HasExtension("GL_ARB_clear_texture");
  return imageLoadStore && clearTexture;
}

bool vtkSPTDepthKeyBuffer::Prepare(
  vtkOpenGLRenderWindow* renWin, int width, int height, int layers, int slabs)
{
  // The texture holds the compiled repetitions' layers, a power of two, per slab: the layers a
  // group uses change with its count, and counts that share their programs share the texture too.
  slabs = std::max(slabs, 1);
  const int allocated = GetCompiledRepetitions(layers) * slabs;
  if (renWin == this->Context && width == this->Width && height == this->Height &&
    allocated == this->AllocatedLayers && slabs == this->Slabs)
  {
    this->Layers = slabs > 1 ? allocated : layers;
    return this->PrepareSlabs(renWin, width, height, slabs);
  }
  if (renWin != this->Context)
  {
    this->ReleaseGraphicsResources(this->Context);
  }
  else
  {
    // Another size: the survivors' shaders still serve.
    this->Keys->ReleaseGraphicsResources(renWin);
    this->Width = this->Height = this->Layers = this->AllocatedLayers = 0;
  }
  const int maxSize = vtkOpenGLLoader::Max3DTextureSize();
  if (std::max({ allocated, width, height }) > maxSize)
  {
    vtkErrorMacro("The depth keys of " << width << " x " << height << " samples and " << allocated
                                       << " repetitions are more than this OpenGL's 3D textures "
                                          "hold per side ("
                                       << maxSize
                                       << ", GL_MAX_3D_TEXTURE_SIZE): render a smaller image "
                                          "(the viewport times SubpixelLevel).");
    this->ReleaseGraphicsResources(renWin);
    return false;
  }
  if (!CreateIntegerImage(this->Keys, renWin, allocated, width, height))
  {
    vtkErrorMacro("Could not allocate the " << width << "x" << height << "x" << allocated
                                            << " depth keys of several repetitions per pass.");
    this->ReleaseGraphicsResources(renWin);
    return false;
  }
  this->Context = renWin;
  this->Width = width;
  this->Height = height;
  this->Layers = slabs > 1 ? allocated : layers;
  this->AllocatedLayers = allocated;
  this->Slabs = slabs;
  return this->PrepareSlabs(renWin, width, height, slabs);
}

bool vtkSPTDepthKeyBuffer::PrepareSlabs(
  vtkOpenGLRenderWindow* renWin, int width, int height, int slabs)
{
  if (slabs <= 1 ||
    (width == this->SlabWidth && height == this->SlabHeight && slabs == this->SlabCount &&
      this->SlabDepths->GetHandle()))
  {
    return true;
  }
  if (!CreateIntegerImage(this->SlabDepths, renWin, SlabTerms * slabs, width, height))
  {
    vtkErrorMacro("Could not allocate the optical depths of "
      << slabs << " depth slabs for " << width << "x" << height << " samples.");
    this->ReleaseGraphicsResources(renWin);
    return false;
  }
  this->SlabWidth = width;
  this->SlabHeight = height;
  this->SlabCount = slabs;
  this->ClearSlabs();
  return true;
}

void vtkSPTDepthKeyBuffer::ClearSlabs()
{
  const GLuint zero = 0u;
  if (this->SlabDepths->GetHandle())
  {
    glClearTexImage(this->SlabDepths->GetHandle(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  }
}

void vtkSPTDepthKeyBuffer::BindSlabImage(int unit)
{
  BindIntegerImage(this->SlabDepths, unit);
}

int vtkSPTDepthKeyBuffer::GetCompiledRepetitions(int repetitions)
{
  return vtkMath::NearestPowerOfTwo(repetitions);
}

void vtkSPTDepthKeyBuffer::Clear(const int footprint[4])
{
  // The texture is layers x width x height: every layer of the footprint's samples.
  const GLuint nothingKept = 0xFFFFFFFFu;
  if (footprint[2] > 0 && footprint[3] > 0)
  {
    glClearTexSubImage(this->Keys->GetHandle(), 0, 0, footprint[0], footprint[1],
      this->AllocatedLayers, footprint[2], footprint[3], GL_RED_INTEGER, GL_UNSIGNED_INT,
      &nothingKept);
  }
}

bool vtkSPTDepthKeyBuffer::CreateIntegerImage(
  vtkTextureObject* texture, vtkOpenGLRenderWindow* renWin, int layers, int width, int height)
{
  texture->SetContext(renWin);
  texture->SetInternalFormat(GL_R32UI);
  texture->SetFormat(GL_RED_INTEGER);
  texture->SetDataType(GL_UNSIGNED_INT);
  texture->SetMinificationFilter(vtkTextureObject::Nearest);
  texture->SetMagnificationFilter(vtkTextureObject::Nearest);
  return texture->Create3DFromRaw(layers, width, height, 1, VTK_UNSIGNED_INT, nullptr);
}

void vtkSPTDepthKeyBuffer::BindIntegerImage(vtkTextureObject* texture, int unit)
{
  glBindImageTexture(
    static_cast<GLuint>(unit), texture->GetHandle(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32UI);
}

void vtkSPTDepthKeyBuffer::BindImage(int unit)
{
  BindIntegerImage(this->Keys, unit);
}

void vtkSPTDepthKeyBuffer::UnbindImage(int unit)
{
  glBindImageTexture(static_cast<GLuint>(unit), 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);
}

void vtkSPTDepthKeyBuffer::Barrier()
{
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
    GL_FRAMEBUFFER_BARRIER_BIT);
}

bool vtkSPTDepthKeyBuffer::PrepareSurvivors(
  int unit, int slabsUnit, int repetitions, int secondHalfFrom, bool sortKeys)
{
  const int which = sortKeys ? 1 : 0;
  std::unique_ptr<vtkOpenGLQuadHelper>& helper = this->Survivors[which];
  // A slab's layers are the most repetitions a group holds: they size the sort's array.
  const int passRepetitions = this->AllocatedLayers / this->Slabs;
  if (!helper || this->SurvivorsRepetitions[which] != passRepetitions ||
    this->SurvivorsSlabs[which] != this->Slabs)
  {
    std::string source = vtkSPTSurvivorsFS;
    const std::string slabTerms =
      this->Slabs > 1 ? "\n#define SPT_SLAB_TERMS " + std::to_string(SlabTerms) : std::string();
    vtkShaderProgram::Substitute(source, "//SPT::Survivors::Dec",
      std::string(sortKeys ? "#define SPT_SORT_KEYS\n" : "") + "#define SPT_REPETITIONS_PER_PASS " +
        std::to_string(passRepetitions) + "\n#define SPT_DEPTH_SLABS " +
        std::to_string(this->Slabs) + slabTerms);
    helper.reset(new vtkOpenGLQuadHelper(this->Context, nullptr, source.c_str(), ""));
    this->SurvivorsRepetitions[which] = passRepetitions;
    this->SurvivorsSlabs[which] = this->Slabs;
  }
  vtkShaderProgram* program = helper->Program;
  if (!program)
  {
    return false;
  }
  this->Context->GetShaderCache()->ReadyShaderProgram(program);
  program->SetUniformi("depthKeys", unit);
  if (program->IsUniformUsed("slabSums"))
  {
    program->SetUniformi("slabSums", slabsUnit);
  }
  program->SetUniformi("repetitionsInGroup", repetitions);
  program->SetUniformi("secondHalfFrom", secondHalfFrom);
  const float passSize[2] = { static_cast<float>(this->Width), static_cast<float>(this->Height) };
  program->SetUniform2f("passSize", passSize);
  helper->Render();
  return true;
}

bool vtkSPTDepthKeyBuffer::DrawSlabsMeanColor(int unit, const std::string& defines)
{
  if (!this->SlabsMean || this->SlabsMeanDefines != defines)
  {
    std::string source = vtkSPTSlabsMeanFS;
    vtkShaderProgram::Substitute(source, "//SPT::Slabs::Dec", defines);
    vtkShaderProgram::Substitute(source, "//SPT::Slabs::Impl", vtkSPTDepthSlabs);
    this->SlabsMean.reset(new vtkOpenGLQuadHelper(this->Context, nullptr, source.c_str(), ""));
    this->SlabsMeanDefines = defines;
  }
  vtkShaderProgram* program = this->SlabsMean->Program;
  if (!program)
  {
    return false;
  }
  this->Context->GetShaderCache()->ReadyShaderProgram(program);
  program->SetUniformi("slabSums", unit);
  const float passSize[2] = { static_cast<float>(this->Width), static_cast<float>(this->Height) };
  program->SetUniform2f("passSize", passSize);
  this->SlabsMean->Render();
  return true;
}

std::vector<unsigned int> vtkSPTDepthKeyBuffer::Read()
{
  const size_t samples = this->Context ? size_t(this->Width) * size_t(this->Height) : 0;
  std::vector<unsigned int> keys(samples * size_t(this->Layers));
  if (keys.empty())
  {
    return keys;
  }
  // The texture is allocated layers x width x height (see Prepare()): every sample's layers
  // in use, without the unused ones after them.
  const bool full = this->Layers == this->AllocatedLayers;
  std::vector<unsigned int> allocated(full ? 0 : samples * size_t(this->AllocatedLayers));
  this->Keys->Activate();
  glGetTexImage(this->Keys->GetTarget(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT,
    full ? keys.data() : allocated.data());
  this->Keys->Deactivate();
  for (size_t sample = 0; !full && sample < samples; ++sample)
  {
    std::copy_n(allocated.begin() + sample * this->AllocatedLayers, this->Layers,
      keys.begin() + sample * this->Layers);
  }
  return keys;
}

void vtkSPTDepthKeyBuffer::Write(const std::vector<unsigned int>& keys)
{
  if (!this->Context || keys.empty() ||
    keys.size() != size_t(this->Width) * size_t(this->Height) * size_t(this->Layers))
  {
    return;
  }
  this->Keys->Activate();
  glTexSubImage3D(this->Keys->GetTarget(), 0, 0, 0, 0, this->Layers, this->Width, this->Height,
    GL_RED_INTEGER, GL_UNSIGNED_INT, keys.data());
  this->Keys->Deactivate();
}

std::vector<unsigned int> vtkSPTDepthKeyBuffer::ReadSlabs()
{
  std::vector<unsigned int> sums;
  if (!this->Context || !this->SlabDepths->GetHandle())
  {
    return sums;
  }
  sums.resize(
    size_t(this->SlabWidth) * size_t(this->SlabHeight) * size_t(SlabTerms * this->SlabCount));
  this->SlabDepths->Activate();
  glGetTexImage(this->SlabDepths->GetTarget(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, sums.data());
  this->SlabDepths->Deactivate();
  return sums;
}

void vtkSPTDepthKeyBuffer::WriteSlabs(const std::vector<unsigned int>& sums)
{
  if (!this->Context || !this->SlabDepths->GetHandle() ||
    sums.size() !=
      size_t(this->SlabWidth) * size_t(this->SlabHeight) * size_t(SlabTerms * this->SlabCount))
  {
    return;
  }
  this->SlabDepths->Activate();
  glTexSubImage3D(this->SlabDepths->GetTarget(), 0, 0, 0, 0, SlabTerms * this->SlabCount,
    this->SlabWidth, this->SlabHeight, GL_RED_INTEGER, GL_UNSIGNED_INT, sums.data());
  this->SlabDepths->Deactivate();
}

size_t vtkSPTDepthKeyBuffer::GetGPUMemorySize() const
{
  if (!this->Context)
  {
    return 0;
  }
  const size_t keys = size_t(this->Width) * size_t(this->Height) * size_t(this->AllocatedLayers);
  const size_t slabs = this->SlabDepths->GetHandle()
    ? size_t(this->SlabWidth) * size_t(this->SlabHeight) * size_t(SlabTerms * this->SlabCount)
    : 0;
  return 4 * (keys + slabs);
}

void vtkSPTDepthKeyBuffer::ReleaseGraphicsResources(vtkWindow* window)
{
  if (window)
  {
    this->Keys->ReleaseGraphicsResources(window);
    this->SlabDepths->ReleaseGraphicsResources(window);
  }
  this->SlabWidth = this->SlabHeight = this->SlabCount = 0;
  this->Slabs = 1;
  this->SlabsMean.reset();
  this->SlabsMeanDefines.clear();
  this->Survivors[0].reset();
  this->Survivors[1].reset();
  this->SurvivorsRepetitions[0] = this->SurvivorsRepetitions[1] = 0;
  this->Context = nullptr;
  this->Width = this->Height = this->Layers = this->AllocatedLayers = 0;
}

void vtkSPTDepthKeyBuffer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Size: " << this->Width << " x " << this->Height << " x " << this->Layers
     << " (allocated " << this->AllocatedLayers << ")\n";
  os << indent << "Slabs: " << this->Slabs << "\n";
}
