#include "vtkTransferFunctionSamples.h"

#include "vtkColorTransferFunction.h"
#include "vtkPiecewiseFunction.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace
{
// The first component's color (clamped to [0, 1]) and attenuation (opacity / unit distance) at
// `samples` scalars over the range; what is not finite becomes 0.
void Sample(vtkVolumeProperty* property, const double scalarRange[2], int samples,
  double unitDistance, std::vector<double>& color, std::vector<double>& attenuation)
{
  const int n = samples;
  std::vector<double> opacity(n);
  property->GetScalarOpacity(0)->GetTable(scalarRange[0], scalarRange[1], n, opacity.data());
  color.assign(3 * n, 0.0);
  if (property->GetColorChannels(0) == 1)
  {
    std::vector<double> gray(n);
    property->GetGrayTransferFunction(0)->GetTable(scalarRange[0], scalarRange[1], n, gray.data());
    for (int i = 0; i < n; ++i)
    {
      std::fill_n(&color[3 * i], 3, gray[i]);
    }
  }
  else
  {
    property->GetRGBTransferFunction(0)->GetTable(scalarRange[0], scalarRange[1], n, color.data());
  }
  attenuation.assign(n, 0.0);
  for (int i = 0; i < n; ++i)
  {
    const double o = std::isfinite(opacity[i]) ? std::max(opacity[i], 0.0) : 0.0;
    attenuation[i] = o / unitDistance;
    for (int c = 0; c < 3; ++c)
    {
      double& value = color[3 * i + c];
      value = std::isfinite(value) ? std::min(std::max(value, 0.0), 1.0) : 0.0;
    }
  }
}
}

bool vtkTransferFunctionSamples::Update(
  vtkVolumeProperty* property, const double scalarRange[2], int samples)
{
  if (property == this->SampledProperty && this->SampleTime > property->GetMTime() &&
    scalarRange[0] == this->SampledRange[0] && scalarRange[1] == this->SampledRange[1] &&
    samples == this->GetNumberOfSamples())
  {
    return true;
  }
  this->SampledProperty = nullptr;
  this->LastError.clear();
  const double unitDistance = property->GetScalarOpacityUnitDistance(0);
  if (!(unitDistance > 0.0) || !std::isfinite(unitDistance))
  {
    std::ostringstream reason;
    reason << "ScalarOpacityUnitDistance of the volume property is " << unitDistance
           << "; it must be a positive, finite distance.";
    this->LastError = reason.str();
    return false;
  }
  std::vector<double> color;
  std::vector<double> attenuation;
  Sample(property, scalarRange, samples, unitDistance, color, attenuation);
  if (color != this->Color)
  {
    this->Color.swap(color);
    this->ColorTime.Modified();
  }
  if (attenuation != this->Attenuation)
  {
    this->Attenuation.swap(attenuation);
    this->AttenuationTime.Modified();
  }
  this->SampledProperty = property;
  this->SampledRange[0] = scalarRange[0];
  this->SampledRange[1] = scalarRange[1];
  this->SampleTime.Modified();
  return true;
}
