// The proof that the GPU k-buffer of vtkHAVSVolumeMapper runs its read-modify-write one
// fragment at a time, in primitive order: its image must equal a CPU simulation of the same
// algorithm (HAVSKBufferModel.h) fed with the same fragments in the same order: the mapper's
// own faces (same mesh, same sort) rasterized at the pixel centers in its draw order, through
// the same pre-integration table. Pixels whose center lies within 0.01 pixels of a triangle
// edge (where coverage is a matter of rasterizer precision) are left out of the comparison.
//
// The test can fail: the CPU image with a perturbed order (consecutive fragments of each pixel
// swapped, or every fourth fragment's update lost, as in a read-modify-write race) differs
// clearly from the GPU image, and the test checks that it does.
//
// Two meshes, every k-buffer size from 2 to 6 (k = 2 keeps one entry per pixel and draws no
// flush pass; an odd k leaves half of the last target unused), and every synchronization mode
// that the context has:
// a soup of 40 overlapping random tetrahedra (every face on the boundary, fragments far from
// sorted) and a jittered block of tetrahedra with a slot cut out (non-convex, gaps).

#include "HAVSKBufferModel.h"

#include "vtkHAVSFaceBuffers.h"
#include "vtkHAVSKBuffer.h"
#include "vtkHAVSVolumeMapper.h"
#include "vtkPreIntegrationTable.h"
#include "vtkTetrahedralMesh.h"
#include "vtkVolumeViewMatrices.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkOpenGLLoader.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTesting.h"
#include "vtkUnstructuredGrid.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include "SPTTestBlock.h"
#include "SPTTestChecks.h"
#include "SPTTestWindow.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <iostream>
#include <random>
#include <string>
#include <vector>

namespace
{
using namespace HAVSKBufferModel;

constexpr int Size = 96;

enum class Perturbation
{
  None,
  SwapPairs,
  LoseEveryFourth
};

vtkSmartPointer<vtkUnstructuredGrid> MakeSoup()
{
  std::mt19937 random(2005);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  vtkNew<vtkPoints> points;
  vtkNew<vtkFloatArray> scalars;
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  for (int t = 0; t < 40; ++t)
  {
    const double center[3] = { uniform(random), uniform(random), uniform(random) };
    vtkIdType ids[4];
    for (vtkIdType& id : ids)
    {
      id = points->InsertNextPoint(center[0] + 0.5 * (uniform(random) - 0.5),
        center[1] + 0.5 * (uniform(random) - 0.5), center[2] + 0.5 * (uniform(random) - 0.5));
      scalars->InsertNextValue(static_cast<float>(uniform(random)));
    }
    grid->InsertNextCell(VTK_TETRA, 4, ids);
  }
  grid->SetPoints(points);
  grid->GetPointData()->SetScalars(scalars);
  return grid;
}

// 5 x 5 x 3 jittered cubes, 5 tetrahedra each, without the cubes of a slot through the middle.
vtkSmartPointer<vtkUnstructuredGrid> MakeSlottedBlock()
{
  const int n[3] = { 5, 5, 3 };
  std::mt19937 random(11);
  std::uniform_real_distribution<double> jitter(-0.2, 0.2);
  return SPTTestBlock::Make(
    n,
    [&](int i, int j, int k, vtkPoints* points, vtkFloatArray* scalars)
    {
      points->InsertNextPoint(i + jitter(random), j + jitter(random), k + jitter(random));
      scalars->InsertNextValue(static_cast<float>(std::sin(0.9 * i) * std::cos(0.7 * j) + 0.3 * k));
    },
    [](int i, int, int k) { return i != 2 || k == 0; }, false); // the slot
}

vtkSmartPointer<vtkVolumeProperty> MakeProperty(const double range[2], double unitDistance)
{
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(range[0], 0.1, 0.3, 1.0);
  color->AddRGBPoint(0.5 * (range[0] + range[1]), 0.2, 1.0, 0.3);
  color->AddRGBPoint(range[1], 1.0, 0.3, 0.1);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(range[0], 0.1);
  opacity->AddPoint(range[1], 0.6);
  auto property = vtkSmartPointer<vtkVolumeProperty>::New();
  property->SetColor(color);
  property->SetScalarOpacity(opacity);
  property->SetScalarOpacityUnitDistance(unitDistance);
  return property;
}

struct Comparison
{
  int Compared = 0;
  int Layered = 0; // compared pixels with 4 fragments or more
  int Ambiguous = 0;
  int Off = 0;        // pixels off by more than the tolerance
  double Largest = 0; // largest channel difference
};

Comparison Compare(const std::vector<PixelFragments>& pixels, const std::vector<glm::vec4>& cpu,
  const std::vector<unsigned char>& gpu, double tolerance)
{
  Comparison result;
  for (size_t p = 0; p < pixels.size(); ++p)
  {
    if (pixels[p].Ambiguous)
    {
      ++result.Ambiguous;
      continue;
    }
    ++result.Compared;
    result.Layered += pixels[p].Fragments.size() >= 4;
    double difference = 0.0;
    for (int c = 0; c < 4; ++c)
    {
      difference = std::max(difference, std::abs(gpu[4 * p + c] / 255.0 - cpu[p][c]));
    }
    result.Off += difference > tolerance;
    result.Largest = std::max(result.Largest, difference);
  }
  return result;
}

// Whether the current context offers the synchronization. Rasterization order is only claimed
// for Mesa's llvmpipe; anywhere else it is a data race that this test would rightly fail.
bool Offers(int access)
{
  switch (access)
  {
    case vtkHAVSVolumeMapper::FRAGMENT_SHADER_INTERLOCK:
      return vtkHAVSKBuffer::HasExtension("GL_ARB_fragment_shader_interlock");
    case vtkHAVSVolumeMapper::FRAMEBUFFER_FETCH:
      return vtkHAVSKBuffer::HasExtension("GL_EXT_shader_framebuffer_fetch");
    default:
    {
      const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
      return vtkHAVSKBuffer::HasExtension("GL_ARB_shader_image_load_store") && renderer &&
        std::strstr(renderer, "llvmpipe") != nullptr;
    }
  }
}

// The CPU images for one k-buffer size, by Perturbation: in draw order, and in the two
// perturbed orders.
using Simulations = std::array<std::vector<glm::vec4>, 3>;

// The mapper drawing the mesh alone, offscreen, onto a transparent background; and on the CPU
// the same mesh, faces, sort and table as the mapper's, and the fragments.
struct Scene
{
  Scene(vtkUnstructuredGrid* grid, double unitDistance)
  {
    this->Window->SetOffScreenRendering(1);
    this->Window->SetAlphaBitPlanes(1);
    this->Window->SetMultiSamples(0);
    this->Window->SetSize(Size, Size);
    this->Renderer->SetBackgroundAlpha(0.0);
    this->Window->AddRenderer(this->Renderer);
    this->Mapper->SetInputData(grid);
    this->Property = MakeProperty(grid->GetPointData()->GetScalars()->GetRange(), unitDistance);
    this->Volume->SetMapper(this->Mapper);
    this->Volume->SetProperty(this->Property);
    this->Renderer->AddVolume(this->Volume);
    this->Renderer->GetActiveCamera()->SetPosition(2.0, -3.0, 2.5);
    this->Renderer->GetActiveCamera()->SetViewUp(0.0, 0.0, 1.0);
    this->Renderer->ResetCamera();
    this->Window->Render(); // creates the context, for Offers()

    this->Mesh->Update(grid, vtkTetrahedralMesh::ScalarSelection());
    this->Faces->Update(this->Mesh);
    vtkVolumeViewMatrices matrices;
    matrices.Compute(this->Renderer, this->Volume, this->Mesh);
    this->Faces->Sort(matrices.MCVC, matrices.ParallelProjection);
    this->Table->Update(this->Property, this->Mesh->GetScalarRange(),
      this->Mesh->GetMaxEdgeLength() * this->Mesh->GetScale(),
      this->Mapper->GetPreIntegrationScalarResolution(),
      this->Mapper->GetPreIntegrationThicknessResolution());
    this->ThicknessToTable = float(1.0 / this->Mesh->GetMaxEdgeLength());
    this->Pixels = Rasterize(this->Faces, matrices, Size);
  }

  // The CPU image of a k-buffer of size k fed with the fragments in draw order, or in a
  // perturbed order.
  std::vector<glm::vec4> Simulate(int k, Perturbation perturbation) const
  {
    std::vector<glm::vec4> image(this->Pixels.size());
    for (size_t p = 0; p < this->Pixels.size(); ++p)
    {
      std::vector<Entry> fragments = this->Pixels[p].Fragments;
      if (perturbation == Perturbation::SwapPairs)
      {
        for (size_t i = 0; i + 1 < fragments.size(); i += 2)
        {
          std::swap(fragments[i], fragments[i + 1]);
        }
      }
      KBuffer kbuffer(k, this->Table, this->ThicknessToTable, this->Pixels[p].LengthScale);
      for (size_t i = 0; i < fragments.size(); ++i)
      {
        if (perturbation != Perturbation::LoseEveryFourth || i % 4 != 3)
        {
          kbuffer.Insert(fragments[i]);
        }
      }
      image[p] = kbuffer.Flush();
    }
    return image;
  }

  void Print(const char* name) const
  {
    size_t fragments = 0, longest = 0;
    for (const PixelFragments& pixel : this->Pixels)
    {
      fragments += pixel.Fragments.size();
      longest = std::max(longest, pixel.Fragments.size());
    }
    std::cout << name << ": " << this->Faces->GetNumberOfFaces() << " faces, " << fragments
              << " fragments, up to " << longest << " per pixel\n";
  }

  vtkSmartPointer<vtkRenderWindow> Window = SPTTestWindow::New();
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkHAVSVolumeMapper> Mapper;
  vtkSmartPointer<vtkVolumeProperty> Property;
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkTetrahedralMesh> Mesh;
  vtkNew<vtkHAVSFaceBuffers> Faces;
  vtkNew<vtkPreIntegrationTable> Table;
  float ThicknessToTable;
  std::vector<PixelFragments> Pixels;
};

// The GPU image with one synchronization against the CPU k-buffer in draw order, and against
// the perturbed orders, which it must tell apart.
void CheckSynchronization(Scene& scene, int k, int access, const Simulations& simulated,
  int* modesRun, SPTTestChecks::FailureCount& failures)
{
  scene.Mapper->SetKBufferSynchronization(access);
  scene.Window->Render();
  if (!failures.Check(scene.Mapper->GetKBufferSynchronizationInUse() >= 0,
        "the mapper draws with synchronization " + std::to_string(access)))
  {
    return;
  }
  ++*modesRun;
  // RGBA, bottom row first.
  const std::vector<unsigned char> image = SPTTestWindow::Capture(scene.Window, true);
  auto compare = [&](Perturbation p)
  { return Compare(scene.Pixels, simulated[int(p)], image, 3.0 / 255.0); };
  const Comparison same = compare(Perturbation::None);
  const Comparison pairs = compare(Perturbation::SwapPairs);
  const Comparison races = compare(Perturbation::LoseEveryFourth);
  std::cout << "  k=" << k << ", synchronization " << access << ": " << same.Off << " of "
            << same.Compared << " pixels off (largest " << same.Largest << ", " << same.Ambiguous
            << " on edges left out); perturbed orders, of " << same.Layered
            << " pixels with 4 fragments or more: " << pairs.Off << " off with pairs swapped, "
            << races.Off << " with every 4th update lost\n";
  failures.Check(same.Off == 0 && same.Ambiguous <= same.Compared / 20,
    "the GPU k-buffer is the CPU k-buffer fed in draw order");
  // A k-buffer of 6 absorbs swapped pairs; lost updates show at any size. Measured on
  // llvmpipe: 70-80% (soup) and 28% (block) of the layered pixels off with lost updates,
  // 92% and 94% with swapped pairs at k = 2; the bounds leave a factor of 2 or more.
  failures.Check(races.Off >= same.Layered / 8 && (k != 2 || pairs.Off >= same.Layered / 4),
    "the comparison tells a perturbed order from the right one");
}

void CheckMesh(vtkUnstructuredGrid* grid, const char* name, double unitDistance, int* modesRun,
  SPTTestChecks::FailureCount& failures)
{
  Scene scene(grid, unitDistance);
  scene.Print(name);
  for (int k = 2; k <= 6; ++k)
  {
    scene.Mapper->SetKBufferSize(k);
    const Simulations simulated = { scene.Simulate(k, Perturbation::None),
      scene.Simulate(k, Perturbation::SwapPairs),
      scene.Simulate(k, Perturbation::LoseEveryFourth) };
    for (int access : { vtkHAVSVolumeMapper::FRAGMENT_SHADER_INTERLOCK,
           vtkHAVSVolumeMapper::FRAMEBUFFER_FETCH, vtkHAVSVolumeMapper::RASTERIZATION_ORDER })
    {
      if (!Offers(access))
      {
        std::cout << "  k=" << k << ", synchronization " << access << ": not in this context\n";
        continue;
      }
      CheckSynchronization(scene, k, access, simulated, modesRun, failures);
    }
  }
}
}

int TestHAVSKBufferOrdering(int, char*[])
{
  int modesRun = 0;
  SPTTestChecks::FailureCount failures;
  CheckMesh(MakeSoup(), "soup of 40 overlapping tetrahedra", 0.4, &modesRun, failures);
  CheckMesh(MakeSlottedBlock(), "jittered block with a slot", 2.0, &modesRun, failures);
  if (modesRun == 0)
  {
    std::cout << "The context has no way to synchronize the k-buffer; nothing to test.\n";
    return VTK_SKIP_RETURN_CODE;
  }
  return failures.ExitStatus();
}
