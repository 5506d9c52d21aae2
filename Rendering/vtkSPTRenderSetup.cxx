#include "vtkSPTRenderSetup.h"

#include "vtkAlgorithm.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPropCollection.h"
#include "vtkRenderer.h"
#include "vtkUnstructuredGridVolumeMapper.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtk_glew.h"

#include "vtkSPTMeshBuffers.h"
#include "vtkSPTViewMatrices.h"

#include <algorithm>
#include <cmath>

bool vtkSPTRenderSetup::GetTarget(
  vtkUnstructuredGridVolumeMapper* mapper, vtkRenderer* ren, Target& target)
{
  target.Window = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
  if (!target.Window)
  {
    vtkErrorWithObjectMacro(mapper, << mapper->GetClassName() << " needs an OpenGL render window.");
    return false;
  }
  ren->GetTiledSizeAndOrigin(&target.Width, &target.Height, &target.X, &target.Y);
  return target.Width > 0 && target.Height > 0;
}

bool vtkSPTRenderSetup::BeginFrame(vtkUnstructuredGridVolumeMapper* mapper, vtkRenderer* ren,
  Target& target, vtkOpenGLRenderWindow*& context)
{
  if (!GetTarget(mapper, ren, target))
  {
    return false;
  }
  if (context && context != target.Window)
  {
    mapper->ReleaseGraphicsResources(context);
  }
  context = target.Window;
  return true;
}

vtkSPTRenderSetup::SavedState::SavedState(vtkOpenGLState* state)
  : State(state)
  , Blend(state, GL_BLEND)
  , DepthTest(state, GL_DEPTH_TEST)
  , CullFace(state, GL_CULL_FACE)
  , ScissorTest(state, GL_SCISSOR_TEST)
  , DepthMask(state)
  , DepthFunction(state)
  , ColorMask(state)
  , ClearColor(state)
  , Viewport(state)
{
  // vtkOpenGLState has no scoped savers of these two.
  state->vtkglGetDoublev(GL_DEPTH_CLEAR_VALUE, &this->ClearDepth);
  state->vtkglGetFloatv(GL_POINT_SIZE, &this->PointSize);
}

vtkSPTRenderSetup::SavedState::~SavedState()
{
  this->State->vtkglClearDepth(this->ClearDepth);
  this->State->vtkglPointSize(this->PointSize);
}

bool vtkSPTRenderSetup::UpdateMesh(
  vtkUnstructuredGridVolumeMapper* mapper, vtkSPTMeshBuffers* mesh, int component, bool cellScalars)
{
  if (vtkAlgorithm* input = mapper->GetInputAlgorithm())
  {
    input->Update();
  }
  vtkSPTMeshBuffers::ScalarSelection selection;
  selection.ScalarMode = mapper->GetScalarMode();
  selection.ArrayAccessMode = mapper->GetArrayAccessMode();
  selection.ArrayId = mapper->GetArrayId();
  selection.ArrayName = mapper->GetArrayName() ? mapper->GetArrayName() : "";
  selection.Component = component;
  const bool built = mesh->Update(mapper->GetDataSetInput(), selection);
  const bool refused = built && !cellScalars && mesh->GetCellScalars();
  if (!built || refused)
  {
    if (mesh->GetBuildTime() != this->ReportedMeshError)
    {
      this->ReportedMeshError = mesh->GetBuildTime();
      if (!built)
      {
        vtkErrorWithObjectMacro(mapper, << mesh->GetLastError());
      }
      else
      {
        vtkErrorWithObjectMacro(
          mapper, << mapper->GetClassName()
                  << " renders point scalars only (its faces interpolate them); the selected array "
                     "is cell data. Convert it with vtkCellDataToPointData, or render it with "
                     "vtkSPTVolumeMapper or vtkPBVRVolumeMapper.");
      }
    }
    return false;
  }
  if (mesh->GetNumberOfSkippedCells() > 0 && mesh->GetBuildTime() != this->ReportedSkippedCells)
  {
    this->ReportedSkippedCells = mesh->GetBuildTime();
    vtkWarningWithObjectMacro(mapper,
      << mesh->GetNumberOfSkippedCells()
      << " cells with coordinates or scalars that are not finite (NaN or Inf) are not drawn.");
  }
  return mesh->GetNumberOfTetrahedra() > 0;
}

bool vtkSPTRenderSetup::CheckProperty(vtkUnstructuredGridVolumeMapper* mapper, vtkVolume* vol)
{
  vtkVolumeProperty* property = vol->GetProperty();
  if (!property->GetIndependentComponents())
  {
    vtkErrorWithObjectMacro(mapper,
      "Dependent components (scalars that are colors) are not supported; turn "
      "IndependentComponents on in the volume property.");
    return false;
  }
  return true;
}

bool vtkSPTRenderSetup::ComputeMatrices(vtkUnstructuredGridVolumeMapper* mapper, vtkRenderer* ren,
  vtkVolume* vol, const vtkSPTMeshBuffers* mesh, vtkSPTViewMatrices& matrices)
{
  matrices.Compute(ren, vol, mesh);
  const auto finite = [](const float* values, int count)
  { return std::all_of(values, values + count, [](float v) { return std::isfinite(v); }); };
  if (!finite(matrices.MCVC, 16) || !finite(matrices.VCDC, 16) || !finite(matrices.DCVC, 16) ||
    !finite(matrices.VCMCLinear, 9))
  {
    vtkErrorWithObjectMacro(mapper,
      "The camera or the volume's transform is not finite (NaN or Inf in its matrices); "
      "nothing is drawn. Check the camera and the data's bounds.");
    return false;
  }
  return true;
}

bool vtkSPTRenderSetup::HasOpaqueScene(vtkRenderer* ren)
{
  if (ren->GetPreserveDepthBuffer())
  {
    return true;
  }
  vtkPropCollection* props = ren->GetViewProps();
  vtkCollectionSimpleIterator it;
  props->InitTraversal(it);
  while (vtkProp* prop = props->GetNextProp(it))
  {
    if (prop->GetVisibility() && prop->IsA("vtkProp3D") && !prop->IsA("vtkVolume") &&
      prop->HasOpaqueGeometry())
    {
      return true;
    }
  }
  return false;
}
