#include "vtkSPTVolumeMapper.h"

#include "vtkCamera.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
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
#include "vtkSPTShaderUtilities.h"

#include "vtkSPTTetrahedraFS.h"
#include "vtkSPTTetrahedraGS.h"
#include "vtkSPTTetrahedraVS.h"

#include <algorithm>

class vtkSPTVolumeMapper::vtkInternals
{
public:
  vtkNew<vtkSPTMeshBuffers> Mesh;
  vtkNew<vtkSPTPreIntegrationTable> Table;
  vtkNew<vtkSPTEnsembleBuffer> Ensemble;
  vtkOpenGLRenderWindow* Context = nullptr;
  vtkMTimeType ReportedMeshError = 0;
  vtkMTimeType ReportedSkippedCells = 0;

  // Model (normalized) -> view (normalized), view -> clip and clip -> view, column-major;
  // and the linear part of view -> model, which turns view-space segments into lengths in
  // the normalized model units of the mesh.
  float MCVC[16];
  float VCDC[16];
  float DCVC[16];
  float VCMCLinear[9];

  void ComputeMatrices(vtkRenderer* ren, vtkVolume* vol);
  vtkShaderProgram* ReadyProgram(vtkOpenGLRenderWindow* renWin, bool cellScalars);
};

void vtkSPTVolumeMapper::vtkInternals::ComputeMatrices(vtkRenderer* ren, vtkVolume* vol)
{
  // Everything is composed in double and handed to the GPU in units of the mesh's own size
  // (view coordinates divided by viewScale), so that float precision holds whatever the
  // magnitude of the coordinates.
  vtkNew<vtkMatrix4x4> normalization;
  this->Mesh->GetNormalizationMatrix(normalization);
  vtkMatrix4x4* model = vol->GetMatrix();
  double linear[3][3], u[3][3], w[3], vt[3][3];
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      linear[i][j] = model->GetElement(i, j);
    }
  }
  vtkMath::SingularValueDecomposition3x3(linear, u, w, vt);
  const double modelScale = std::max({ std::abs(w[0]), std::abs(w[1]), std::abs(w[2]) });
  const double viewScale = this->Mesh->GetScale() * (modelScale > 0.0 ? modelScale : 1.0);

  vtkCamera* camera = ren->GetActiveCamera();
  vtkNew<vtkMatrix4x4> modelToView;
  vtkMatrix4x4::Multiply4x4(camera->GetModelViewTransformMatrix(), model, modelToView);
  vtkMatrix4x4::Multiply4x4(modelToView, normalization, modelToView);
  vtkNew<vtkMatrix4x4> viewToClip;
  viewToClip->DeepCopy(camera->GetProjectionTransformMatrix(ren->GetTiledAspectRatio(), -1, 1));
  // Normalized view coordinates are view coordinates / viewScale. The projection of a
  // normalized point is P diag(viewScale, viewScale, viewScale, 1), which is the same
  // projective map as P with its translation column divided by viewScale: clip coordinates
  // (and w) stay O(1) too.
  for (int i = 0; i < 4; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      modelToView->SetElement(j, i, modelToView->GetElement(j, i) / viewScale);
    }
    viewToClip->SetElement(i, 3, viewToClip->GetElement(i, 3) / viewScale);
  }
  vtkNew<vtkMatrix4x4> clipToView;
  vtkMatrix4x4::Invert(viewToClip, clipToView);
  vtkSPTShaderUtilities::ToColumnMajor(modelToView, this->MCVC);
  vtkSPTShaderUtilities::ToColumnMajor(viewToClip, this->VCDC);
  vtkSPTShaderUtilities::ToColumnMajor(clipToView, this->DCVC);
  double viewToModel[3][3];
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      linear[i][j] = modelToView->GetElement(i, j);
    }
  }
  vtkMath::Invert3x3(linear, viewToModel);
  for (int column = 0; column < 3; ++column)
  {
    for (int row = 0; row < 3; ++row)
    {
      this->VCMCLinear[3 * column + row] = static_cast<float>(viewToModel[row][column]);
    }
  }
}

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
  internals.ComputeMatrices(ren, vol);
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
      program->SetUniformMatrix4x4("MCVCMatrix", internals.MCVC);
      program->SetUniformMatrix4x4("VCDCMatrix", internals.VCDC);
      program->SetUniformMatrix4x4("DCVCMatrix", internals.DCVC);
      program->SetUniformMatrix3x3("VCMCLinear", internals.VCMCLinear);
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
