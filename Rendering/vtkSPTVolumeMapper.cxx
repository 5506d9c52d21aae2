#include "vtkSPTVolumeMapper.h"

#include "vtkObjectFactory.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtk_glew.h"

#include "vtkSPTEnsembleBuffer.h"
#include "vtkSPTMeshBuffers.h"
#include "vtkSPTPreIntegrationTable.h"
#include "vtkSPTViewTransforms.h"

#include "vtkSPTTetrahedraFS.h"
#include "vtkSPTTetrahedraGS.h"
#include "vtkSPTTetrahedraVS.h"

#include <string>

class vtkSPTVolumeMapper::vtkInternals
{
public:
  vtkNew<vtkSPTMeshBuffers> Mesh;
  vtkNew<vtkSPTPreIntegrationTable> Table;
  vtkNew<vtkSPTEnsembleBuffer> Ensemble;
  vtkOpenGLRenderWindow* Context = nullptr;
  vtkMTimeType ReportedMeshError = 0;
  vtkMTimeType ReportedSkippedCells = 0;
  vtkSPTViewTransforms Transforms;

  vtkShaderProgram* ReadyProgram(vtkOpenGLRenderWindow* renWin, bool cellScalars);
};

vtkShaderProgram* vtkSPTVolumeMapper::vtkInternals::ReadyProgram(
  vtkOpenGLRenderWindow* renWin, bool cellScalars)
{
  std::string geometry = vtkSPTTetrahedraGS;
  vtkShaderProgram::Substitute(
    geometry, "//SPT::Defines::Dec", cellScalars ? "#define SPT_CELL_SCALARS" : "");
  return renWin->GetShaderCache()->ReadyShaderProgram(
    vtkSPTTetrahedraVS, vtkSPTTetrahedraFS, geometry.c_str());
}

vtkStandardNewMacro(vtkSPTVolumeMapper);

vtkSPTVolumeMapper::vtkSPTVolumeMapper()
  : Internals(new vtkInternals)
{
}

vtkSPTVolumeMapper::~vtkSPTVolumeMapper() = default;

vtkIdType vtkSPTVolumeMapper::GetNumberOfTetrahedra()
{
  return this->Internals->Mesh->GetNumberOfTetrahedra();
}

vtkIdType vtkSPTVolumeMapper::GetNumberOfSkippedCells()
{
  return this->Internals->Mesh->GetNumberOfSkippedCells();
}

vtkIdType vtkSPTVolumeMapper::GetGPUMemorySize()
{
  const vtkInternals& internals = *this->Internals;
  return static_cast<vtkIdType>(internals.Mesh->GetGPUMemorySize() +
    internals.Table->GetGPUMemorySize() + internals.Ensemble->GetGPUMemorySize());
}

void vtkSPTVolumeMapper::Render(vtkRenderer* ren, vtkVolume* vol)
{
  vtkInternals& internals = *this->Internals;
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
  if (!renWin)
  {
    vtkErrorMacro("vtkSPTVolumeMapper needs an OpenGL render window.");
    return;
  }
  int width, height, x, y;
  ren->GetTiledSizeAndOrigin(&width, &height, &x, &y);
  if (width <= 0 || height <= 0)
  {
    return;
  }
  if (internals.Context && internals.Context != renWin)
  {
    this->ReleaseGraphicsResources(internals.Context);
  }
  internals.Context = renWin;

  // Input and transfer functions: rebuilt only when they changed.
  if (this->GetInputAlgorithm())
  {
    this->GetInputAlgorithm()->Update();
  }
  vtkSPTMeshBuffers::ScalarSelection selection;
  selection.ScalarMode = this->ScalarMode;
  selection.ArrayAccessMode = this->ArrayAccessMode;
  selection.ArrayId = this->ArrayId;
  selection.ArrayName = this->ArrayName ? this->ArrayName : "";
  selection.Component = this->VectorMode == COMPONENT ? this->VectorComponent : -1;
  if (!internals.Mesh->Update(this->GetDataSetInput(), selection))
  {
    if (internals.Mesh->GetBuildTime() != internals.ReportedMeshError)
    {
      internals.ReportedMeshError = internals.Mesh->GetBuildTime();
      vtkErrorMacro(<< internals.Mesh->GetLastError());
    }
    return;
  }
  if (internals.Mesh->GetNumberOfTetrahedra() == 0)
  {
    return;
  }
  vtkVolumeProperty* property = vol->GetProperty();
  if (!property->GetIndependentComponents())
  {
    vtkErrorMacro("Dependent components (scalars that are colors) are not supported; turn "
                  "IndependentComponents on in the volume property.");
    return;
  }
  if (internals.Mesh->GetNumberOfSkippedCells() > 0 &&
    internals.Mesh->GetBuildTime() != internals.ReportedSkippedCells)
  {
    internals.ReportedSkippedCells = internals.Mesh->GetBuildTime();
    vtkWarningMacro(<< internals.Mesh->GetNumberOfSkippedCells()
                    << " cells with coordinates or scalars that are not finite (NaN or Inf) "
                       "are not drawn.");
  }
  internals.Transforms.Compute(ren, vol, internals.Mesh);
  const double maxThickness = internals.Mesh->GetMaxEdgeLength();
  if (!internals.Table->Update(property, internals.Mesh->GetScalarRange(),
        maxThickness * internals.Mesh->GetScale(), this->PreIntegrationScalarResolution,
        this->PreIntegrationThicknessResolution))
  {
    vtkErrorMacro(<< internals.Table->GetLastError());
    return;
  }
  if (!internals.Mesh->Upload(renWin))
  {
    return;
  }
  vtkTextureObject* table = internals.Table->GetTexture(renWin);
  if (!table)
  {
    return;
  }

  vtkOpenGLClearErrorMacro();
  vtkOpenGLState* ostate = renWin->GetState();
  vtkOpenGLState::ScopedglEnableDisable blend(ostate, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable depthTest(ostate, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable cullFace(ostate, GL_CULL_FACE);
  vtkOpenGLState::ScopedglEnableDisable scissorTest(ostate, GL_SCISSOR_TEST);
  vtkOpenGLState::ScopedglDepthMask depthMask(ostate);
  vtkOpenGLState::ScopedglDepthFunc depthFunction(ostate);
  vtkOpenGLState::ScopedglColorMask colorMask(ostate);
  vtkOpenGLState::ScopedglClearColor clearColor(ostate);
  vtkOpenGLState::ScopedglViewport viewport(ostate);

  vtkSPTEnsembleBuffer* ensemble = internals.Ensemble;
  if (!ensemble->Prepare(renWin, width, height, this->SubpixelLevel))
  {
    return;
  }
  ostate->PushFramebufferBindings();
  ensemble->CaptureSceneDepth(x, y);
  ensemble->ClearSum();

  const bool cellScalars = internals.Mesh->GetCellScalars();
  vtkShaderProgram* program = internals.ReadyProgram(renWin, cellScalars);
  if (!program)
  {
    ostate->PopFramebufferBindings();
    vtkErrorMacro("Could not compile the SPT shaders.");
    return;
  }
  table->Activate();
  vtkTextureObject* sceneDepth = ensemble->GetSceneDepthTexture();
  sceneDepth->Activate();
  vtkTextureObject* cellScalarTexture = internals.Mesh->GetCellScalarTexture();
  if (cellScalars)
  {
    cellScalarTexture->Activate();
  }

  const int scalarSamples = internals.Table->GetScalarResolution();
  const int thicknessSamples = internals.Table->GetLengthResolution();
  const float texelScale[3] = { float(scalarSamples - 1) / scalarSamples,
    float(scalarSamples - 1) / scalarSamples, float(thicknessSamples - 1) / thicknessSamples };
  const float texelOffset[3] = { 0.5f / scalarSamples, 0.5f / scalarSamples,
    0.5f / thicknessSamples };
  const float passSize[2] = { float(ensemble->GetPassWidth()), float(ensemble->GetPassHeight()) };

  ostate->vtkglDisable(GL_BLEND);
  ostate->vtkglDisable(GL_CULL_FACE);
  ostate->vtkglDisable(GL_SCISSOR_TEST);
  ostate->vtkglEnable(GL_DEPTH_TEST);
  ostate->vtkglDepthFunc(GL_LESS);
  for (int repetition = 0; repetition < this->RepetitionLevel; ++repetition)
  {
    ensemble->BeginPass();
    // The ensemble's accumulation binds its own program between passes.
    renWin->GetShaderCache()->ReadyShaderProgram(program);
    if (repetition == 0)
    {
      program->SetUniformMatrix4x4("MCVCMatrix", internals.Transforms.MCVC);
      program->SetUniformMatrix4x4("VCDCMatrix", internals.Transforms.VCDC);
      program->SetUniformMatrix4x4("DCVCMatrix", internals.Transforms.DCVC);
      program->SetUniformMatrix3x3("VCMCLinear", internals.Transforms.VCMCLinear);
      program->SetUniformi("preIntegrationTable", table->GetTextureUnit());
      program->SetUniform3f("tableTexelScale", texelScale);
      program->SetUniform3f("tableTexelOffset", texelOffset);
      program->SetUniformf(
        "thicknessToTable", maxThickness > 0.0 ? float(1.0 / maxThickness) : 0.0f);
      program->SetUniformi("sceneDepthTexture", sceneDepth->GetTextureUnit());
      program->SetUniformi("subpixelLevel", this->SubpixelLevel);
      program->SetUniform2f("passSizeInPixels", passSize);
      program->SetUniformi("seed", static_cast<int>(this->Seed));
      if (cellScalars)
      {
        program->SetUniformi("cellScalars", cellScalarTexture->GetTextureUnit());
      }
    }
    program->SetUniformi("repetition", repetition);
    internals.Mesh->Bind(program);
    internals.Mesh->Draw(program, 0, internals.Mesh->GetNumberOfTetrahedra());
    internals.Mesh->Unbind();
    ensemble->EndPass();
  }

  if (cellScalars)
  {
    cellScalarTexture->Deactivate();
  }
  sceneDepth->Deactivate();
  table->Deactivate();
  ostate->PopFramebufferBindings();
  ensemble->Resolve(x, y, this->RepetitionLevel);
  vtkOpenGLCheckErrorMacro("failed after Render");
}

void vtkSPTVolumeMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  vtkInternals& internals = *this->Internals;
  internals.Mesh->ReleaseGraphicsResources(window);
  internals.Table->ReleaseGraphicsResources(window);
  internals.Ensemble->ReleaseGraphicsResources(window);
  internals.Context = nullptr;
  this->Superclass::ReleaseGraphicsResources(window);
}

void vtkSPTVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RepetitionLevel: " << this->RepetitionLevel << "\n";
  os << indent << "SubpixelLevel: " << this->SubpixelLevel << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "PreIntegrationScalarResolution: " << this->PreIntegrationScalarResolution
     << "\n";
  os << indent << "PreIntegrationThicknessResolution: "
     << this->PreIntegrationThicknessResolution << "\n";
  os << indent << "VectorMode: " << (this->VectorMode == MAGNITUDE ? "Magnitude" : "Component")
     << "\n";
  os << indent << "VectorComponent: " << this->VectorComponent << "\n";
  os << indent << "NumberOfTetrahedra: " << this->GetNumberOfTetrahedra() << "\n";
  os << indent << "NumberOfSkippedCells: " << this->GetNumberOfSkippedCells() << "\n";
  os << indent << "GPUMemorySize: " << this->GetGPUMemorySize() << "\n";
}
