/**
 * @class   vtkTransferFunctionSamples
 * @brief   a volume property's transfer functions sampled over a scalar range, cached
 *
 * The optical model of every mapper of the module, in samples: the first component's color
 * (RGB, clamped to [0, 1]) and attenuation (opacity / unit distance, per data unit) at evenly
 * spaced scalars over the range. The pre-integration table integrates them; PBVR turns the
 * attenuation into particle densities and looks the colors up. Update() samples again only
 * when the property, the range or the number of samples changed, and the times of the colors
 * and of the attenuation move only when their values do: a property can be touched without a
 * change of its functions (VTK creates default functions on first access).
 *
 * Private helper of the module's mappers; not wrapped.
 */

#ifndef vtkTransferFunctionSamples_h
#define vtkTransferFunctionSamples_h

#include "SPTRenderingCoreModule.h" // For export macro
#include "vtkTimeStamp.h"           // For the caches

#include <string> // For the error
#include <vector> // For the samples

class vtkVolumeProperty;

class SPTRENDERINGCORE_EXPORT vtkTransferFunctionSamples
{
public:
  vtkTransferFunctionSamples() = default;
  vtkTransferFunctionSamples(const vtkTransferFunctionSamples&) = delete;
  vtkTransferFunctionSamples& operator=(const vtkTransferFunctionSamples&) = delete;

  /**
   * Sample the property's functions at `samples` scalars from scalarRange[0] to
   * scalarRange[1], unless these are what was sampled last. False, with the reason in
   * GetLastError(), when the unit distance is not a positive, finite distance.
   */
  bool Update(vtkVolumeProperty* property, const double scalarRange[2], int samples);
  const std::string& GetLastError() const { return this->LastError; }

  ///@{
  /// The samples: RGB triples, and the attenuation per data unit.
  const std::vector<double>& GetColor() const { return this->Color; }
  const std::vector<double>& GetAttenuation() const { return this->Attenuation; }
  int GetNumberOfSamples() const { return static_cast<int>(this->Attenuation.size()); }
  ///@}

  ///@{
  /// When the values of the colors, and of the attenuation, last changed.
  vtkMTimeType GetColorTime() const { return this->ColorTime.GetMTime(); }
  vtkMTimeType GetAttenuationTime() const { return this->AttenuationTime.GetMTime(); }
  ///@}

private:
  std::vector<double> Color;
  std::vector<double> Attenuation;
  std::string LastError;
  vtkVolumeProperty* SampledProperty = nullptr; // identity only, never dereferenced
  double SampledRange[2] = { 0.0, 0.0 };
  vtkTimeStamp SampleTime;
  vtkTimeStamp ColorTime;
  vtkTimeStamp AttenuationTime;
};

#endif
