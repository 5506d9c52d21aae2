#include "vtkHAVSVolumeMapper.h"

#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLLoader.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include "vtkGPUFrameTimer.h"
#include "vtkHAVSFaceBuffers.h"
#include "vtkHAVSKBuffer.h"
#include "vtkHAVSNearCap.h"
#include "vtkPreIntegrationTable.h"
#include "vtkSavedGLState.h"
#include "vtkTetrahedralMesh.h"
#include "vtkVolumeViewMatrices.h"

#include "vtkHAVSFacesFS.h"
#include "vtkHAVSFacesVS.h"
#include "vtkHAVSFlushFS.h"
#include "vtkHAVSKBufferCommon.h"

#include <memory>
#include <string>

class vtkHAVSVolumeMapper::vtkInternals
{
public:
  vtkNew<vtkHAVSFaceBuffers> Faces;
  vtkHAVSNearCap NearCap;
  vtkNew<vtkPreIntegrationTable> Table;
  vtkNew<vtkHAVSKBuffer> KBuffer;
  vtkVolumeViewMatrices Matrices;
  vtkTetrahedralMesh* Mesh = nullptr; // the base class's
  // The frame's context, as the base class has it.
  vtkOpenGLRenderWindow* Context = nullptr;
  std::unique_ptr<vtkOpenGLQuadHelper> Flush;
  std::string FlushSource;
  vtkGPUFrameTimer Timer;
  int AccessInUse = -1;
  bool InterlockFailed = false;
  int ReportedAccessError = -1;

  std::string Source(const char* shader) const
  {
    std::string source = shader;
    // The segments are cut by the clipping planes only where the mapper has some.
    vtkShaderProgram::Substitute(source, "//HAVS::Defines::Dec",
      this->KBuffer->GetShaderDefinitions() + this->Matrices.ClippingPlaneDefine("HAVS"));
    vtkShaderProgram::Substitute(source, "//HAVS::KBuffer::Impl", vtkHAVSKBufferCommon);
    return source;
  }

  int ChooseAccess(int requested)
  {
    const bool interlock =
      !this->InterlockFailed && vtkHAVSKBuffer::HasExtension("GL_ARB_fragment_shader_interlock");
    const bool fetch = vtkHAVSKBuffer::HasExtension("GL_EXT_shader_framebuffer_fetch");
    const bool images = vtkHAVSKBuffer::HasExtension("GL_ARB_shader_image_load_store");
    switch (requested)
    {
      case AUTOMATIC:
        return interlock ? FRAGMENT_SHADER_INTERLOCK : (fetch ? FRAMEBUFFER_FETCH : 0);
      case FRAGMENT_SHADER_INTERLOCK:
        return interlock ? requested : 0;
      case FRAMEBUFFER_FETCH:
        return fetch ? requested : 0;
      default:
        return images ? requested : 0;
    }
  }

  void SetKBufferUniforms(vtkShaderProgram* program, vtkTextureObject* table)
  {
    this->Table->SetUniforms(program, table, this->Mesh->GetMaxEdgeLength());
    program->SetUniformMatrix3x3("VCMCLinear", this->Matrices.VCMCLinear);
    program->SetUniformMatrix4x4("DCVCMatrix", this->Matrices.DCVC);
    program->SetUniformi("parallelProjection", this->Matrices.ParallelProjection ? 1 : 0);
    this->Matrices.SetClippingPlaneUniforms(program);
  }

  bool DrawFaces(vtkTextureObject* table, int width, int height)
  {
    vtkShaderProgram* program = this->Context->GetShaderCache()->ReadyShaderProgram(
      vtkHAVSFacesVS, this->Source(vtkHAVSFacesFS).c_str(), "");
    if (!program)
    {
      return false;
    }
    GLint frontFace = GL_CCW;
    glGetIntegerv(GL_FRONT_FACE, &frontFace);
    this->KBuffer->BeginPass(program);
    this->SetKBufferUniforms(program, table);
    program->SetUniformMatrix4x4("MCVCMatrix", this->Matrices.MCVC);
    program->SetUniformMatrix4x4("VCDCMatrix", this->Matrices.VCDC);
    const float viewportSize[2] = { float(width), float(height) };
    program->SetUniform2f("viewportSize", viewportSize);
    // Outward faces seen from behind are where rays leave the mesh: back-facing, unless the
    // view mirrors space or front faces wind clockwise.
    const bool exitIsFrontFacing = (frontFace == GL_CW) != this->Matrices.Mirrored;
    program->SetUniformi("exitIsFrontFacing", exitIsFrontFacing ? 1 : 0);
    // The near cap faces the eye as faces where rays enter the mesh do.
    if (!this->DrawNearCap(program, !exitIsFrontFacing == (frontFace == GL_CCW)))
    {
      return false;
    }
    this->Faces->Draw(program);
    this->KBuffer->EndPass();
    return true;
  }

  bool DrawFlush(vtkTextureObject* table)
  {
    if (this->KBuffer->GetNumberOfEntries() < 2)
    {
      // One entry is no segment: the flush would composite nothing and only empty the entries,
      // which the next frame's Clear() does. (Drawn anyway, it would also lose the color on
      // llvmpipe: see FRAMEBUFFER_FETCH in vtkHAVSKBuffer.h.)
      return true;
    }
    const std::string source = this->Source(vtkHAVSFlushFS);
    if (!this->Flush || source != this->FlushSource)
    {
      this->Flush.reset(new vtkOpenGLQuadHelper(this->Context, nullptr, source.c_str(), ""));
      this->FlushSource = source;
    }
    vtkShaderProgram* program = this->Flush->Program;
    if (!program || !this->Context->GetShaderCache()->ReadyShaderProgram(program))
    {
      return false;
    }
    this->KBuffer->BeginPass(program);
    this->SetKBufferUniforms(program, table);
    this->Flush->Render();
    this->KBuffer->EndPass();
    return true;
  }

  bool DrawNearCap(vtkShaderProgram* program, bool counterClockwise)
  {
    // Where the near plane cuts the mesh, the rays start inside it: the cut enters the k-buffer
    // first, as faces where the rays enter the mesh, which the shader tells by their facing.
    if (!this->Matrices.NearPlaneCutsBounds)
    {
      return true;
    }
    double modelToClip[4][4];
    vtkMatrix4x4::Multiply4x4(
      &this->Matrices.ViewToClip[0][0], &this->Matrices.ModelToView[0][0], &modelToClip[0][0]);
    if (!this->NearCap.Build(this->Mesh, this->Faces->GetVertices(),
          this->Faces->GetVertexScalars(), modelToClip, vtkHAVSFaceBuffers::BoundaryScalarOffset,
          counterClockwise))
    {
      return true;
    }
    vtkOpenGLState* ostate = this->Context->GetState();
    vtkOpenGLState::ScopedglEnableDisable depthClamp(ostate, GL_DEPTH_CLAMP);
    ostate->vtkglEnable(GL_DEPTH_CLAMP); // the cut lies on the near plane
    if (!this->NearCap.Draw(program))
    {
      vtkGenericWarningMacro("Could not upload the near plane's cut through the mesh.");
    }
    return true;
  }
};

vtkStandardNewMacro(vtkHAVSVolumeMapper);

vtkHAVSVolumeMapper::vtkHAVSVolumeMapper()
  : Internals(new vtkInternals)
{
  this->Internals->Mesh = this->GetMesh();
}

vtkHAVSVolumeMapper::~vtkHAVSVolumeMapper() = default;

int vtkHAVSVolumeMapper::GetKBufferSynchronizationInUse()
{
  return this->Internals->AccessInUse;
}

vtkIdType vtkHAVSVolumeMapper::GetNumberOfFaces()
{
  return this->Internals->Faces->GetNumberOfFaces();
}

vtkIdType vtkHAVSVolumeMapper::GetNumberOfBoundaryFaces()
{
  return this->Internals->Faces->GetNumberOfBoundaryFaces();
}

vtkIdType vtkHAVSVolumeMapper::GetGPUMemorySize()
{
  const vtkInternals& internals = *this->Internals;
  return static_cast<vtkIdType>(internals.Faces->GetGPUMemorySize() +
    internals.Table->GetGPUMemorySize() + internals.KBuffer->GetGPUMemorySize() +
    internals.NearCap.GetGPUMemorySize());
}

bool vtkHAVSVolumeMapper::PrepareInput(vtkRenderer* ren, vtkVolume* vol)
{
  vtkInternals& internals = *this->Internals;
  if (!this->PrepareMesh(vol, false))
  {
    return false;
  }
  vtkTetrahedralMesh* mesh = this->GetMesh();
  vtkVolumeProperty* property = vol->GetProperty();
  internals.Faces->Update(mesh);
  if (!this->ComputeMatrices(ren, vol, internals.Matrices))
  {
    return false;
  }
  if (!internals.Table->Update(property, mesh->GetScalarRange(),
        mesh->GetMaxEdgeLength() * mesh->GetScale(), this->PreIntegrationScalarResolution,
        this->PreIntegrationThicknessResolution))
  {
    vtkErrorMacro(<< internals.Table->GetLastError());
    return false;
  }
  return true;
}

void vtkHAVSVolumeMapper::Render(vtkRenderer* ren, vtkVolume* vol)
{
  vtkInternals& internals = *this->Internals;
  RenderTarget target;
  if (!this->BeginFrame(ren, target))
  {
    return;
  }
  internals.Context = target.Window;
  vtkOpenGLRenderWindow* renWin = target.Window;
  internals.AccessInUse = -1;
  if (!this->PrepareInput(ren, vol))
  {
    return;
  }
  const int access = internals.ChooseAccess(this->KBufferSynchronization);
  if (!access)
  {
    if (internals.ReportedAccessError != this->KBufferSynchronization)
    {
      internals.ReportedAccessError = this->KBufferSynchronization;
      vtkErrorMacro("This OpenGL context cannot keep the k-buffer's read-modify-write in "
                    "primitive order as requested (KBufferSynchronization "
        << this->KBufferSynchronization
        << "): it needs GL_ARB_fragment_shader_interlock or "
           "GL_EXT_shader_framebuffer_fetch. "
           "SetKBufferSynchronizationToRasterizationOrder() renders without "
           "either, correctly only where the rasterizer keeps primitive order.");
    }
    return;
  }

  internals.Faces->Sort(internals.Matrices.MCVC, internals.Matrices.ParallelProjection);
  this->LastSortTime = internals.Faces->GetLastSortTime();
  vtkTextureObject* table = internals.Table->GetTexture(renWin);
  if (!table || !internals.Faces->Upload(renWin) ||
    !internals.KBuffer->Prepare(renWin, target.Width, target.Height, this->KBufferSize, access))
  {
    return;
  }
  this->DrawKBuffer(target, access);
}

void vtkHAVSVolumeMapper::DrawKBuffer(const RenderTarget& target, int access)
{
  vtkInternals& internals = *this->Internals;
  vtkOpenGLRenderWindow* renWin = target.Window;
  vtkOpenGLClearErrorMacro();
  vtkOpenGLState* ostate = renWin->GetState();
  vtkSavedGLState savedState(ostate);
  internals.Timer.Start();

  vtkHAVSKBuffer* kbuffer = internals.KBuffer;
  ostate->PushFramebufferBindings();
  kbuffer->CaptureSceneDepth(target.X, target.Y);
  kbuffer->Clear();
  // Both facings are drawn: a boundary face's facing tells an exit from an entry.
  ostate->vtkglDisable(GL_DEPTH_TEST);
  ostate->vtkglDisable(GL_CULL_FACE);
  ostate->vtkglDepthMask(GL_FALSE);
  vtkTextureObject* table = internals.Table->GetTexture(renWin);
  table->Activate();
  const bool drawn =
    internals.DrawFaces(table, target.Width, target.Height) && internals.DrawFlush(table);
  table->Deactivate();
  ostate->PopFramebufferBindings();
  if (drawn)
  {
    kbuffer->Resolve(target.X, target.Y);
  }
  this->LastGPUTime = internals.Timer.Stop();
  internals.AccessInUse = drawn ? access : -1;
  if (!drawn)
  {
    if (access == FRAGMENT_SHADER_INTERLOCK && this->KBufferSynchronization == AUTOMATIC)
    {
      internals.InterlockFailed = true; // the next render falls back to framebuffer fetch
    }
    vtkErrorMacro("Could not compile the HAVS k-buffer shaders (KBufferSize "
      << this->KBufferSize << ", synchronization " << access << ").");
  }
  vtkOpenGLCheckErrorMacro("failed after Render");
}

void vtkHAVSVolumeMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  vtkInternals& internals = *this->Internals;
  internals.Faces->ReleaseGraphicsResources(window);
  internals.Table->ReleaseGraphicsResources(window);
  internals.KBuffer->ReleaseGraphicsResources(window);
  internals.NearCap.ReleaseGraphicsResources();
  internals.Flush.reset();
  internals.FlushSource.clear();
  internals.Timer.Release(this->GetContext() != nullptr);
  internals.InterlockFailed = false;
  this->Superclass::ReleaseGraphicsResources(window);
}

void vtkHAVSVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "KBufferSize: " << this->KBufferSize << "\n";
  os << indent << "KBufferSynchronization: " << this->KBufferSynchronization << "\n";
  os << indent << "KBufferSynchronizationInUse: " << this->GetKBufferSynchronizationInUse() << "\n";
  os << indent << "NumberOfFaces: " << this->GetNumberOfFaces() << "\n";
  os << indent << "NumberOfBoundaryFaces: " << this->GetNumberOfBoundaryFaces() << "\n";
  os << indent << "GPUMemorySize: " << this->GetGPUMemorySize() << "\n";
  os << indent << "LastSortTime: " << this->LastSortTime << "\n";
  os << indent << "LastGPUTime: " << this->LastGPUTime << "\n";
}
