#include "vtkSPTComputeTraversal.h"

#include "vtkObjectFactory.h"
#include "vtkOpenGLLoader.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

#include "vtkSPTComputeSumsFS.h"
#include "vtkSPTDepthKeyBuffer.h"

#include <algorithm>
#include <initializer_list>
#include <string>
#include <vector>

namespace
{
// A compute program built through OpenGL, in a vtkShaderProgram so that VTK's uniform setters
// (which need only a linked handle) set its uniforms as they set any other program's.
class vtkSPTComputeProgram : public vtkShaderProgram
{
public:
  static vtkSPTComputeProgram* New();
  vtkTypeMacro(vtkSPTComputeProgram, vtkShaderProgram);

  // Compile and link; false with the compiler's or linker's log.
  bool Build(const std::string& source, std::string& log)
  {
    const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
    const char* text = source.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint status = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &status);
    if (status != GL_TRUE)
    {
      log = InfoLog(shader, glGetShaderiv, glGetShaderInfoLog);
      glDeleteShader(shader);
      return false;
    }
    const GLuint program = glCreateProgram();
    glAttachShader(program, shader);
    glLinkProgram(program);
    glDetachShader(program, shader);
    glDeleteShader(shader);
    glGetProgramiv(program, GL_LINK_STATUS, &status);
    if (status != GL_TRUE)
    {
      log = InfoLog(program, glGetProgramiv, glGetProgramInfoLog);
      glDeleteProgram(program);
      return false;
    }
    this->Handle = static_cast<int>(program);
    this->Linked = true;
    return true;
  }

  void Use() { glUseProgram(static_cast<GLuint>(this->Handle)); }

protected:
  vtkSPTComputeProgram() = default;
  ~vtkSPTComputeProgram() override = default;

private:
  // The info log of a shader or a program, read with its own pair of functions.
  template <typename GetValue, typename GetLog>
  static std::string InfoLog(GLuint object, GetValue getValue, GetLog getLog)
  {
    GLint length = 0;
    getValue(object, GL_INFO_LOG_LENGTH, &length);
    std::vector<char> buffer(static_cast<size_t>(length) + 1, '\0');
    getLog(object, length, nullptr, buffer.data());
    return buffer.data();
  }

  vtkSPTComputeProgram(const vtkSPTComputeProgram&) = delete;
  void operator=(const vtkSPTComputeProgram&) = delete;
};

vtkStandardNewMacro(vtkSPTComputeProgram);
}

vtkStandardNewMacro(vtkSPTComputeTraversal);

namespace
{
// Two targets of four terms per sample.
constexpr int Layers = 8;
}

vtkSPTComputeTraversal::vtkSPTComputeTraversal() = default;

vtkSPTComputeTraversal::~vtkSPTComputeTraversal() = default;

bool vtkSPTComputeTraversal::IsSupported(vtkOpenGLRenderWindow* renWin)
{
  if (!renWin)
  {
    return false;
  }
  renWin->MakeCurrent();
  return vtkOpenGLLoader::HasVersion(4, 3) ||
    vtkOpenGLLoader::HasExtension("GL_ARB_compute_shader");
}

bool vtkSPTComputeTraversal::IsSoftwareRasterizer(vtkOpenGLRenderWindow* renWin)
{
  if (!renWin)
  {
    return false;
  }
  renWin->MakeCurrent();
  const GLubyte* name = glGetString(GL_RENDERER);
  const std::string renderer = name ? reinterpret_cast<const char*>(name) : "";
  for (const char* software : { "llvmpipe", "softpipe", "SwiftShader", "Software Rasterizer" })
  {
    if (renderer.find(software) != std::string::npos)
    {
      return true;
    }
  }
  return false;
}

bool vtkSPTComputeTraversal::IsWanted(
  vtkOpenGLRenderWindow* renWin, bool onAnyRenderer, int width, int height)
{
  if (renWin != this->QueriedContext)
  {
    this->Supported = IsSupported(renWin);
    this->Software = IsSoftwareRasterizer(renWin);
    this->MaxSize = this->Supported ? vtkOpenGLLoader::Max3DTextureSize() : 0;
    this->QueriedContext = renWin;
    this->BuildFailed = false;
  }
  // The sums are a 3D texture of (term, sample): a larger pass rasterizes every cell.
  const bool fits = std::max({ Layers, width, height }) <= this->MaxSize;
  return this->Supported && !this->BuildFailed && fits && (onAnyRenderer || this->Software);
}

vtkShaderProgram* vtkSPTComputeTraversal::GetProgram(
  vtkOpenGLRenderWindow* renWin, const std::string& source)
{
  if (renWin != this->Context)
  {
    this->ReleaseContextResources(this->Context);
    this->Context = renWin;
  }
  auto found = this->Programs.find(source);
  if (found != this->Programs.end())
  {
    return found->second;
  }
  vtkSmartPointer<vtkSPTComputeProgram> program = vtkSmartPointer<vtkSPTComputeProgram>::New();
  std::string log;
  if (!program->Build(source, log))
  {
    // A driver can advertise compute shaders and still not build this one (a GLSL version or
    // a limit below what OpenGL 4.3 promises). The rasterizer draws the same image.
    vtkWarningMacro("The compute traversal does not build in this OpenGL context; its cells are "
                    "rasterized instead. The compiler says: "
      << log);
    if (renWin == this->QueriedContext)
    {
      this->BuildFailed = true;
    }
    return nullptr;
  }
  this->Programs[source] = program;
  return program;
}

void vtkSPTComputeTraversal::Use(vtkOpenGLRenderWindow* renWin, vtkShaderProgram* program)
{
  // VTK's cache binds a program only when it is not its last one: it must forget it.
  renWin->GetShaderCache()->ReleaseCurrentShader();
  static_cast<vtkSPTComputeProgram*>(program)->Use();
}

void vtkSPTComputeTraversal::Dispatch(vtkShaderProgram* program, vtkIdType first, vtkIdType count)
{
  // A dispatch holds at most GL_MAX_COMPUTE_WORK_GROUP_COUNT groups along x (65,535 at the
  // least: 4 million cells of 64): larger ranges go in several.
  GLint maxGroups = 0;
  glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 0, &maxGroups);
  const vtkIdType most = vtkIdType(std::max(maxGroups, 1)) * GroupSize;
  for (vtkIdType done = 0; done < count; done += most)
  {
    const vtkIdType cells = std::min(most, count - done);
    program->SetUniformi("firstCell", static_cast<int>(first + done));
    program->SetUniformi("cellCount", static_cast<int>(cells));
    glDispatchCompute(static_cast<GLuint>((cells + GroupSize - 1) / GroupSize), 1, 1);
  }
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
    GL_TEXTURE_UPDATE_BARRIER_BIT);
}

bool vtkSPTComputeTraversal::PrepareSums(vtkOpenGLRenderWindow* renWin, int width, int height)
{
  if (renWin != this->Context || width != this->Width || height != this->Height)
  {
    if (renWin != this->Context)
    {
      this->ReleaseContextResources(this->Context);
      this->Context = renWin;
    }
    else if (this->Sums->GetHandle())
    {
      this->Sums->ReleaseGraphicsResources(renWin);
    }
    if (!vtkSPTDepthKeyBuffer::CreateIntegerImage(this->Sums, renWin, Layers, width, height))
    {
      vtkErrorMacro("Could not allocate the compute traversal's " << width << "x" << height
                                                                  << " fixed-point sums.");
      this->Width = this->Height = 0;
      return false;
    }
    this->Width = width;
    this->Height = height;
  }
  const GLuint zero = 0;
  glClearTexImage(this->Sums->GetHandle(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  return true;
}

void vtkSPTComputeTraversal::BindSumsImage(int unit)
{
  vtkSPTDepthKeyBuffer::BindIntegerImage(this->Sums, unit);
}

bool vtkSPTComputeTraversal::AddSums(vtkOpenGLRenderWindow* renWin, bool secondTarget)
{
  std::unique_ptr<vtkOpenGLQuadHelper>& quad = this->AddSumsQuads[secondTarget ? 1 : 0];
  if (!quad)
  {
    std::string source = vtkSPTComputeSumsFS;
    vtkShaderProgram::Substitute(source, "//Volume::Defines::Dec",
      std::string(secondTarget ? "#define ENSEMBLE_SECOND_HALF\n" : "") + "#define SPT_FIXED_ONE " +
        std::to_string(FixedPointOne));
    quad.reset(new vtkOpenGLQuadHelper(renWin, nullptr, source.c_str(), ""));
  }
  vtkShaderProgram* program = quad->Program;
  if (!program)
  {
    return false;
  }
  renWin->GetShaderCache()->ReadyShaderProgram(program);
  this->Sums->Activate();
  program->SetUniformi("sums", this->Sums->GetTextureUnit());
  quad->Render();
  this->Sums->Deactivate();
  return true;
}

size_t vtkSPTComputeTraversal::GetGPUMemorySize() const
{
  return size_t(this->Width) * size_t(this->Height) * Layers * 4;
}

void vtkSPTComputeTraversal::ReleaseGraphicsResources(vtkWindow* window)
{
  this->ReleaseContextResources(window);
  // A later window may have this one's address: it is asked again.
  this->QueriedContext = nullptr;
}

void vtkSPTComputeTraversal::ReleaseContextResources(vtkWindow* window)
{
  if (window)
  {
    for (auto& entry : this->Programs)
    {
      entry.second->ReleaseGraphicsResources(window);
    }
    this->Sums->ReleaseGraphicsResources(window);
  }
  this->Programs.clear();
  this->AddSumsQuads[0].reset();
  this->AddSumsQuads[1].reset();
  this->Width = this->Height = 0;
  this->Context = nullptr;
}

void vtkSPTComputeTraversal::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Programs: " << this->Programs.size() << "\n";
  os << indent << "Sums: " << this->Width << " x " << this->Height << " x " << Layers << "\n";
}
