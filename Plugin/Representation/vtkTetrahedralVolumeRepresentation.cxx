#include "vtkTetrahedralVolumeRepresentation.h"

#include "vtkAbstractVolumeMapper.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataSetAttributes.h"
#include "vtkFloatArray.h"
#include "vtkInformation.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkPSPTVolumeMapper.h"
#include "vtkPVRenderView.h"
#include "vtkPoints.h"
#include "vtkTetrahedralVolumeMapper.h"
#include "vtkUnstructuredGrid.h"
#include "vtkVolumeProperty.h"

vtkStandardNewMacro(vtkTetrahedralVolumeRepresentation);

//------------------------------------------------------------------------------
vtkTetrahedralVolumeRepresentation::vtkTetrahedralVolumeRepresentation() = default;

//------------------------------------------------------------------------------
vtkTetrahedralVolumeRepresentation::~vtkTetrahedralVolumeRepresentation() = default;

//------------------------------------------------------------------------------
void vtkTetrahedralVolumeRepresentation::SetVolumeMapper(vtkAbstractVolumeMapper* mapper)
{
  if (this->VolumeMapper == mapper)
  {
    return;
  }
  this->VolumeMapper = mapper;
  // The superclass keeps its mappers by name and draws with the active one.
  if (mapper)
  {
    this->AddVolumeMapper(mapper->GetClassName(), mapper);
  }
  this->Superclass::SetActiveVolumeMapper(mapper ? mapper->GetClassName() : nullptr);
  this->Modified();
}

//------------------------------------------------------------------------------
vtkAbstractVolumeMapper* vtkTetrahedralVolumeRepresentation::GetVolumeMapper()
{
  return this->VolumeMapper;
}

//------------------------------------------------------------------------------
void vtkTetrahedralVolumeRepresentation::SetActiveVolumeMapper(const char*) {}

//------------------------------------------------------------------------------
vtkMultiProcessController* vtkTetrahedralVolumeRepresentation::ParallelController()
{
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  const bool parallel = vtkPSPTVolumeMapper::SafeDownCast(this->VolumeMapper) && controller &&
    controller->GetNumberOfProcesses() > 1;
  return parallel ? controller : nullptr;
}

//------------------------------------------------------------------------------
void vtkTetrahedralVolumeRepresentation::KeepPieceDrawn(
  vtkSPTVolumeMapper* mapper, vtkMultiProcessController* controller)
{
  // ParaView's volume does not call its mapper when the piece lacks the selected array, as an
  // empty piece may; every rank's mapper must take part in the reductions, so such a piece is
  // replaced by an empty grid that has the array (with an error if it had cells).
  vtkDataSet* input = mapper->GetDataSetInput();
  const char* name = mapper->GetArrayName();
  int cellFlag = 0;
  if (!input || !name || !name[0] ||
    vtkAbstractMapper::GetScalars(input, mapper->GetScalarMode(), mapper->GetArrayAccessMode(),
      mapper->GetArrayId(), name, cellFlag))
  {
    return;
  }
  if (input->GetNumberOfCells() > 0)
  {
    vtkErrorWithObjectMacro(mapper,
      "Rank " << controller->GetLocalProcessId() << "'s piece has no array '" << name
              << "'; it is not drawn.");
  }
  vtkNew<vtkFloatArray> scalars;
  scalars->SetName(name);
  vtkNew<vtkUnstructuredGrid> empty;
  empty->SetPoints(vtkNew<vtkPoints>());
  empty->Allocate(0);
  const bool cellScalars = mapper->GetScalarMode() == VTK_SCALAR_MODE_USE_CELL_FIELD_DATA;
  empty->GetAttributes(cellScalars ? vtkDataObject::CELL : vtkDataObject::POINT)->AddArray(scalars);
  mapper->SetInputDataObject(empty);
}

//------------------------------------------------------------------------------
int vtkTetrahedralVolumeRepresentation::ProcessViewRequest(
  vtkInformationRequestKey* request, vtkInformation* inInfo, vtkInformation* outInfo)
{
  if (!this->Superclass::ProcessViewRequest(request, inInfo, outInfo))
  {
    return 0;
  }
  vtkMultiProcessController* controller = this->ParallelController();
  if (request == vtkPVView::REQUEST_UPDATE() && controller)
  {
    // Each rank draws its own piece as it is: the data is left where it is, and the ranks'
    // images are not composited in visibility order.
    vtkPVRenderView::SetOrderedCompositingConfiguration(inInfo, this, 0);
    outInfo->Set(vtkPVRenderView::NEED_ORDERED_COMPOSITING(), 0);
  }
  else if (request == vtkPVView::REQUEST_RENDER())
  {
    // Only when every rank renders (distributed rendering); otherwise the data is delivered
    // to the rank that renders, which draws it alone.
    auto* view = vtkPVRenderView::SafeDownCast(inInfo->Get(vtkPVView::VIEW()));
    const bool lod =
      inInfo->Has(vtkPVRenderView::USE_LOD()) && inInfo->Get(vtkPVRenderView::USE_LOD()) != 0;
    const bool distributed = view &&
      (lod ? view->GetUseDistributedRenderingForLODRender()
           : view->GetUseDistributedRenderingForRender());
    if (auto* mapper = vtkPSPTVolumeMapper::SafeDownCast(this->VolumeMapper))
    {
      mapper->SetController(distributed ? controller : nullptr);
      if (distributed && controller)
      {
        KeepPieceDrawn(mapper, controller);
      }
    }
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkTetrahedralVolumeRepresentation::UpdateMapperParameters()
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
void vtkTetrahedralVolumeRepresentation::PrintSelf(ostream& os, vtkIndent indent)
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
