#include "vtkSPTDepthKeyBuffer.h"

#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkSPTOpenGL.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

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
  const bool imageLoadStore =
    vtkSPTOpenGL::HasVersion(4, 2) || vtkSPTOpenGL::HasExtension("GL_ARB_shader_image_load_store");
  const bool clearTexture =
    vtkSPTOpenGL::HasVersion(4, 4) || vtkSPTOpenGL::HasExtension("GL_ARB_clear_texture");
  return imageLoadStore && clearTexture;
}

bool vtkSPTDepthKeyBuffer::Prepare(vtkOpenGLRenderWindow* renWin, int width, int height, int layers)
{
  // The texture holds the compiled lanes' layers, a power of two: the layers a group uses
  // change with its count, and counts that share their programs share the texture too.
  const int allocated = GetCompiledLanes(layers);
  if (renWin == this->Context && width == this->Width && height == this->Height &&
    allocated == this->AllocatedLayers)
  {
    this->Layers = layers;
    return true;
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
  const int maxSize = vtkSPTOpenGL::Max3DTextureSize();
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
  this->Keys->SetContext(renWin);
  this->Keys->SetInternalFormat(GL_R32UI);
  this->Keys->SetFormat(GL_RED_INTEGER);
  this->Keys->SetDataType(GL_UNSIGNED_INT);
  this->Keys->SetMinificationFilter(vtkTextureObject::Nearest);
  this->Keys->SetMagnificationFilter(vtkTextureObject::Nearest);
  if (!this->Keys->Create3DFromRaw(allocated, width, height, 1, VTK_UNSIGNED_INT, nullptr))
  {
    vtkErrorMacro("Could not allocate the " << width << "x" << height << "x" << allocated
                                            << " depth keys of several repetitions per pass.");
    this->ReleaseGraphicsResources(renWin);
    return false;
  }
  this->Context = renWin;
  this->Width = width;
  this->Height = height;
  this->Layers = layers;
  this->AllocatedLayers = allocated;
  return true;
}

int vtkSPTDepthKeyBuffer::GetCompiledLanes(int repetitions)
{
  return vtkMath::NearestPowerOfTwo(repetitions);
}

void vtkSPTDepthKeyBuffer::Clear()
{
  const GLuint nothingKept = 0xFFFFFFFFu;
  glClearTexImage(this->Keys->GetHandle(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &nothingKept);
}

void vtkSPTDepthKeyBuffer::BindImage(int unit)
{
  glBindImageTexture(
    static_cast<GLuint>(unit), this->Keys->GetHandle(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32UI);
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
  int unit, int repetitions, int secondHalfFrom, bool sortKeys)
{
  std::unique_ptr<vtkOpenGLQuadHelper>& helper = this->Survivors[sortKeys ? 1 : 0];
  // The layers are the most repetitions a group holds: they size the sort's array.
  const int lanes = this->AllocatedLayers;
  if (!helper || this->SurvivorsLanes[sortKeys ? 1 : 0] != lanes)
  {
    std::string source = vtkSPTSurvivorsFS;
    vtkShaderProgram::Substitute(source, "//SPT::Survivors::Dec",
      std::string(sortKeys ? "#define SPT_SORT_KEYS\n" : "") + "#define SPT_REPETITIONS_PER_PASS " +
        std::to_string(lanes));
    helper.reset(new vtkOpenGLQuadHelper(this->Context, nullptr, source.c_str(), ""));
    this->SurvivorsLanes[sortKeys ? 1 : 0] = lanes;
  }
  vtkShaderProgram* program = helper->Program;
  if (!program)
  {
    return false;
  }
  this->Context->GetShaderCache()->ReadyShaderProgram(program);
  program->SetUniformi("depthKeys", unit);
  program->SetUniformi("repetitionsInGroup", repetitions);
  program->SetUniformi("secondHalfFrom", secondHalfFrom);
  const float passSize[2] = { static_cast<float>(this->Width), static_cast<float>(this->Height) };
  program->SetUniform2f("passSize", passSize);
  helper->Render();
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

size_t vtkSPTDepthKeyBuffer::GetGPUMemorySize() const
{
  return this->Context
    ? size_t(this->Width) * size_t(this->Height) * size_t(this->AllocatedLayers) * 4
    : 0;
}

void vtkSPTDepthKeyBuffer::ReleaseGraphicsResources(vtkWindow* window)
{
  if (window)
  {
    this->Keys->ReleaseGraphicsResources(window);
  }
  this->Survivors[0].reset();
  this->Survivors[1].reset();
  this->SurvivorsLanes[0] = this->SurvivorsLanes[1] = 0;
  this->Context = nullptr;
  this->Width = this->Height = this->Layers = this->AllocatedLayers = 0;
}

void vtkSPTDepthKeyBuffer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Size: " << this->Width << " x " << this->Height << " x " << this->Layers
     << " (allocated " << this->AllocatedLayers << ")\n";
}
