#include "vtkSITetrahedralVolumeRepresentationProxy.h"

#include "vtkAbstractVolumeMapper.h"
#include "vtkObjectFactory.h"
#include "vtkTetrahedralVolumeRepresentation.h"

vtkStandardNewMacro(vtkSITetrahedralVolumeRepresentationProxy);

//------------------------------------------------------------------------------
vtkSITetrahedralVolumeRepresentationProxy::vtkSITetrahedralVolumeRepresentationProxy() = default;

//------------------------------------------------------------------------------
vtkSITetrahedralVolumeRepresentationProxy::~vtkSITetrahedralVolumeRepresentationProxy() = default;

//------------------------------------------------------------------------------
bool vtkSITetrahedralVolumeRepresentationProxy::CreateVTKObjects()
{
  if (!this->Superclass::CreateVTKObjects())
  {
    return false;
  }

  auto* representation = vtkTetrahedralVolumeRepresentation::SafeDownCast(this->GetVTKObject());
  if (!representation)
  {
    vtkErrorMacro(
      "Proxy " << (this->GetXMLName() ? this->GetXMLName() : "(unnamed)")
               << ": its class must be vtkTetrahedralVolumeRepresentation, not "
               << (this->GetVTKObject() ? this->GetVTKObject()->GetClassName() : "(none)"));
    return false;
  }

  vtkSIProxy* mapperProxy = this->GetSubSIProxy("VolumeMapper");
  auto* mapper =
    mapperProxy ? vtkAbstractVolumeMapper::SafeDownCast(mapperProxy->GetVTKObject()) : nullptr;
  if (!mapper)
  {
    vtkErrorMacro("Proxy " << (this->GetXMLName() ? this->GetXMLName() : "(unnamed)")
                           << " needs a subproxy \"VolumeMapper\" whose class is a "
                              "vtkAbstractVolumeMapper.");
    return false;
  }
  representation->SetVolumeMapper(mapper);
  return true;
}

//------------------------------------------------------------------------------
void vtkSITetrahedralVolumeRepresentationProxy::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
