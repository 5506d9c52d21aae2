#include "vtkTetrahedralVolumeMapper.h"

#include "vtkAlgorithm.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPlaneCollection.h"
#include "vtkPropCollection.h"
#include "vtkRenderer.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include "vtkOpenGLLoader.h"
#include "vtkTetrahedralMesh.h"
#include "vtkVolumeViewMatrices.h"

#include <algorithm>
#include <cmath>
#include <string>

vtkTetrahedralVolumeMapper::vtkTetrahedralVolumeMapper() = default;

vtkTetrahedralVolumeMapper::~vtkTetrahedralVolumeMapper() = default;

vtkIdType vtkTetrahedralVolumeMapper::GetNumberOfTetrahedra()
{
  return this->Mesh->GetNumberOfTetrahedra();
}

vtkIdType vtkTetrahedralVolumeMapper::GetNumberOfSkippedCells()
{
  return this->Mesh->GetNumberOfSkippedCells();
}

void vtkTetrahedralVolumeMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Context = nullptr;
  this->Superclass::ReleaseGraphicsResources(window);
}

bool vtkTetrahedralVolumeMapper::BeginFrame(vtkRenderer* ren, RenderTarget& target)
{
  target.Window = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
  if (!target.Window)
  {
    vtkErrorMacro(<< this->GetClassName() << " needs an OpenGL render window.");
    return false;
  }
  ren->GetTiledSizeAndOrigin(&target.Width, &target.Height, &target.X, &target.Y);
  if (target.Width <= 0 || target.Height <= 0)
  {
    return false;
  }
  if (this->Context && this->Context != target.Window)
  {
    // Releasing makes the other window's context current (vtkTextureObject does): this
    // frame's context is made current again by CheckContext(), before anything is created.
    this->ReleaseGraphicsResources(this->Context);
  }
  this->Context = target.Window;
  return this->CheckContext(target.Window);
}

bool vtkTetrahedralVolumeMapper::CheckContext(vtkOpenGLRenderWindow* window)
{
  // The mappers' shaders are GLSL 1.50 with geometry shaders: OpenGL 3.2 core, which is also
  // VTK's minimum (VTK 9.2 itself accepts 3.1). A context VTK could not initialize reports 0.0.
  window->MakeCurrent();
  int major = 0, minor = 0;
  vtkOpenGLLoader::GetVersion(major, minor);
  if (major > 3 || (major == 3 && minor >= 2))
  {
    return true;
  }
  if (window->GetContextCreationTime() != this->ReportedContextError)
  {
    this->ReportedContextError = window->GetContextCreationTime();
    const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    vtkErrorMacro(
      << this->GetClassName() << " needs OpenGL 3.2 or later (core profile, "
      << "geometry shaders); this context is "
      << (major > 0 ? "OpenGL " + std::to_string(major) + "." + std::to_string(minor)
                    : std::string("not a usable OpenGL context"))
      << " (" << (renderer ? renderer : "no renderer") << ", " << window->GetClassName()
      << "). Update the graphics driver, or use Mesa's llvmpipe (Debian: "
         "libgl1-mesa-dri; OpenGL 4.5); without X, render in vtkHeadlessEGLRenderWindow. "
         "Nothing is drawn.");
  }
  return false;
}

bool vtkTetrahedralVolumeMapper::PrepareMesh(vtkVolume* vol, bool cellScalars)
{
  if (vtkAlgorithm* input = this->GetInputAlgorithm())
  {
    input->Update();
  }
  vtkTetrahedralMesh::ScalarSelection selection;
  selection.ScalarMode = this->GetScalarMode();
  selection.ArrayAccessMode = this->GetArrayAccessMode();
  selection.ArrayId = this->GetArrayId();
  selection.ArrayName = this->GetArrayName() ? this->GetArrayName() : "";
  selection.Component = this->VectorMode == COMPONENT ? this->VectorComponent : -1;
  vtkTetrahedralMesh* mesh = this->Mesh;
  const bool built = mesh->Update(this->GetDataSetInput(), selection);
  const bool refused = built && !cellScalars && mesh->GetCellScalars();
  if (!built || refused)
  {
    if (mesh->GetBuildTime() != this->ReportedMeshError)
    {
      this->ReportedMeshError = mesh->GetBuildTime();
      if (!built)
      {
        vtkErrorMacro(<< mesh->GetLastError());
      }
      else
      {
        vtkErrorMacro(<< this->GetClassName()
                      << " renders point scalars only (its faces interpolate them); the selected "
                         "array is cell data. Convert it with vtkCellDataToPointData, or render "
                         "it with vtkSPTVolumeMapper or vtkPBVRVolumeMapper.");
      }
    }
    return false;
  }
  if (mesh->GetNumberOfSkippedCells() > 0 && mesh->GetBuildTime() != this->ReportedSkippedCells)
  {
    this->ReportedSkippedCells = mesh->GetBuildTime();
    vtkWarningMacro(<< mesh->GetNumberOfSkippedCells()
                    << " cells with coordinates or scalars that are not finite (NaN or Inf) are "
                       "not drawn.");
  }
  if (mesh->GetNumberOfTetrahedra() == 0)
  {
    return false;
  }
  if (!vol->GetProperty()->GetIndependentComponents())
  {
    vtkErrorMacro("Dependent components (scalars that are colors) are not supported; turn "
                  "IndependentComponents on in the volume property.");
    return false;
  }
  return true;
}

bool vtkTetrahedralVolumeMapper::ComputeMatrices(
  vtkRenderer* ren, vtkVolume* vol, vtkVolumeViewMatrices& matrices)
{
  matrices.Compute(ren, vol, this->Mesh);
  const auto finite = [](const float* values, int count)
  { return std::all_of(values, values + count, [](float v) { return std::isfinite(v); }); };
  if (!finite(matrices.MCVC, 16) || !finite(matrices.VCDC, 16) || !finite(matrices.DCVC, 16) ||
    !finite(matrices.VCMCLinear, 9))
  {
    vtkErrorMacro("The camera or the volume's transform is not finite (NaN or Inf in its "
                  "matrices); nothing is drawn. Check the camera and the data's bounds.");
    return false;
  }
  if (!matrices.ComputeClippingPlanes(ren, this->ClippingPlanes))
  {
    vtkErrorMacro(<< this->ClippingPlanes->GetNumberOfItems() << " clipping planes: at most "
                  << vtkVolumeViewMatrices::MaximumClippingPlanes
                  << " are supported; nothing is drawn. Remove some (RemoveClippingPlane()).");
    return false;
  }
  if (!finite(matrices.ClippingPlanes[0], 4 * matrices.ClippingPlaneCount))
  {
    vtkErrorMacro("A clipping plane is not finite (NaN or Inf in its origin or normal); "
                  "nothing is drawn.");
    return false;
  }
  return true;
}

bool vtkTetrahedralVolumeMapper::HasOpaqueScene(vtkRenderer* ren)
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

void vtkTetrahedralVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PreIntegrationScalarResolution: " << this->PreIntegrationScalarResolution
     << "\n";
  os << indent << "PreIntegrationThicknessResolution: " << this->PreIntegrationThicknessResolution
     << "\n";
  os << indent << "VectorMode: " << (this->VectorMode == MAGNITUDE ? "Magnitude" : "Component")
     << "\n";
  os << indent << "VectorComponent: " << this->VectorComponent << "\n";
  os << indent << "NumberOfTetrahedra: " << this->Mesh->GetNumberOfTetrahedra() << "\n";
  os << indent << "NumberOfSkippedCells: " << this->Mesh->GetNumberOfSkippedCells() << "\n";
}
