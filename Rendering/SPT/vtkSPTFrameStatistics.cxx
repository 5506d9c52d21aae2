#include "vtkSPTFrameStatistics.h"

#include "vtkObjectFactory.h"

vtkStandardNewMacro(vtkSPTFrameStatistics);

void vtkSPTFrameStatistics::Reset()
{
  this->Record(Values());
}

void vtkSPTFrameStatistics::Record(const Values& values)
{
  this->RepetitionCount = values.RepetitionCount;
  this->EstimatedError = values.EstimatedError;
  this->DepthSlabs = values.DepthSlabs;
  this->PointCellCount = values.PointCellCount;
  this->ComputedCellCount = values.ComputedCellCount;
  this->ParallelBytes = values.ParallelBytes;
  this->Modified();
}

void vtkSPTFrameStatistics::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RepetitionCount: " << this->RepetitionCount << "\n";
  os << indent << "EstimatedError: " << this->EstimatedError << "\n";
  os << indent << "DepthSlabs: " << this->DepthSlabs << "\n";
  os << indent << "PointCellCount: " << this->PointCellCount << "\n";
  os << indent << "ComputedCellCount: " << this->ComputedCellCount << "\n";
  os << indent << "ParallelBytes: " << this->ParallelBytes << "\n";
}
