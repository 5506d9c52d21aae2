#include "vtkSPTVolumeRepresentation.h"

#include "vtkAbstractVolumeMapper.h"
#include "vtkColorTransferFunction.h"
#include "vtkObjectFactory.h"
#include "vtkTetrahedralVolumeMapper.h"
#include "vtkVolumeProperty.h"

vtkStandardNewMacro(vtkSPTVolumeRepresentation);

//------------------------------------------------------------------------------
vtkSPTVolumeRepresentation::vtkSPTVolumeRepresentation() = default;

//------------------------------------------------------------------------------
vtkSPTVolumeRepresentation::~vtkSPTVolumeRepresentation() = default;

//------------------------------------------------------------------------------
void vtkSPTVolumeRepresentation::SetVolumeMapper(vtkAbstractVolumeMapper* mapper)
{
  if (this->VolumeMapper == mapper)
  {
    return;
  }
  this->VolumeMapper = mapper;
  if (mapper)
  {
    // The superclass keeps its mappers by name and draws with the active one.
    this->AddVolumeMapper(mapper->GetClassName(), mapper);
    this->Superclass::SetActiveVolumeMapper(mapper->GetClassName());
  }
  else
  {
    this->Superclass::SetActiveVolumeMapper(nullptr);
  }
  this->Modified();
}

//------------------------------------------------------------------------------
vtkAbstractVolumeMapper* vtkSPTVolumeRepresentation::GetVolumeMapper()
{
  return this->VolumeMapper;
}

//------------------------------------------------------------------------------
void vtkSPTVolumeRepresentation::SetActiveVolumeMapper(const char*) {}

//------------------------------------------------------------------------------
void vtkSPTVolumeRepresentation::UpdateMapperParameters()
{
  this->Superclass::UpdateMapperParameters();

  // As ParaView does for its image volume mappers: the color map's vector mode chooses the
  // magnitude or one component of a multi-component array.
  auto* mapper = vtkTetrahedralVolumeMapper::SafeDownCast(this->VolumeMapper);
  if (!mapper)
  {
    return;
  }
  vtkColorTransferFunction* colors = this->Property->GetRGBTransferFunction(0);
  if (colors && colors->GetVectorMode() == vtkScalarsToColors::COMPONENT)
  {
    mapper->SetVectorModeToComponent();
    mapper->SetVectorComponent(colors->GetVectorComponent());
  }
  else
  {
    mapper->SetVectorModeToMagnitude();
  }
}

//------------------------------------------------------------------------------
void vtkSPTVolumeRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "VolumeMapper: ";
  if (this->VolumeMapper)
  {
    os << this->VolumeMapper->GetClassName() << " (" << this->VolumeMapper.Get() << ")\n";
  }
  else
  {
    os << "(none)\n";
  }
}
