#include "vtkVolumeViewMatrices.h"

#include "vtkCamera.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPlane.h"
#include "vtkPlaneCollection.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkVolume.h"

#include "vtkTetrahedralMesh.h"

#include <algorithm>
#include <cmath>

namespace
{
// A row-major n x n matrix (acting on column vectors) as the column-major floats that
// glUniformMatrix*fv expect without transposition.
void ToColumnMajor(const double* rowMajor, int n, float* out)
{
  for (int column = 0; column < n; ++column)
  {
    for (int row = 0; row < n; ++row)
    {
      out[n * column + row] = static_cast<float>(rowMajor[n * row + column]);
    }
  }
}

// The linear part (upper left 3x3) of a row-major 4x4 matrix.
void LinearPart(const double matrix[4][4], double linear[3][3])
{
  for (int i = 0; i < 3; ++i)
  {
    std::copy_n(matrix[i], 3, linear[i]);
  }
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

// Where the corners of the bounding box fall in clip space. A corner beyond the near plane (or
// behind the eye) has clip z < -w; the box is convex, so without such a corner no cell reaches
// there. In front of the near plane, the projections of the corners bound those of every point
// in the box.
struct BoundsInClipSpace
{
  bool NearCut = false;                // some corner lies beyond the near plane or behind the eye
  double NearestW = VTK_DOUBLE_MAX;    // the smallest clip w of the corners
  double LargestNDC[2] = { 0.0, 0.0 }; // the largest |x / w| and |y / w| of the corners
  // The smallest and largest x / w and y / w of the corners: xmin, xmax, ymin, ymax.
  double NDC[4] = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
  // The smallest and largest -z of the corners in view coordinates (in front of the eye > 0).
  double Depth[2] = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
};

BoundsInClipSpace ProjectBounds(
  const double bounds[6], const double modelToView[4][4], const double viewToClip[4][4])
{
  BoundsInClipSpace result;
  for (int corner = 0; corner < 8; ++corner)
  {
    const double point[4] = { bounds[corner & 1], bounds[2 + ((corner >> 1) & 1)],
      bounds[4 + ((corner >> 2) & 1)], 1.0 };
    double view[4], clip[4];
    vtkMatrix4x4::MultiplyPoint(&modelToView[0][0], point, view);
    vtkMatrix4x4::MultiplyPoint(&viewToClip[0][0], view, clip);
    result.Depth[0] = std::min(result.Depth[0], -view[2]);
    result.Depth[1] = std::max(result.Depth[1], -view[2]);
    const bool nearCut = !(clip[2] >= -clip[3] && clip[3] > 0.0);
    result.NearCut = result.NearCut || nearCut;
    result.NearestW = std::min(result.NearestW, clip[3]);
    for (int i = 0; i < 2 && !nearCut; ++i)
    {
      const double ndc = clip[i] / clip[3];
      result.LargestNDC[i] = std::max(result.LargestNDC[i], std::abs(ndc));
      result.NDC[2 * i] = std::min(result.NDC[2 * i], ndc);
      result.NDC[2 * i + 1] = std::max(result.NDC[2 * i + 1], ndc);
    }
  }
  return result;
}

// For points a and b in front of the near plane, with |x / w| <= m at b:
// |x_a / w_a - x_b / w_b| <= (|x_a - x_b| + m |w_a - w_b|) / min(w_a, w_b), and the clip
// differences are at most the rows' norms times the view distance |a - b|, itself at most the
// largest stretch of model -> view times the model distance. The typical extent is that of a
// segment across the view at the depth of the bounds' centre.
void ScreenLengths(const BoundsInClipSpace& box, const double bounds[6],
  const vtkVolumeViewMatrices& m, double bound[2], double typical[2])
{
  bound[0] = bound[1] = typical[0] = typical[1] = 0.0;
  if (box.NearCut || !(box.NearestW > 0.0))
  {
    return;
  }
  const double stretch = vtkVolumeViewMatrices::LargestSingularValue(m.ModelToViewLinear);
  const double center[3] = { 0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]),
    0.5 * (bounds[4] + bounds[5]) };
  double centerW = m.ViewToClip[3][3];
  for (int j = 0; j < 3; ++j)
  {
    const double view = vtkMath::Dot(m.ModelToView[j], center) + m.ModelToView[j][3];
    centerW += m.ViewToClip[3][j] * view;
  }
  centerW = std::max(centerW, box.NearestW);
  const double wRow = vtkMath::Norm(m.ViewToClip[3]);
  for (int i = 0; i < 2; ++i)
  {
    const double row = vtkMath::Norm(m.ViewToClip[i]);
    bound[i] = stretch * (row + box.LargestNDC[i] * wRow) / box.NearestW;
    typical[i] = stretch * row / centerW;
  }
}
}

double vtkVolumeViewMatrices::LargestSingularValue(const double matrix[3][3])
{
  double u[3][3], w[3], vt[3][3];
  vtkMath::SingularValueDecomposition3x3(matrix, u, w, vt);
  return std::max({ std::abs(w[0]), std::abs(w[1]), std::abs(w[2]) });
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
  double modelLinear[3][3];
  LinearPart(model->Element, modelLinear);
  const double modelScale = LargestSingularValue(modelLinear);
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
  ToColumnMajor(modelToView->GetData(), 4, this->MCVC);
  ToColumnMajor(viewToClip->GetData(), 4, this->VCDC);
  ToColumnMajor(clipToView->GetData(), 4, this->DCVC);
  vtkMatrix4x4::DeepCopy(&this->ModelToView[0][0], modelToView);
  vtkMatrix4x4::DeepCopy(&this->ViewToClip[0][0], viewToClip);
  LinearPart(this->ModelToView, this->ModelToViewLinear);

  this->Mirrored = vtkMath::Determinant3x3(this->ModelToViewLinear) < 0.0;
  const double* bounds = mesh->GetNormalizedBounds();
  const BoundsInClipSpace box = ProjectBounds(bounds, this->ModelToView, this->ViewToClip);
  this->NearPlaneCutsBounds = box.NearCut;
  for (int i = 0; i < 4; ++i)
  {
    // The whole view where the near plane cuts the box: its corners bound nothing then.
    const double whole = (i % 2 == 0) ? -1.0 : 1.0;
    this->ScreenBounds[i] = box.NearCut ? whole : std::max(-1.0, std::min(1.0, box.NDC[i]));
  }
  ScreenLengths(box, bounds, *this, this->NDCPerLength, this->TypicalNDCPerLength);
  for (int side = 0; side < 2; ++side)
  {
    this->BoundsDistance[side] = box.Depth[side] * this->ViewScale;
    const double ndc[4] = { 0.0, 0.0, side == 0 ? -1.0 : 1.0, 1.0 };
    double view[4];
    clipToView->MultiplyPoint(ndc, view);
    this->ClippingDistance[side] = view[3] != 0.0 ? -view[2] / view[3] * this->ViewScale : 0.0;
  }
  vtkMath::Invert3x3(this->ModelToViewLinear, this->ViewToModelLinear);
  ToColumnMajor(&this->ViewToModelLinear[0][0], 3, this->VCMCLinear);
}

bool vtkVolumeViewMatrices::ComputeClippingPlanes(vtkRenderer* ren, vtkPlaneCollection* planes)
{
  const int count = planes ? planes->GetNumberOfItems() : 0;
  if (count > MaximumClippingPlanes)
  {
    return false;
  }
  // A plane p of world coordinates is (view -> world)^T p in view coordinates, and the
  // normalized view scales view coordinates by 1 / ViewScale.
  vtkNew<vtkMatrix4x4> planeToView;
  vtkMatrix4x4::Invert(ren->GetActiveCamera()->GetModelViewTransformMatrix(), planeToView);
  planeToView->Transpose();
  this->ClippingPlaneCount = 0;
  for (int i = 0; i < count; ++i)
  {
    vtkPlane* plane = planes->GetItem(i);
    double normal[3], origin[3];
    plane->GetNormal(normal);
    plane->GetOrigin(origin);
    const double world[4] = { normal[0], normal[1], normal[2], -vtkMath::Dot(normal, origin) };
    double view[4];
    planeToView->MultiplyPoint(world, view);
    for (int j = 0; j < 3; ++j)
    {
      view[j] *= this->ViewScale;
    }
    const double length = vtkMath::Norm(view);             // of the normal
    const double unit = length > 0.0 ? 1.0 / length : 0.0; // a zero normal keeps everything
    for (int j = 0; j < 4; ++j)
    {
      this->ClippingPlanes[i][j] = static_cast<float>(view[j] * unit);
    }
    ++this->ClippingPlaneCount;
  }
  return true;
}

void vtkVolumeViewMatrices::SetClippingPlaneUniforms(vtkShaderProgram* program) const
{
  if (program->IsUniformUsed("clippingPlanes"))
  {
    program->SetUniform4fv("clippingPlanes", MaximumClippingPlanes, this->ClippingPlanes);
  }
  if (program->IsUniformUsed("clippingPlaneCount"))
  {
    program->SetUniformi("clippingPlaneCount", this->ClippingPlaneCount);
  }
}

std::string vtkVolumeViewMatrices::ClippingPlaneDefine(const std::string& prefix) const
{
  return this->ClippingPlaneCount > 0 ? "#define " + prefix + "_CLIPPING_PLANES\n" : "";
}

void vtkVolumeViewMatrices::AppendSignature(std::vector<double>& signature) const
{
  signature.insert(signature.end(), this->MCVC, this->MCVC + 16);
  signature.insert(signature.end(), this->VCDC, this->VCDC + 16);
  signature.push_back(this->ClippingPlaneCount);
  signature.insert(signature.end(), this->ClippingPlanes[0],
    this->ClippingPlanes[0] + 4 * this->ClippingPlaneCount);
}

void vtkVolumeViewMatrices::SetUniforms(vtkShaderProgram* program) const
{
  program->SetUniformMatrix4x4("MCVCMatrix", const_cast<float*>(this->MCVC));
  program->SetUniformMatrix4x4("VCDCMatrix", const_cast<float*>(this->VCDC));
  program->SetUniformMatrix3x3("VCMCLinear", const_cast<float*>(this->VCMCLinear));
  this->SetClippingPlaneUniforms(program);
}
