// The programs of an SPT frame and their uniforms: which shaders a pass kind and a volume's
// kind of cells compile from, with which defines (vtkSPTFrame.h).
#include "vtkSPTFrame.h"

#include "vtkObject.h"
#include "vtkOpenGLLoader.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

#include "vtkEnsembleBuffer.h"
#include "vtkPreIntegrationTable.h"
#include "vtkSPTComputeTraversal.h"
#include "vtkSPTDepthKeyBuffer.h"
#include "vtkSPTMeshBuffers.h"
#include "vtkTetrahedralMesh.h"
#include "vtkVolumeViewMatrices.h"

#include "vtkHashRandom.h"
#include "vtkSPTDepthSlabs.h"
#include "vtkSPTFacePlane.h"
#include "vtkSPTPassColorsFS.h"
#include "vtkSPTPassCoverageFS.h"
#include "vtkSPTPassDepthColorsFS.h"
#include "vtkSPTPassKeysFS.h"
#include "vtkSPTPassSingleFS.h"
#include "vtkSPTPointCell.h"
#include "vtkSPTTetrahedraCS.h"
#include "vtkSPTTetrahedraFS.h"
#include "vtkSPTTetrahedraGS.h"
#include "vtkSPTTetrahedraPointsVS.h"
#include "vtkSPTTetrahedraVS.h"

#include <algorithm>
#include <climits>
#include <string>

namespace
{
// A slab whose optical depth reaches this hides what lies behind it to within float precision
// (exp(-40) = 4e-18): it adds no more.
constexpr int SlabDepthCap = 40;
}

std::string vtkSPTFrame::SlabDefines(PassKind kind) const
{
  const bool groups =
    kind == PassKind::Keys || kind == PassKind::KeysAndCoverage || kind == PassKind::Colors;
  if (!groups || this->FrameSettings.DepthSlabs <= 1)
  {
    return "";
  }
  return "#define SPT_DEPTH_SLABS " + std::to_string(this->FrameSettings.DepthSlabs) +
    "\n#define SPT_SLAB_FIXED_ONE " + std::to_string(vtkSPTDepthKeyBuffer::GetSlabFixedOne()) +
    "u\n#define SPT_SLAB_DEPTH_CAP " + std::to_string(SlabDepthCap) + "u\n#define SPT_SLAB_TERMS " +
    std::to_string(vtkSPTDepthKeyBuffer::SlabTerms) + "\n";
}

vtkShaderProgram*& vtkSPTFrame::ProgramOf(PassKind kind, size_t volume, bool points)
{
  const bool cellScalars = this->Volumes[volume].Buffers->GetMesh()->GetCellScalars();
  return this->Programs[static_cast<int>(kind)][cellScalars ? 1 : 0][points ? 1 : 0];
}

std::string vtkSPTFrame::PassDefines(
  PassKind kind, bool cellScalars, int passRepetitions, bool halves) const
{
  // The scene depth only when opaque geometry was drawn; the segments are cut by the clipping
  // planes (and the cells wholly cut away are skipped) only where some volume has them.
  std::string defines = cellScalars ? "#define SPT_CELL_SCALARS\n" : "";
  defines += this->FrameSettings.OpaqueScene ? "#define SPT_SCENE_DEPTH\n" : "";
  defines += this->FrameSettings.GlobalIds ? "#define SPT_GLOBAL_IDS\n" : "";
  defines += this->ClippingPlanes ? "#define SPT_CLIPPING_PLANES\n" : "";
  defines += this->SlabDefines(kind) + "#define SPT_REPETITIONS_PER_PASS " +
    std::to_string(passRepetitions) + "\n";
  const bool coverage =
    kind == PassKind::KeysAndCoverage || kind == PassKind::DepthColorsAndCoverage;
  defines += coverage ? "#define SPT_WRITE_COVERAGE\n" : "";
  const bool weighted = kind == PassKind::Colors && this->FrameSettings.VisibilityEstimator;
  defines += weighted ? "#define SPT_VISIBILITY_WEIGHTED\n" : "";
  // A second output only where one is bound.
  defines += kind == PassKind::Colors && halves ? "#define ENSEMBLE_SECOND_HALF\n" : "";
  return defines;
}

namespace
{
// `defines` and the parts the shaders share, substituted into `source`.
void SubstituteShared(std::string& source, const std::string& defines)
{
  vtkShaderProgram::Substitute(source, "//Volume::Defines::Dec", defines);
  vtkShaderProgram::Substitute(source, "//Volume::Random::Impl", vtkHashRandom);
  vtkShaderProgram::Substitute(source, "//SPT::Slabs::Impl", vtkSPTDepthSlabs);
  vtkShaderProgram::Substitute(source, "//SPT::FacePlane::Impl", vtkSPTFacePlane);
  vtkShaderProgram::Substitute(source, "//SPT::PointCell::Impl", vtkSPTPointCell);
}
}

vtkShaderProgram* vtkSPTFrame::ReadyProgram(
  bool cellScalars, bool clippedCells, bool points, PassKind kind, int passRepetitions, bool halves)
{
  const char* const passes[NumberOfPassKinds] = { vtkSPTPassSingleFS, vtkSPTPassKeysFS,
    vtkSPTPassKeysFS, vtkSPTPassColorsFS, vtkSPTPassCoverageFS, vtkSPTPassDepthColorsFS,
    vtkSPTPassDepthColorsFS };
  // The path for cells that a clipping plane cuts is compiled in only while one cuts some
  // volume's bounds: a fragment stage pays for its branches.
  const std::string defines = this->PassDefines(kind, cellScalars, passRepetitions, halves) +
    (clippedCells && !points ? "#define SPT_CLIPPED_CELLS\n" : "");
  std::string vertex = points ? vtkSPTTetrahedraPointsVS : vtkSPTTetrahedraVS;
  std::string geometry = points ? "" : vtkSPTTetrahedraGS;
  // VTK declares GLSL 1.50; image load/store comes as the extension, and the slabs' controls
  // are kept as float bits in an integer image.
  const bool atomics =
    kind == PassKind::Keys || kind == PassKind::KeysAndCoverage || kind == PassKind::Colors;
  const std::string slabs =
    this->SlabDefines(kind).empty() ? "" : "\n#extension GL_ARB_shader_bit_encoding : require";
  std::string fragment = vtkSPTTetrahedraFS;
  vtkShaderProgram::Substitute(fragment, "//SPT::Extensions::Dec",
    atomics ? "#extension GL_ARB_shader_image_load_store : require" + slabs : "");
  vtkShaderProgram::Substitute(fragment, "//SPT::Pass::Impl", passes[static_cast<int>(kind)]);
  for (std::string* source : { &vertex, &geometry, &fragment })
  {
    SubstituteShared(*source, defines);
  }
  return this->Window->GetShaderCache()->ReadyShaderProgram(
    vertex.c_str(), fragment.c_str(), geometry.c_str());
}

vtkShaderProgram* vtkSPTFrame::ReadyComputeProgram(
  bool cellScalars, PassKind kind, int passRepetitions, bool halves)
{
  // The pass's fragment code, with the cell's planes and the sample's position set by the
  // compute pass's main() (vtkSPTTetrahedraCS.glsl) instead of read from the points.
  const bool colors = kind == PassKind::Colors;
  const std::string defines = this->PassDefines(kind, cellScalars, passRepetitions, halves) +
    (colors ? "#define SPT_COMPUTE_COLORS\n" : "") + "#define SPT_COMPUTE_GROUP_SIZE " +
    std::to_string(vtkSPTComputeTraversal::GroupSize) + "\n#define SPT_FIXED_ONE " +
    std::to_string(vtkSPTComputeTraversal::FixedPointOne);
  std::string source = vtkSPTTetrahedraFS;
  vtkShaderProgram::Substitute(source, "//VTK::System::Dec", "#version 430\n#define SPT_COMPUTE");
  vtkShaderProgram::Substitute(source, "//SPT::Extensions::Dec", "");
  vtkShaderProgram::Substitute(source, "//VTK::Output::Dec", "");
  vtkShaderProgram::Substitute(source, "//SPT::Pass::Impl",
    std::string(colors ? vtkSPTPassColorsFS : vtkSPTPassKeysFS) + vtkSPTTetrahedraCS);
  SubstituteShared(source, defines);
  return this->FrameSettings.Compute->GetProgram(this->Window, source);
}

bool vtkSPTFrame::ReadyPrograms(
  const bool (&needed)[NumberOfPassKinds], int passRepetitions, int first, int count, bool halves)
{
  // Each call has uniforms of its own (first, count, halves).
  std::fill_n(&this->Programs[0][0][0], NumberOfPassKinds * 2 * 2, nullptr);
  std::fill_n(&this->ComputePrograms[0][0], NumberOfPassKinds * 2, nullptr);
  for (int k = 0; k < NumberOfPassKinds; ++k)
  {
    for (size_t v = 0; v < this->Volumes.size(); ++v)
    {
      const PassKind kind = static_cast<PassKind>(k);
      const bool cellScalars = this->Volumes[v].Buffers->GetMesh()->GetCellScalars();
      if (needed[k] && this->Computes(kind, v) && !this->ComputePrograms[k][cellScalars ? 1 : 0])
      {
        vtkShaderProgram* program =
          this->ReadyComputeProgram(cellScalars, kind, passRepetitions, halves);
        if (!program)
        {
          // The traversal warned and will not be asked again in this context. The rasterizer
          // takes its cells from this group on (the same estimate: the sums differ by the fixed
          // point's rounding), so every program is chosen again.
          this->ComputeCellCounts.assign(this->Volumes.size(), 0);
          return this->ReadyPrograms(needed, passRepetitions, first, count, halves);
        }
        this->ComputePrograms[k][cellScalars ? 1 : 0] = program;
        vtkSPTComputeTraversal::Use(this->Window, program);
        this->SetFrameUniforms(program, first, count, halves);
        program->SetUniformi("sums", SumsImageUnit);
      }
      for (const bool points : { false, true })
      {
        vtkShaderProgram*& program = this->ProgramOf(kind, v, points);
        if (!needed[k] || !this->Rasterizes(kind, v, points) || program)
        {
          continue;
        }
        program = this->ReadyProgram(this->Volumes[v].Buffers->GetMesh()->GetCellScalars(),
          this->NearPlaneCuts, points, kind, passRepetitions, halves);
        if (!program)
        {
          vtkErrorWithObjectMacro(this->Reporter, "Could not compile the SPT shaders.");
          return false;
        }
        this->SetFrameUniforms(program, first, count, halves);
      }
    }
  }
  return true;
}

void vtkSPTFrame::SetFrameUniforms(
  vtkShaderProgram* program, int first, int count, bool halves) const
{
  vtkEnsembleBuffer* ensemble = this->Ensemble;
  const float passSize[2] = { float(ensemble->GetPassWidth()), float(ensemble->GetPassHeight()) };
  program->SetUniformi("sceneDepthTexture", ensemble->GetSceneDepthTexture()->GetTextureUnit());
  program->SetUniformi("subpixelLevel", this->FrameSettings.SubpixelLevel);
  program->SetUniform2f("passSizeInPixels", passSize);
  float pixelScale[2];
  ensemble->GetPixelScale(pixelScale);
  program->SetUniform2f("pixelScale", pixelScale);
  program->SetUniformi("seed", static_cast<int>(this->FrameSettings.Seed));
  // Strata: the repetitions of this draw form one block (progressive renders add blocks),
  // or two, one per half, so that the halves stay independent.
  const int block = halves ? count / 2 : count;
  program->SetUniformi("stratumCount", this->FrameSettings.StratifiedSampling ? block : 0);
  program->SetUniformi("stratumOrigin", first);
  program->SetUniformi("secondHalfStart", halves ? first + block : INT_MAX);
  int bits = 0;
  while ((1 << bits) < block)
  {
    ++bits;
  }
  program->SetUniformi("stratumMask", (1 << bits) - 1);
  program->SetUniformi("stratumShift", std::max((bits + 1) / 2, 1));
  if (program->IsUniformUsed("depthKeys"))
  {
    program->SetUniformi("depthKeys", DepthKeyImageUnit);
  }
  if (program->IsUniformUsed("slabSums"))
  {
    program->SetUniformi("slabSums", SlabDepthsImageUnit);
  }
  if (program->IsUniformUsed("slabStartsLow"))
  {
    program->SetUniform4f("slabStartsLow", this->SlabStarts);
    program->SetUniform4f("slabStartsHigh", this->SlabStarts + 4);
  }
}

void vtkSPTFrame::SetVolumeUniforms(vtkShaderProgram* program, const Volume& volume)
{
  const vtkVolumeViewMatrices& matrices = *volume.Matrices;
  program->SetUniformMatrix4x4("MCVCMatrix", const_cast<float*>(matrices.MCVC));
  program->SetUniformMatrix4x4("VCDCMatrix", const_cast<float*>(matrices.VCDC));
  program->SetUniformMatrix4x4("DCVCMatrix", const_cast<float*>(matrices.DCVC));
  program->SetUniformMatrix3x3("VCMCLinear", const_cast<float*>(matrices.VCMCLinear));
  volume.Table->SetUniforms(program, volume.TableTexture, volume.MaxThickness);
  const int scalarUnit = volume.Buffers->GetScalarTexture()->GetTextureUnit();
  program->SetUniformi("scalars", scalarUnit);
  program->SetUniformi("cellScalars", scalarUnit);
  program->SetUniformi("points", volume.Buffers->GetPointTexture()->GetTextureUnit());
  program->SetUniformi("tetrahedra", volume.Buffers->GetTetrahedronTexture()->GetTextureUnit());
  program->SetUniformi("cellIdOffset", static_cast<int>(volume.CellIdOffset));
  const bool parallel = matrices.ParallelProjection;
  const float eyeVC[4] = { 0.0f, 0.0f, parallel ? 1.0f : 0.0f, parallel ? 0.0f : 1.0f };
  program->SetUniform4f("eyeVC", eyeVC);
  matrices.SetClippingPlaneUniforms(program);
}
