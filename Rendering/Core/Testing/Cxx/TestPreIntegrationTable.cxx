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

#include "SPTTestChecks.h"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <random>
#include <string>

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

// The table's settings: scalar samples at multiples of 1/8, on the control points.
const double Range[2] = { 0.0, 10.0 };
constexpr double MaxLength = 3.0;
constexpr int ScalarResolution = 81;
constexpr int LengthResolution = 17;

// VTK 9.2's vtkUnstructuredGridLinearRayIntegrator splits segments only at the color
// function's control points (its loop over the opacity points stops after the first), so the
// color function here has a point wherever the opacity has one.
struct TransferFunctions
{
  TransferFunctions()
  {
    this->Color->AddRGBPoint(0.0, 0.1, 0.2, 0.9);
    this->Color->AddRGBPoint(2.0, 0.3, 0.1, 0.6);
    this->Color->AddRGBPoint(3.0, 0.2, 0.9, 0.3);
    this->Color->AddRGBPoint(5.0, 0.6, 0.85, 0.2);
    this->Color->AddRGBPoint(5.5, 0.7, 0.8, 0.3);
    this->Color->AddRGBPoint(7.0, 1.0, 0.8, 0.1);
    this->Color->AddRGBPoint(10.0, 0.9, 0.1, 0.1);
    this->Opacity->AddPoint(0.0, 0.0);
    this->Opacity->AddPoint(2.0, 0.05);
    this->Opacity->AddPoint(5.0, 0.8);
    this->Opacity->AddPoint(5.5, 0.1);
    this->Opacity->AddPoint(10.0, 0.6);
    this->Property->SetColor(this->Color);
    this->Property->SetScalarOpacity(this->Opacity);
    this->Property->SetScalarOpacityUnitDistance(0.7);
  }

  vtkNew<vtkColorTransferFunction> Color;
  vtkNew<vtkPiecewiseFunction> Opacity;
  vtkNew<vtkVolumeProperty> Property;
};

bool UpdateTable(vtkPreIntegrationTable* table, vtkVolumeProperty* property)
{
  return table->Update(property, Range, MaxLength, ScalarResolution, LengthResolution);
}

const float* Entry(const vtkPreIntegrationTable* table, int i, int j, int k)
{
  return &table->GetTable()[4 * (i + ScalarResolution * (j + size_t(ScalarResolution) * k))];
}

// Random entries against both integrals, plus the corners and the diagonal.
int CheckAgainstIntegrals(const vtkPreIntegrationTable* table, vtkVolumeProperty* property)
{
  std::mt19937 random(2009);
  std::uniform_int_distribution<int> scalarIndex(0, ScalarResolution - 1);
  std::uniform_int_distribution<int> lengthIndex(0, LengthResolution - 1);
  int failures = 0;
  double worstFine = 0.0, worstVTK = 0.0;
  for (int n = 0; n < 300; ++n)
  {
    const int i = n < 4 ? (n % 2) * (ScalarResolution - 1) : scalarIndex(random);
    const int j = n < 4 ? (n / 2) * (ScalarResolution - 1) : (n % 7 == 0 ? i : scalarIndex(random));
    const int k = n < 4 ? LengthResolution - 1 : lengthIndex(random);
    const double front = table->GetScalar(i);
    const double back = table->GetScalar(j);
    const double length = table->GetLength(k);
    double fine[4], vtk[4];
    FineIntegral(property, front, back, length, fine);
    VTKLinearIntegral(property, Range, front, back, length, vtk);
    const float* value = Entry(table, i, j, k);
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
  return failures;
}

// Homogeneous segments have a closed form: alpha = 1 - exp(-tau d), color = C alpha. Opacity
// never decreases with length, and zero length is transparent.
void CheckClosedForms(const vtkPreIntegrationTable* table, const TransferFunctions& functions,
  SPTTestChecks::FailureCount& failures)
{
  int homogeneous = 0, growing = 0;
  for (int i = 0; i < ScalarResolution; i += 5)
  {
    for (int k = 0; k < LengthResolution; k += 4)
    {
      const double s = table->GetScalar(i);
      const double alpha =
        1.0 - std::exp(-functions.Opacity->GetValue(s) / 0.7 * table->GetLength(k));
      double rgb[3];
      functions.Color->GetColor(s, rgb);
      const double exact[4] = { rgb[0] * alpha, rgb[1] * alpha, rgb[2] * alpha, alpha };
      homogeneous += !Near(Entry(table, i, i, k), exact, 2.0e-6, "closed form", i, i, k);
    }
  }
  for (int i = 0; i < ScalarResolution; i += 3)
  {
    for (int j = 0; j < ScalarResolution; j += 3)
    {
      growing += Entry(table, i, j, 0)[3] != 0.0f;
      for (int k = 1; k < LengthResolution; ++k)
      {
        growing += Entry(table, i, j, k)[3] < Entry(table, i, j, k - 1)[3];
      }
    }
  }
  failures.Check(homogeneous == 0, "the homogeneous segments");
  failures.Check(growing == 0,
    std::to_string(growing) + " entries: zero length is transparent, opacity grows with length");
}

// A property touched without a change (VTK creates default functions on first access) is
// sampled again but not integrated again; a changed function is.
void CheckCaching(vtkPreIntegrationTable* table, TransferFunctions& functions,
  SPTTestChecks::FailureCount& failures)
{
  const int integrations = table->GetIntegrationCount();
  const vtkMTimeType built = table->GetBuildTime();
  functions.Property->Modified();
  functions.Color->Modified();
  failures.Check(UpdateTable(table, functions.Property) &&
      table->GetIntegrationCount() == integrations && table->GetBuildTime() == built,
    "an unchanged property is not integrated again");
  functions.Opacity->AddPoint(8.0, 0.3);
  failures.Check(UpdateTable(table, functions.Property) &&
      table->GetIntegrationCount() == integrations + 1 && table->GetBuildTime() != built,
    "a changed opacity function rebuilds the table");
  functions.Opacity->RemovePoint(8.0);
  failures.Check(UpdateTable(table, functions.Property),
    "Update succeeds after the opacity function is restored");
  // The longest edge measured from float coordinates normalized in another frame differs in
  // the seventh digit: the same table. A length that differs in the fourth digit is another.
  const vtkMTimeType restored = table->GetBuildTime();
  failures.Check(table->Update(functions.Property, Range, MaxLength * (1.0 + 3e-7),
                   ScalarResolution, LengthResolution) &&
      table->GetBuildTime() == restored,
    "a longest edge equal to float precision keeps the table");
  failures.Check(table->Update(functions.Property, Range, MaxLength * (1.0 + 1e-4),
                   ScalarResolution, LengthResolution) &&
      table->GetBuildTime() != restored,
    "another longest edge rebuilds the table");
}

// The steps the ranks of a parallel render take, each integrating a share of the scalar pairs
// (here three uneven shares), give Update()'s table bit for bit, and the same signature.
void CheckShares(vtkVolumeProperty* property, SPTTestChecks::FailureCount& failures)
{
  vtkNew<vtkPreIntegrationTable> whole;
  vtkNew<vtkPreIntegrationTable> table;
  bool pending = false;
  if (!failures.Check(UpdateTable(whole, property) &&
          table->Prepare(property, Range, MaxLength, ScalarResolution, LengthResolution, pending) &&
          pending,
        "Update() succeeds, and Prepare() on a new table asks for the integration"))
  {
    return;
  }
  const vtkIdType pairs = table->GetNumberOfScalarPairs();
  const size_t per = size_t(table->GetValuesPerScalarPair());
  std::vector<float> values(size_t(pairs) * per, -1.0f);
  const vtkIdType cuts[4] = { 0, 7, pairs / 2 + 3, pairs };
  for (int share = 0; share < 3; ++share)
  {
    table->IntegrateScalarPairs(cuts[share], cuts[share + 1], &values[cuts[share] * per]);
  }
  table->SetIntegrated(values.data());
  failures.Check(
    table->GetTable() == whole->GetTable(), "the table integrated in shares is Update()'s");
  failures.Check(table->GetSignature() == whole->GetSignature(),
    "the table integrated in shares has Update()'s signature");
}
}

int TestPreIntegrationTable(int, char*[])
{
  TransferFunctions functions;
  vtkNew<vtkPreIntegrationTable> table;
  SPTTestChecks::FailureCount failures;
  if (!failures.Check(
        UpdateTable(table, functions.Property), "Update succeeds on a valid property") ||
    !failures.Check(table->GetTable().size() ==
        size_t(4) * ScalarResolution * ScalarResolution * LengthResolution,
      "the table has 4 values per entry"))
  {
    return failures.ExitStatus();
  }

  failures.Check(CheckAgainstIntegrals(table, functions.Property) == 0, "the integrals");
  CheckClosedForms(table, functions, failures);
  CheckCaching(table, functions, failures);
  CheckShares(functions.Property, failures);

  // A unit distance that is not positive is refused with a reason that names it.
  functions.Property->SetScalarOpacityUnitDistance(0.0);
  failures.Check(!UpdateTable(table, functions.Property) &&
      table->GetLastError().find("ScalarOpacityUnitDistance") != std::string::npos,
    "a zero unit distance is refused with a clear error");

  // A table too large to integrate in reasonable time and memory is refused, naming the
  // settings to lower, before anything is allocated.
  functions.Property->SetScalarOpacityUnitDistance(0.7);
  vtkNew<vtkPreIntegrationTable> huge;
  failures.Check(!huge->Update(functions.Property, Range, MaxLength, 1024, 1024) &&
      huge->GetLastError().find("PreIntegrationThicknessResolution") != std::string::npos &&
      huge->GetTable().empty(),
    "a 1024 x 1024 x 1024 table is refused with a clear error");
  failures.Check(!huge->Update(functions.Property, Range, MaxLength, 1024, 64) &&
      huge->GetLastError().find("times the integration time") != std::string::npos,
    "a 1024 x 1024 x 64 table (minutes of integration) is refused");
  return failures.ExitStatus();
}
