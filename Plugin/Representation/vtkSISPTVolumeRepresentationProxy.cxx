#include "vtkSISPTVolumeRepresentationProxy.h"

#include "vtkAbstractVolumeMapper.h"
#include "vtkObjectFactory.h"
#include "vtkSPTVolumeRepresentation.h"

vtkStandardNewMacro(vtkSISPTVolumeRepresentationProxy);

//------------------------------------------------------------------------------
vtkSISPTVolumeRepresentationProxy::vtkSISPTVolumeRepresentationProxy() = default;

//------------------------------------------------------------------------------
vtkSISPTVolumeRepresentationProxy::~vtkSISPTVolumeRepresentationProxy() = default;

//------------------------------------------------------------------------------
bool vtkSISPTVolumeRepresentationProxy::CreateVTKObjects()
{
  if (!this->Superclass::CreateVTKObjects())
  {
    return false;
  }

  auto* representation = vtkSPTVolumeRepresentation::SafeDownCast(this->GetVTKObject());
  if (!representation)
  {
    vtkErrorMacro(
      "Proxy " << (this->GetXMLName() ? this->GetXMLName() : "(unnamed)")
               << ": its class must be vtkSPTVolumeRepresentation, not "
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
void vtkSISPTVolumeRepresentationProxy::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
