#include "vtkStochasticVolumeMapper.h"

#include "vtkEnsembleBuffer.h"

vtkStochasticVolumeMapper::vtkStochasticVolumeMapper()
  : Ensemble(vtkSmartPointer<vtkEnsembleBuffer>::New())
{
}

vtkStochasticVolumeMapper::~vtkStochasticVolumeMapper() = default;

vtkEnsembleBuffer* vtkStochasticVolumeMapper::GetEnsemble() const
{
  return this->Ensemble;
}

void vtkStochasticVolumeMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Ensemble->ReleaseGraphicsResources(window);
  this->Superclass::ReleaseGraphicsResources(window);
}

void vtkStochasticVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RepetitionLevel: " << this->RepetitionLevel << "\n";
  os << indent << "SubpixelLevel: " << this->SubpixelLevel << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
}
