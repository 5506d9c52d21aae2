// Unit test of the pre-integration table: every checked entry must match an independent,
// fine numerical integration of the same transfer functions, and VTK's own exact
// piecewise-linear integrator (the reference renderer's), on the same segment.

#include "vtkPreIntegrationTable.h"

#include "vtkColorTransferFunction.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkUnstructuredGridLinearRayIntegrator.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <random>

namespace
{
// Front-to-back emission-absorption along a segment whose scalar varies linearly, with the
// model of vtkUnstructuredGridLinearRayIntegrator (tau = opacity / unit distance, emission
// C tau), by the midpoint rule with many steps.
void FineIntegral(
  vtkVolumeProperty* property, double front, double back, double length, double rgba[4])
{
  const int steps = 20000;
  const double unit = property->GetScalarOpacityUnitDistance();
  double transmittance = 1.0;
  rgba[0] = rgba[1] = rgba[2] = 0.0;
  for (int i = 0; i < steps; ++i)
  {
    const double s = front + (back - front) * (i + 0.5) / steps;
    const double tau = property->GetScalarOpacity()->GetValue(s) / unit;
    double color[3];
    property->GetRGBTransferFunction()->GetColor(s, color);
    const double alpha = 1.0 - std::exp(-tau * length / steps);
    for (int c = 0; c < 3; ++c)
    {
      rgba[c] += transmittance * alpha * color[c];
    }
    transmittance *= 1.0 - alpha;
  }
  rgba[3] = 1.0 - transmittance;
}

void VTKLinearIntegral(vtkVolumeProperty* property, const double range[2], double front,
  double back, double length, double rgba[4])
{
  vtkNew<vtkVolume> volume;
  volume->SetProperty(property);
  vtkNew<vtkFloatArray> scalars;
  scalars->InsertNextValue(static_cast<float>(range[0]));
  scalars->InsertNextValue(static_cast<float>(range[1]));
  vtkNew<vtkUnstructuredGridLinearRayIntegrator> integrator;
  integrator->Initialize(volume, scalars);
  vtkNew<vtkDoubleArray> lengths, nearScalars, farScalars;
  lengths->InsertNextValue(length);
  nearScalars->InsertNextValue(front);
  farScalars->InsertNextValue(back);
  float color[4] = { 0.0f, 0.0f, 0.0f, 0.0f };
  integrator->Integrate(lengths, nearScalars, farScalars, color);
  for (int c = 0; c < 4; ++c)
  {
    rgba[c] = color[c];
  }
}

bool Near(const float* table, const double* expected, double tolerance, const char* what, int i,
  int j, int k)
{
  for (int c = 0; c < 4; ++c)
  {
    if (!(std::abs(table[c] - expected[c]) <= tolerance))
    {
      std::cerr << "Entry (" << i << ", " << j << ", " << k << ") channel " << c << ": table "
                << table[c] << ", " << what << " " << expected[c] << " (tolerance " << tolerance
                << ")\n";
      return false;
    }
  }
  return true;
}
}

int TestPreIntegrationTable(int, char*[])
{
  // VTK 9.2's vtkUnstructuredGridLinearRayIntegrator splits segments only at the color
  // function's control points (its loop over the opacity points stops after the first), so the
  // color function here has a point wherever the opacity has one.
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(0.0, 0.1, 0.2, 0.9);
  color->AddRGBPoint(2.0, 0.3, 0.1, 0.6);
  color->AddRGBPoint(3.0, 0.2, 0.9, 0.3);
  color->AddRGBPoint(5.0, 0.6, 0.85, 0.2);
  color->AddRGBPoint(5.5, 0.7, 0.8, 0.3);
  color->AddRGBPoint(7.0, 1.0, 0.8, 0.1);
  color->AddRGBPoint(10.0, 0.9, 0.1, 0.1);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.0);
  opacity->AddPoint(2.0, 0.05);
  opacity->AddPoint(5.0, 0.8);
  opacity->AddPoint(5.5, 0.1);
  opacity->AddPoint(10.0, 0.6);
  vtkNew<vtkVolumeProperty> property;
  property->SetColor(color);
  property->SetScalarOpacity(opacity);
  property->SetScalarOpacityUnitDistance(0.7);

  const double range[2] = { 0.0, 10.0 };
  const double maxLength = 3.0;
  const int scalarResolution = 81; // scalar samples at multiples of 1/8: on the control points
  const int lengthResolution = 17;
  vtkNew<vtkPreIntegrationTable> table;
  if (!table->Update(property, range, maxLength, scalarResolution, lengthResolution))
  {
    std::cerr << "Update failed on a valid property.\n";
    return EXIT_FAILURE;
  }
  const std::vector<float>& values = table->GetTable();
  auto entry = [&](int i, int j, int k)
  { return &values[4 * (i + scalarResolution * (j + size_t(scalarResolution) * k))]; };
  if (values.size() != size_t(4) * scalarResolution * scalarResolution * lengthResolution)
  {
    std::cerr << "Table has " << values.size() << " values.\n";
    return EXIT_FAILURE;
  }

  // Random entries against both integrals, plus the corners and the diagonal.
  std::mt19937 random(2009);
  std::uniform_int_distribution<int> scalarIndex(0, scalarResolution - 1);
  std::uniform_int_distribution<int> lengthIndex(0, lengthResolution - 1);
  int failures = 0;
  double worstFine = 0.0, worstVTK = 0.0;
  for (int n = 0; n < 300; ++n)
  {
    const int i = n < 4 ? (n % 2) * (scalarResolution - 1) : scalarIndex(random);
    const int j = n < 4 ? (n / 2) * (scalarResolution - 1) : (n % 7 == 0 ? i : scalarIndex(random));
    const int k = n < 4 ? lengthResolution - 1 : lengthIndex(random);
    const double front = table->GetScalar(i);
    const double back = table->GetScalar(j);
    const double length = table->GetLength(k);
    double fine[4], vtk[4];
    FineIntegral(property, front, back, length, fine);
    VTKLinearIntegral(property, range, front, back, length, vtk);
    const float* value = entry(i, j, k);
    for (int c = 0; c < 4; ++c)
    {
      worstFine = std::max(worstFine, std::abs(value[c] - fine[c]));
      worstVTK = std::max(worstVTK, std::abs(value[c] - vtk[c]));
    }
    // The table's quadrature (two steps per table cell) against 20000 steps, and against VTK's
    // closed form, which evaluates erf and Dawson's integral in single precision.
    failures += !Near(value, fine, 2.0e-3, "fine integral", i, j, k);
    failures += !Near(value, vtk, 2.0e-3, "VTK linear integrator", i, j, k);
  }
  std::cout << "Largest difference: " << worstFine << " (fine integral), " << worstVTK
            << " (VTK linear integrator)\n";

  // Homogeneous segments have a closed form: alpha = 1 - exp(-tau d), color = C alpha.
  for (int i = 0; i < scalarResolution; i += 5)
  {
    for (int k = 0; k < lengthResolution; k += 4)
    {
      const double s = table->GetScalar(i);
      const double alpha = 1.0 - std::exp(-opacity->GetValue(s) / 0.7 * table->GetLength(k));
      double rgb[3];
      color->GetColor(s, rgb);
      const double exact[4] = { rgb[0] * alpha, rgb[1] * alpha, rgb[2] * alpha, alpha };
      failures += !Near(entry(i, i, k), exact, 2.0e-6, "closed form", i, i, k);
    }
  }

  // Opacity never decreases with length, and zero length is transparent.
  for (int i = 0; i < scalarResolution; i += 3)
  {
    for (int j = 0; j < scalarResolution; j += 3)
    {
      if (entry(i, j, 0)[3] != 0.0f)
      {
        ++failures;
        std::cerr << "Zero-length entry (" << i << ", " << j << ") is not transparent.\n";
      }
      for (int k = 1; k < lengthResolution; ++k)
      {
        if (entry(i, j, k)[3] < entry(i, j, k - 1)[3])
        {
          ++failures;
          std::cerr << "Opacity falls with length at (" << i << ", " << j << ", " << k << ")\n";
        }
      }
    }
  }

  // A property touched without a change (VTK creates default functions on first access) is
  // sampled again but not integrated again; a changed function is.
  const int integrations = table->GetIntegrationCount();
  const vtkMTimeType built = table->GetBuildTime();
  property->Modified();
  color->Modified();
  if (!table->Update(property, range, maxLength, scalarResolution, lengthResolution) ||
    table->GetIntegrationCount() != integrations || table->GetBuildTime() != built)
  {
    ++failures;
    std::cerr << "An unchanged property was integrated again.\n";
  }
  opacity->AddPoint(8.0, 0.3);
  if (!table->Update(property, range, maxLength, scalarResolution, lengthResolution) ||
    table->GetIntegrationCount() != integrations + 1 || table->GetBuildTime() == built)
  {
    ++failures;
    std::cerr << "A changed opacity function did not rebuild the table.\n";
  }
  opacity->RemovePoint(8.0);

  // A unit distance that is not positive is refused with a reason that names it.
  property->SetScalarOpacityUnitDistance(0.0);
  if (table->Update(property, range, maxLength, scalarResolution, lengthResolution) ||
    table->GetLastError().find("ScalarOpacityUnitDistance") == std::string::npos)
  {
    ++failures;
    std::cerr << "A zero unit distance was not refused with a clear error.\n";
  }

  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
