#include "vtkSPTFrameStatistics.h"

#include "vtkObjectFactory.h"

vtkStandardNewMacro(vtkSPTFrameStatistics);

void vtkSPTFrameStatistics::Reset()
{
  this->Record(Values());
}

void vtkSPTFrameStatistics::Record(const Values& values)
{
  this->Current = values;
  this->Modified();
}

void vtkSPTFrameStatistics::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RepetitionCount: " << this->Current.RepetitionCount << "\n";
  os << indent << "FewestRepetitionCount: " << this->Current.FewestRepetitionCount << "\n";
  os << indent << "EstimatedError: " << this->Current.EstimatedError << "\n";
  os << indent << "DepthSlabs: " << this->Current.DepthSlabs << "\n";
  os << indent << "PointCellCount: " << this->Current.PointCellCount << "\n";
  os << indent << "ComputedCellCount: " << this->Current.ComputedCellCount << "\n";
  os << indent << "ParallelBytes: " << this->Current.ParallelBytes << "\n";
}
