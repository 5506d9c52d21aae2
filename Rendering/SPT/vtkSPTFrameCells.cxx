// What the traversals of an SPT frame draw of each volume, and how: the cells drawn as points,
// those a compute pass visits, the outlines; and the depth slabs' ranges (vtkSPTFrame.h).
#include "vtkSPTFrame.h"

#include "vtkOpenGLLoader.h"

#include "vtkEnsembleBuffer.h"
#include "vtkSPTComputeTraversal.h"
#include "vtkSPTMeshBuffers.h"
#include "vtkTetrahedralMesh.h"
#include "vtkVolumeViewMatrices.h"

#include <algorithm>
#include <cmath>

namespace
{
// The compute traversal takes the cells drawn as points that are about this many pixels across
// or less: a sample's work grows with the group's repetitions, and at 256 repetitions per traversal
// on a 200,000-cell TetGen mesh, computing all its points (up to 8 pixels across) took 1.13 to 1.17
// of the frame that computes those up to 4 pixels (0.69 to 0.88 at 2 to 32 repetitions); on the
// 1M-cell one, 4 pixels take nearly all its points.
constexpr double ComputedCellSize = 4.0;
// ... and only where they are at least this many per sample of the image.
constexpr double ComputedCellsPerSample = 0.25;
}

void vtkSPTFrame::ChooseSlabs()
{
  // Any split of each ray between its segments composites exactly in expectation; equal parts
  // of the depth the volumes' bounds span within the clipping range are a split that every
  // volume of the frame (and every rank, whose bounds are the whole's) agrees on.
  const int slabs = this->FrameSettings.DepthSlabs;
  std::fill(std::begin(this->SlabStarts), std::end(this->SlabStarts), 2.0f);
  if (slabs <= 1 || this->Volumes.empty())
  {
    return;
  }
  const vtkVolumeViewMatrices& view = *this->Volumes.front().Matrices;
  double nearest = VTK_DOUBLE_MAX;
  double farthest = -VTK_DOUBLE_MAX;
  for (const Volume& volume : this->Volumes)
  {
    nearest = std::min(nearest, volume.Matrices->BoundsDistance[0]);
    farthest = std::max(farthest, volume.Matrices->BoundsDistance[1]);
  }
  nearest = std::max(nearest, view.ClippingDistance[0]);
  farthest = std::min(farthest, view.ClippingDistance[1]);
  if (!(nearest < farthest) || view.ViewScale <= 0.0)
  {
    return; // nothing in view: one slab
  }
  for (int k = 1; k < slabs; ++k)
  {
    const double distance = nearest + (farthest - nearest) * k / slabs;
    // The window depth of that distance, through the first volume's projection.
    const double z = -distance / view.ViewScale;
    const double clipZ = view.ViewToClip[2][2] * z + view.ViewToClip[2][3];
    const double clipW = view.ViewToClip[3][2] * z + view.ViewToClip[3][3];
    const double depth = clipW != 0.0 ? 0.5 * clipZ / clipW + 0.5 : 2.0;
    this->SlabStarts[k - 1] = static_cast<float>(std::max(0.0, std::min(depth, 1.0)));
  }
}

void vtkSPTFrame::ChooseSmallCells()
{
  // The cells drawn as points are about SmallCellSize pixels across at the depth of the mesh's
  // centre, and no point may exceed the largest size OpenGL draws, wherever it lies. Of them,
  // the compute traversal takes the leading classes, about ComputedCellSize pixels across.
  GLfloat pointSizes[2] = { 1.0f, 1.0f };
  glGetFloatv(GL_POINT_SIZE_RANGE, pointSizes);
  const double halfSize[2] = { 0.5 * this->Ensemble->GetPassWidth(),
    0.5 * this->Ensemble->GetPassHeight() };
  this->PointCellCounts.clear();
  this->ComputeCellCounts.clear();
  vtkIdType computed = 0;
  for (const Volume& volume : this->Volumes)
  {
    const double* bound = volume.Matrices->NDCPerLength;
    const double* typical = volume.Matrices->TypicalNDCPerLength;
    const double largestPixels = std::max(bound[0] * halfSize[0], bound[1] * halfSize[1]);
    const double typicalPixels = std::max(typical[0] * halfSize[0], typical[1] * halfSize[1]);
    const bool inView = largestPixels > 0.0 && typicalPixels > 0.0;
    const double length = inView ? std::min(this->FrameSettings.SmallCellSize / typicalPixels,
                                     (pointSizes[1] - 1.0) / largestPixels)
                                 : -1.0;
    this->PointCellCounts.push_back(volume.Buffers->CountSmallCells(length));
    const double computeLength = !inView || this->FrameSettings.ComputeEveryPoint
      ? length
      : std::min(length, ComputedCellSize / typicalPixels);
    this->ComputeCellCounts.push_back(
      this->FrameSettings.Compute ? volume.Buffers->CountSmallCells(computeLength) : 0);
    computed += this->ComputeCellCounts.back();
  }
  // A traversal that computes clears the fixed-point sums and adds them to the image, a pass
  // over every sample: it pays where the cells it takes from the rasterizer are many.
  const double samples =
    double(this->Ensemble->GetPassWidth()) * double(this->Ensemble->GetPassHeight());
  if (!this->FrameSettings.ComputeEveryPoint && computed < ComputedCellsPerSample * samples)
  {
    this->ComputeCellCounts.assign(this->Volumes.size(), 0);
  }
  this->ComputedCellCounts.assign(this->Volumes.size(), 0);
}

bool vtkSPTFrame::Computes(PassKind kind, size_t volume) const
{
  return this->FrameSettings.Compute &&
    (kind == PassKind::Keys || kind == PassKind::KeysAndCoverage || kind == PassKind::Colors) &&
    this->ComputeCellCounts[volume] > 0;
}

vtkIdType vtkSPTFrame::FirstRasterizedPoint(PassKind kind, size_t volume) const
{
  return this->Computes(kind, volume) ? this->ComputeCellCounts[volume] : 0;
}

bool vtkSPTFrame::Rasterizes(PassKind kind, size_t volume, bool points) const
{
  const vtkIdType pointCells = this->PointCellCounts[volume];
  return points ? pointCells > this->FirstRasterizedPoint(kind, volume)
                : pointCells < this->Volumes[volume].Buffers->GetMesh()->GetNumberOfTetrahedra();
}

bool vtkSPTFrame::ComputesMostCells() const
{
  vtkIdType computed = 0;
  vtkIdType cells = 0;
  for (size_t v = 0; v < this->Volumes.size(); ++v)
  {
    computed += this->FrameSettings.Compute ? this->ComputeCellCounts[v] : 0;
    cells += this->Volumes[v].Buffers->GetMesh()->GetNumberOfTetrahedra();
  }
  return computed > 0 && 2 * computed >= cells;
}

bool vtkSPTFrame::Computes(PassKind kind) const
{
  for (size_t v = 0; v < this->Volumes.size(); ++v)
  {
    if (this->Computes(kind, v))
    {
      return true;
    }
  }
  return false;
}
