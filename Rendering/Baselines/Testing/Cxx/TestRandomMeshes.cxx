// Random meshes rendered with the three mappers, as Testing/Python/test_fuzz.py does, so that
// `make sanitize` runs the mappers' input handling and drawing on invalid input under
// AddressSanitizer and UndefinedBehaviorSanitizer: random points (also NaN and Inf), random and
// invalid connectivity (out-of-range ids, wrong point counts, 2D and quadratic cells) and
// random arrays (1 to 9 components, NaN and Inf, too short), for fixed seeds. Checks: every
// render returns without an OpenGL error, the input is not modified, and
// some seeds draw while others report an error.

#include "vtkHAVSVolumeMapper.h"
#include "vtkPBVRVolumeMapper.h"
#include "vtkSPTVolumeMapper.h"

#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkColorTransferFunction.h"
#include "vtkDoubleArray.h"
#include "vtkMinimalStandardRandomSequence.h"
#include "vtkNew.h"
#include "vtkOpenGLLoader.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkTestErrorObserver.h"
#include "vtkUnstructuredGrid.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include "SPTTestChecks.h"
#include "SPTTestWindow.h"

#include <cmath>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

namespace
{
class Random
{
public:
  explicit Random(int seed) { this->Sequence->SetSeed(seed); }
  double Uniform(double low, double high)
  {
    this->Sequence->Next();
    return this->Sequence->GetRangeValue(low, high);
  }
  int Integer(int low, int high) // [low, high)
  {
    return std::min(high - 1, static_cast<int>(std::floor(this->Uniform(low, high))));
  }
  bool Chance(double p) { return this->Uniform(0.0, 1.0) < p; }

private:
  vtkNew<vtkMinimalStandardRandomSequence> Sequence;
};

double Special(Random& random)
{
  const double values[] = { std::numeric_limits<double>::quiet_NaN(),
    std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity() };
  return values[random.Integer(0, 3)];
}

vtkSmartPointer<vtkDoubleArray> RandomArray(Random& random, vtkIdType count, const char* name)
{
  const int componentChoices[] = { 1, 1, 1, 3, 9 };
  const int components = componentChoices[random.Integer(0, 5)];
  auto array = vtkSmartPointer<vtkDoubleArray>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  const vtkIdType tuples = random.Chance(0.05) ? std::max<vtkIdType>(count - 1, 0) : count;
  array->SetNumberOfTuples(tuples);
  const double scale = std::pow(10.0, random.Chance(0.2) ? random.Uniform(-30, 30) : 0.0);
  for (vtkIdType i = 0; i < tuples * components; ++i)
  {
    array->SetValue(i, random.Chance(0.005) ? Special(random) : scale * random.Uniform(-1, 1));
  }
  return array;
}

vtkSmartPointer<vtkUnstructuredGrid> RandomGrid(Random& random)
{
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  const int numberOfPoints = random.Integer(0, 30);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  const double scale = std::pow(10.0, random.Chance(0.2) ? random.Uniform(-30, 30) : 0.0);
  for (int i = 0; i < numberOfPoints; ++i)
  {
    double p[3] = { scale * random.Uniform(-1, 1), scale * random.Uniform(-1, 1),
      scale * random.Uniform(-1, 1) };
    if (random.Chance(0.005))
    {
      p[random.Integer(0, 3)] = Special(random);
    }
    points->InsertNextPoint(p);
  }
  grid->SetPoints(points);
  const int types[] = { VTK_TETRA, VTK_HEXAHEDRON, VTK_WEDGE, VTK_PYRAMID, VTK_VOXEL, VTK_TRIANGLE,
    VTK_QUADRATIC_TETRA, VTK_QUADRATIC_HEXAHEDRON };
  const int sizes[] = { 4, 8, 6, 5, 8, 3, 10, 20 };
  const int numberOfCells = random.Integer(0, 25);
  for (int c = 0; c < numberOfCells; ++c)
  {
    const int t = random.Integer(0, 8);
    const int size = random.Chance(0.01) ? random.Integer(0, 12) : sizes[t];
    const int high = std::max(numberOfPoints, 1) + (random.Chance(0.01) ? 3 : 0);
    const int low = random.Chance(0.01) ? -1 : 0;
    vtkIdType ids[20];
    for (int i = 0; i < size; ++i)
    {
      ids[i] = random.Integer(low, high);
    }
    grid->InsertNextCell(types[t], size, ids);
  }
  if (random.Chance(0.9))
  {
    grid->GetPointData()->SetScalars(RandomArray(random, grid->GetNumberOfPoints(), "a"));
  }
  if (random.Chance(0.5))
  {
    grid->GetCellData()->AddArray(RandomArray(random, grid->GetNumberOfCells(), "b"));
  }
  return grid;
}

vtkSmartPointer<vtkVolumeProperty> RandomProperty(Random& random)
{
  vtkNew<vtkColorTransferFunction> color;
  vtkNew<vtkPiecewiseFunction> opacity;
  const int nodes = random.Integer(0, 4);
  for (int i = 0; i < nodes; ++i)
  {
    const double x = random.Uniform(-2, 2);
    color->AddRGBPoint(x, random.Uniform(0, 1), random.Uniform(0, 1), random.Uniform(0, 1));
    opacity->AddPoint(x, random.Uniform(0, 1));
  }
  auto property = vtkSmartPointer<vtkVolumeProperty>::New();
  property->SetColor(color);
  property->SetScalarOpacity(opacity);
  property->SetScalarOpacityUnitDistance(std::pow(10.0, random.Uniform(-3, 1)));
  return property;
}

vtkSmartPointer<vtkUnstructuredGridVolumeMapper> RandomMapper(Random& random, int kind)
{
  vtkSmartPointer<vtkUnstructuredGridVolumeMapper> mapper;
  if (kind == 0)
  {
    auto spt = vtkSmartPointer<vtkSPTVolumeMapper>::New();
    spt->SetRepetitionLevel(random.Integer(1, 4));
    spt->SetAutoAdjustRepetitions(false);
    spt->SetPreIntegrationScalarResolution(16);
    spt->SetPreIntegrationThicknessResolution(8);
    mapper = spt;
  }
  else if (kind == 1)
  {
    auto havs = vtkSmartPointer<vtkHAVSVolumeMapper>::New();
    havs->SetKBufferSize(random.Integer(2, 7));
    havs->SetPreIntegrationScalarResolution(16);
    havs->SetPreIntegrationThicknessResolution(8);
    mapper = havs;
  }
  else
  {
    auto pbvr = vtkSmartPointer<vtkPBVRVolumeMapper>::New();
    pbvr->SetRepetitionLevel(random.Integer(1, 4));
    pbvr->SetMaximumParticleMemory(16);
    mapper = pbvr;
  }
  if (random.Chance(0.3))
  {
    mapper->SetScalarModeToUseCellFieldData();
    mapper->SelectScalarArray(random.Chance(0.5) ? "b" : "c");
  }
  return mapper;
}

struct Counts
{
  int Drew = 0;
  int Errors = 0;
};

// Render one seed.
void RenderSeed(vtkRenderWindow* window, vtkRenderer* renderer, int kind, int seed, Counts& counts,
  SPTTestChecks::FailureCount& failures)
{
  Random random(1000 * kind + seed + 1);
  vtkSmartPointer<vtkUnstructuredGrid> grid = RandomGrid(random);
  vtkSmartPointer<vtkVolumeProperty> property = RandomProperty(random);
  vtkSmartPointer<vtkUnstructuredGridVolumeMapper> mapper = RandomMapper(random, kind);
  vtkNew<vtkTest::ErrorObserver> messages;
  mapper->AddObserver(vtkCommand::ErrorEvent, messages);
  mapper->AddObserver(vtkCommand::WarningEvent, messages);
  const vtkMTimeType inputTime = grid->GetMTime();

  mapper->SetInputData(grid);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(property);
  renderer->AddVolume(volume);
  vtkNew<vtkCamera> camera; // nothing carried over from the last seed
  renderer->SetActiveCamera(camera);
  renderer->ResetCamera();
  window->Render();
  const GLenum error = glGetError();

  const std::vector<unsigned char> rgba = SPTTestWindow::Capture(window, true);
  bool drew = false;
  for (size_t alpha = 3; alpha < rgba.size(); alpha += 4)
  {
    drew = drew || rgba[alpha] > 0;
  }
  renderer->RemoveVolume(volume);
  mapper->ReleaseGraphicsResources(window);

  counts.Drew += drew ? 1 : 0;
  counts.Errors += messages->GetError() || messages->GetWarning() ? 1 : 0;
  const std::string what = "mapper " + std::to_string(kind) + ", seed " + std::to_string(seed);
  failures.Check(error == GL_NO_ERROR, what + ": no OpenGL error");
  failures.Check(grid->GetMTime() == inputTime, what + ": the input is not modified");
}
}

int TestRandomMeshes(int, char*[])
{
  constexpr int Seeds = 60;
  vtkSmartPointer<vtkRenderWindow> window = SPTTestWindow::New();
  window->SetSize(32, 32);
  window->SetMultiSamples(0);
  window->SetAlphaBitPlanes(1);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  window->Render();
  glGetError();

  SPTTestChecks::FailureCount failures;
  const std::string names[] = { "SPT", "HAVS", "PBVR" };
  for (int kind = 0; kind < 3; ++kind)
  {
    Counts counts;
    for (int seed = 0; seed < Seeds; ++seed)
    {
      RenderSeed(window, renderer, kind, seed, counts, failures);
    }
    std::cout << names[kind] << ": " << counts.Drew << " of " << Seeds << " seeds drew, "
              << counts.Errors << " reported an error or a warning\n";
    failures.Check(counts.Drew >= 5 && counts.Errors >= 5,
      names[kind] + ": the random input reaches both drawing and errors");
  }
  return failures.ExitStatus();
}
