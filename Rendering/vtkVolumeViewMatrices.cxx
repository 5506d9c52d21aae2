#include "vtkVolumeViewMatrices.h"

#include "vtkCamera.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkRenderer.h"
#include "vtkVolume.h"

#include "vtkShaderSourceUtilities.h"
#include "vtkTetrahedralMesh.h"

#include <algorithm>
#include <cmath>

namespace
{
// The largest singular value of the linear part of a model matrix: how much it scales.
double ModelScale(vtkMatrix4x4* model)
{
  double linear[3][3], u[3][3], w[3], vt[3][3];
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      linear[i][j] = model->GetElement(i, j);
    }
  }
  vtkMath::SingularValueDecomposition3x3(linear, u, w, vt);
  return std::max({ std::abs(w[0]), std::abs(w[1]), std::abs(w[2]) });
}

// Normalized view coordinates are view coordinates / viewScale. The projection of a
// normalized point is P diag(viewScale, viewScale, viewScale, 1), which is the same
// projective map as P with its translation column divided by viewScale: clip coordinates
// (and w) stay O(1) too.
void ToNormalizedView(vtkMatrix4x4* modelToView, vtkMatrix4x4* viewToClip, double viewScale)
{
  for (int i = 0; i < 4; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      modelToView->SetElement(j, i, modelToView->GetElement(j, i) / viewScale);
    }
    viewToClip->SetElement(i, 3, viewToClip->GetElement(i, 3) / viewScale);
  }
}

void ToRowMajor(vtkMatrix4x4* matrix, double elements[4][4])
{
  for (int i = 0; i < 4; ++i)
  {
    for (int j = 0; j < 4; ++j)
    {
      elements[i][j] = matrix->GetElement(i, j);
    }
  }
}

// A corner of the bounding box beyond the near plane (or behind the eye) or a side plane has
// clip z < -w, |x| > w or |y| > w; the box is convex, so without such a corner no cell
// reaches there.
bool ClipPlanesCut(
  const double bounds[6], const double modelToView[4][4], const double viewToClip[4][4])
{
  bool cut = false;
  for (int corner = 0; corner < 8; ++corner)
  {
    const double point[4] = { bounds[corner & 1], bounds[2 + ((corner >> 1) & 1)],
      bounds[4 + ((corner >> 2) & 1)], 1.0 };
    double view[4], clip[4];
    for (int i = 0; i < 4; ++i)
    {
      view[i] = modelToView[i][0] * point[0] + modelToView[i][1] * point[1] +
        modelToView[i][2] * point[2] + modelToView[i][3];
    }
    for (int i = 0; i < 4; ++i)
    {
      clip[i] = viewToClip[i][0] * view[0] + viewToClip[i][1] * view[1] +
        viewToClip[i][2] * view[2] + viewToClip[i][3] * view[3];
    }
    const bool inside =
      clip[2] >= -clip[3] && std::abs(clip[0]) <= clip[3] && std::abs(clip[1]) <= clip[3];
    cut = cut || !inside;
  }
  return cut;
}
}

void vtkVolumeViewMatrices::Compute(
  vtkRenderer* ren, vtkVolume* vol, const vtkTetrahedralMesh* mesh)
{
  // Everything is composed in double and handed to the GPU in units of the mesh's own size
  // (view coordinates divided by viewScale), so that float precision holds whatever the
  // magnitude of the coordinates.
  vtkNew<vtkMatrix4x4> normalization;
  mesh->GetNormalizationMatrix(normalization);
  vtkMatrix4x4* model = vol->GetMatrix();
  const double modelScale = ModelScale(model);
  this->ViewScale = mesh->GetScale() * (modelScale > 0.0 ? modelScale : 1.0);

  vtkCamera* camera = ren->GetActiveCamera();
  this->ParallelProjection = camera->GetParallelProjection() != 0;
  vtkNew<vtkMatrix4x4> modelToView;
  vtkMatrix4x4::Multiply4x4(camera->GetModelViewTransformMatrix(), model, modelToView);
  vtkMatrix4x4::Multiply4x4(modelToView, normalization, modelToView);
  vtkNew<vtkMatrix4x4> viewToClip;
  viewToClip->DeepCopy(camera->GetProjectionTransformMatrix(ren->GetTiledAspectRatio(), -1, 1));
  ToNormalizedView(modelToView, viewToClip, this->ViewScale);
  vtkNew<vtkMatrix4x4> clipToView;
  vtkMatrix4x4::Invert(viewToClip, clipToView);
  vtkShaderSourceUtilities::ToColumnMajor(modelToView, this->MCVC);
  vtkShaderSourceUtilities::ToColumnMajor(viewToClip, this->VCDC);
  vtkShaderSourceUtilities::ToColumnMajor(clipToView, this->DCVC);
  ToRowMajor(modelToView, this->ModelToView);
  ToRowMajor(viewToClip, this->ViewToClip);

  double linear[3][3];
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      linear[i][j] = this->ModelToView[i][j];
    }
  }
  this->Mirrored = vtkMath::Determinant3x3(linear) < 0.0;
  this->ClipPlanesCutBounds =
    ClipPlanesCut(mesh->GetNormalizedBounds(), this->ModelToView, this->ViewToClip);
  vtkMath::Invert3x3(linear, this->ViewToModelLinear);
  for (int column = 0; column < 3; ++column)
  {
    for (int row = 0; row < 3; ++row)
    {
      this->VCMCLinear[3 * column + row] = static_cast<float>(this->ViewToModelLinear[row][column]);
    }
  }
}
