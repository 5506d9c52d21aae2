#include "vtkSPTVolumeMapper.h"
#include "vtkSPTVolumeMapperInternals.h"

#include "vtkAbstractVolumeMapper.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLLoader.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkPropCollection.h"
#include "vtkRenderer.h"
#include "vtkTextureObject.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include "vtkEnsembleBuffer.h"
#include "vtkPreIntegrationTable.h"
#include "vtkSPTDepthKeyBuffer.h"
#include "vtkSPTFrame.h"
#include "vtkSPTMeshBuffers.h"
#include "vtkSavedGLState.h"
#include "vtkTetrahedralMesh.h"
#include "vtkVolumeViewMatrices.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

vtkObjectFactoryNewMacro(vtkSPTVolumeMapper);

vtkSPTVolumeMapper::vtkSPTVolumeMapper()
  : Internals(new vtkInternals)
{
  // The random numbers follow the global cell ids where the input has them, so that any
  // split of a data set into pieces (ranks, or one process) draws the same image.
  this->GetMesh()->SetUseGlobalIds(true);
}

vtkSPTVolumeMapper::~vtkSPTVolumeMapper() = default;

vtkIdType vtkSPTVolumeMapper::GetGPUMemorySize()
{
  const vtkInternals& internals = *this->Internals;
  return static_cast<vtkIdType>(internals.Buffers->GetGPUMemorySize() +
    internals.Table->GetGPUMemorySize() + this->GetEnsemble()->GetGPUMemorySize() +
    internals.DepthKeys->GetGPUMemorySize() + internals.Compute->GetGPUMemorySize());
}

vtkSPTVolumeMapper::SharedVolumeList vtkSPTVolumeMapper::vtkInternals::SharedVolumes(
  vtkRenderer* ren, vtkVolume* vol, vtkSPTVolumeMapper* self, int& selfProps)
{
  SharedVolumeList visible;
  vtkPropCollection* props = ren->GetViewProps();
  vtkCollectionSimpleIterator it;
  props->InitTraversal(it);
  while (vtkProp* prop = props->GetNextProp(it))
  {
    vtkVolume* volume = vtkVolume::SafeDownCast(prop);
    auto* mapper = volume ? vtkSPTVolumeMapper::SafeDownCast(volume->GetMapper()) : nullptr;
    if (mapper && volume->GetVisibility() && volume->GetProperty())
    {
      visible.emplace_back(volume, mapper);
    }
  }
  // A mapper holds one mesh, one table and one set of matrices, so it stands for one volume
  // of a frame: a mapper that several props draw draws each of them in a frame of its own.
  const auto propsOf = [&visible](const vtkSPTVolumeMapper* mapper)
  {
    return static_cast<int>(std::count_if(visible.begin(), visible.end(),
      [mapper](const std::pair<vtkVolume*, vtkSPTVolumeMapper*>& v)
      { return v.second == mapper; }));
  };
  selfProps = propsOf(self);
  SharedVolumeList shared;
  bool listed = false;
  for (const auto& entry : visible)
  {
    // A prop may draw its mapper through a vtkVolume of its own (ParaView's vtkPVLODVolume
    // renders through its vtkLODProp3D's), with the prop's matrix and property: the volume
    // drawn stands for the prop of its mapper.
    const bool own = entry.first == vol || entry.second == self;
    if (selfProps <= 1 && propsOf(entry.second) == 1)
    {
      shared.emplace_back(own ? vol : entry.first, entry.second);
      listed = listed || own;
    }
  }
  if (!listed)
  {
    shared.assign(1, { vol, self }); // drawn outside the renderer's props, or by several: alone
  }
  return shared;
}

bool vtkSPTVolumeMapper::vtkInternals::PrepareVolume(vtkSPTVolumeMapper* mapper, vtkRenderer* ren,
  vtkVolume* vol, vtkOpenGLRenderWindow* window, vtkSPTFrame::Volume& out,
  const double* sharedBounds, const double* sharedRange, double sharedEdge)
{
  vtkInternals& internals = *mapper->Internals;
  // Input and transfer functions: rebuilt only when they changed.
  vtkTetrahedralMesh* mesh = mapper->GetMesh();
  mesh->SetSharedFrame(sharedBounds, sharedRange);
  if (!mapper->PrepareMesh(vol, true) || !mapper->ComputeMatrices(ren, vol, internals.Matrices))
  {
    return false;
  }
  // The longest edge in the data's units, and in the normalized mesh's (the table's thickness).
  const double maxThickness =
    sharedBounds ? sharedEdge / mesh->GetScale() : mesh->GetMaxEdgeLength();
  const double tableThickness = sharedBounds ? sharedEdge : maxThickness * mesh->GetScale();
  vtkPreIntegrationTable* table = internals.Table;
  if (!table->Update(vol->GetProperty(), mesh->GetScalarRange(), tableThickness,
        mapper->PreIntegrationScalarResolution, mapper->PreIntegrationThicknessResolution))
  {
    vtkErrorWithObjectMacro(mapper, << table->GetLastError());
    return false;
  }
  if (!internals.Buffers->Upload(window, mesh))
  {
    return false;
  }
  out.Buffers = internals.Buffers;
  out.Table = table;
  out.TableTexture = table->GetTexture(window);
  out.Matrices = &internals.Matrices;
  out.MaxThickness = maxThickness;
  return out.TableTexture != nullptr;
}

std::vector<double> vtkSPTVolumeMapper::vtkInternals::Signature(
  vtkRenderer* ren, const std::vector<vtkSPTVolumeMapper*>& mappers, const RenderTarget& target)
{
  // Everything that changes the expected image: each volume's matrices (camera, volume
  // transform) and clipping planes as they are now (a vtkPlane changed in place, as an
  // interactive widget changes it, changes them), input and table as built and mapper
  // settings, the viewport, and whatever any prop of the renderer would draw differently
  // (opaque geometry bounds the volume).
  std::vector<double> signature;
  for (vtkSPTVolumeMapper* mapper : mappers)
  {
    const vtkInternals& internals = *mapper->Internals;
    internals.Matrices.AppendSignature(signature);
    signature.push_back(double(mapper->GetMesh()->GetBuildTime()));
    signature.push_back(double(internals.Table->GetBuildTime()));
    signature.push_back(double(mapper->GetMTime()));
  }
  const int viewport[4] = { target.X, target.Y, target.Width, target.Height };
  AppendSceneSignature(ren, viewport, signature);
  signature.push_back(mappers.front()->GetEnsemble()->GetSampleDistance());
  return signature;
}

bool vtkSPTVolumeMapper::vtkInternals::CollectVolumes(vtkRenderer* ren,
  const SharedVolumeList& shared, RenderTarget& target, std::vector<vtkSPTFrame::Volume>& volumes,
  std::vector<vtkSPTVolumeMapper*>& mappers)
{
  unsigned int cellIds = 0;
  for (const auto& member : shared)
  {
    vtkSPTFrame::Volume volume;
    if (member.second->BeginFrame(ren, target) &&
      PrepareVolume(member.second, ren, member.first, target.Window, volume))
    {
      // The volumes' cells are numbered one after another, so that each has random numbers
      // of its own.
      volume.CellIdOffset = cellIds;
      cellIds += static_cast<unsigned int>(member.second->GetNumberOfTetrahedra());
      volumes.push_back(volume);
      mappers.push_back(member.second);
    }
  }
  return !volumes.empty();
}

bool vtkSPTVolumeMapper::vtkInternals::StartAccumulation(
  vtkSPTVolumeMapper* self, const RenderTarget& target, bool halves, bool sameImage)
{
  vtkEnsembleBuffer* ensemble = self->GetEnsemble();
  ensemble->CaptureSceneDepth(target.X, target.Y);
  self->ResetAccumulation();
  this->CoverageDrawn = false;
  this->Target.Restart(sameImage);
  if (!self->ReuseNoiseEstimate)
  {
    this->Target.NoisePerRepetition = -1.0; // every image starts alike
  }
  if (!ensemble->SetHalves(halves))
  {
    self->ForgetAccumulation();
    return false;
  }
  ensemble->ClearSum();
  return true;
}

double vtkSPTVolumeMapper::vtkInternals::RoundingError() const
{
  // Rounding to b bits spreads a value's error evenly over one level, 1 / (2^b - 1): its root
  // mean square is a level over sqrt(12) (0.00113 for 8 bits, what an exact image read back
  // through 8 bits is off by).
  return this->ColorBits > 0 ? 1.0 / ((std::ldexp(1.0, this->ColorBits) - 1.0) * std::sqrt(12.0))
                             : 0.0;
}

double vtkSPTVolumeMapper::vtkInternals::NoiseTarget(vtkSPTVolumeMapper* self)
{
  // The image shown is the rounded one: its error is the noise and the rounding, independent,
  // so the noise may have what the rounding leaves of the target.
  const double rounding = this->RoundingError();
  const double left = self->TargetError * self->TargetError - rounding * rounding;
  const bool reachable = left > 0.0;
  if (!reachable && !this->WarnedTargetBelowRounding)
  {
    vtkWarningWithObjectMacro(self,
      "TargetError " << self->TargetError << " is not above the error of rounding the image to "
                     << this->ColorBits << " bits per channel (" << rounding
                     << "): no noise meets it, so every image draws RepetitionLevel repetitions.");
  }
  this->WarnedTargetBelowRounding = !reachable;
  return reachable ? std::sqrt(left) : 0.0;
}

double vtkSPTVolumeMapper::vtkInternals::ImageError(vtkSPTVolumeMapper* self) const
{
  if (self->TargetError <= 0.0 || this->Target.Estimate < 0.0)
  {
    return -1.0;
  }
  const double rounding = this->RoundingError();
  return std::sqrt(this->Target.Estimate * this->Target.Estimate + rounding * rounding);
}

void vtkSPTVolumeMapper::vtkInternals::Report(vtkSPTVolumeMapper* self,
  const std::vector<vtkSPTVolumeMapper*>& all, const std::vector<vtkSPTVolumeMapper*>& owners,
  const vtkSPTFrame& frame, vtkIdType parallelBytes) const
{
  vtkSPTFrameStatistics::Values values;
  values.RepetitionCount = self->GetAccumulatedRepetitions();
  values.FewestRepetitionCount =
    std::max(0, values.RepetitionCount - self->GetEnsemble()->GetTiles().GetMostMissed());
  values.EstimatedError = this->ImageError(self);
  values.DepthSlabs = frame.GetDepthSlabs();
  values.ParallelBytes = parallelBytes;
  for (vtkSPTVolumeMapper* mapper : all)
  {
    mapper->EstimatedError = values.EstimatedError;
    mapper->LastRepetitionCount = values.RepetitionCount;
    const auto owner = std::find(owners.begin(), owners.end(), mapper);
    const size_t v = static_cast<size_t>(owner - owners.begin());
    values.PointCellCount = owner != owners.end() ? frame.GetPointCellCount(v) : 0;
    values.ComputedCellCount = owner != owners.end() ? frame.GetComputedCellCount(v) : 0;
    mapper->FrameStatistics->Record(values);
  }
}

bool vtkSPTVolumeMapper::vtkInternals::DrawTimed(
  vtkSPTVolumeMapper* self, vtkSPTFrame& frame, const FramePlan& plan)
{
  self->StartTiming();
  int drawn = 0;
  if (plan.Count > 0 && self->TargetError > 0.0)
  {
    drawn = frame.DrawToTarget(plan.First, plan.Count, plan.PerPass, plan.Coverage,
      self->ExactCoverage && (this->CoverageDrawn || plan.Coverage), this->NoiseTarget(self),
      this->Target);
  }
  else if (plan.Count > 0)
  {
    drawn =
      frame.DrawRepetitions(plan.First, plan.Count, plan.PerPass, plan.Coverage) ? plan.Count : -1;
  }
  const bool ok = frame.Finish(drawn >= 0);
  const double seconds = self->StopTiming();
  if (!ok)
  {
    self->ForgetAccumulation();
    return false;
  }
  self->AddRepetitions(drawn, plan.PerPass, plan.Kind, seconds);
  this->CoverageDrawn = this->CoverageDrawn || (plan.Coverage && drawn > 0);
  return true;
}

void vtkSPTVolumeMapper::Render(vtkRenderer* ren, vtkVolume* vol)
{
  // Several SPT volumes in one renderer share one ensemble, so that their segments interleave
  // wherever they overlap: the first of them draws them all, with its own settings.
  int props = 0;
  const auto shared = vtkInternals::SharedVolumes(ren, vol, this, props);
  if (props > 1 && !this->Internals->WarnedSharedMapper)
  {
    vtkWarningMacro("This mapper is drawn by "
      << props
      << " volumes of one renderer: each is drawn in a frame of its own, composited over the "
         "image before it as VTK's other volume mappers do, and not interleaved with the "
         "others where they overlap. Give each volume its own vtkSPTVolumeMapper (they may "
         "share the input) to composite them exactly.");
  }
  this->Internals->WarnedSharedMapper = props > 1;
  const bool first = shared.front().second == this;
  if (first && this->RenderAcrossRanks(ren, shared))
  {
    return;
  }
  RenderTarget target;
  std::vector<vtkSPTFrame::Volume> volumes;
  std::vector<vtkSPTVolumeMapper*> mappers;
  if (!first || !vtkInternals::CollectVolumes(ren, shared, target, volumes, mappers))
  {
    return;
  }
  this->Internals->DrawFrame(this, ren, vol, target, volumes, mappers);
}

void vtkSPTVolumeMapper::vtkInternals::DrawFrame(vtkSPTVolumeMapper* self, vtkRenderer* ren,
  vtkVolume* vol, const RenderTarget& target, const std::vector<vtkSPTFrame::Volume>& volumes,
  const std::vector<vtkSPTVolumeMapper*>& mappers)
{
  vtkInternals& internals = *this;
  vtkOpenGLRenderWindow* renWin = target.Window;
  vtkOpenGLClearErrorMacro();
  vtkOpenGLState* ostate = renWin->GetState();
  vtkSavedGLState savedState(ostate);
  vtkEnsembleBuffer* ensemble = self->GetEnsemble();
  if (!ensemble->Prepare(
        renWin, target.Width, target.Height, self->SubpixelLevel, self->ChooseSampleDistance(vol)))
  {
    return;
  }
  internals.ColorBits = vtkOpenGLLoader::DrawColorBits(); // where the image will be resolved
  const bool globalIds = std::all_of(volumes.begin(), volumes.end(),
    [](const vtkSPTFrame::Volume& v) { return v.Buffers->GetRandomIdTexture() != nullptr; });
  vtkSPTFrame::Settings settings =
    internals.FrameSettings(self, renWin, HasOpaqueScene(ren), globalIds);
  const int perPass = internals.ChooseTraversal(self, renWin, settings);
  if (perPass < 1)
  {
    return;
  }
  const vtkInternals::FramePlan plan =
    internals.Plan(self, vol, perPass, vtkInternals::Signature(ren, mappers, target), settings);
  ostate->PushFramebufferBindings();
  const bool started = plan.First > 0 ||
    internals.StartAccumulation(self, target, self->TargetError > 0.0, plan.SameImage);
  vtkSPTFrame frame(renWin, ensemble, internals.DepthKeys, volumes, settings, self);
  const bool drawn = started && (plan.Count <= 0 || internals.DrawTimed(self, frame, plan));
  ostate->PopFramebufferBindings();
  if (!drawn)
  {
    return;
  }
  internals.Report(self, mappers, mappers, frame);
  ensemble->Resolve(target.X, target.Y, self->GetAccumulatedRepetitions(),
    self->ExactCoverage && internals.CoverageDrawn);
  vtkOpenGLCheckErrorMacro("failed after Render");
}

void vtkSPTVolumeMapper::SetSamplingToPaper()
{
  this->SetRepetitionsPerPass(1);
  this->SetEstimator(SURVIVOR_ESTIMATOR);
  this->SetStratifiedSampling(false);
  this->SetExactCoverage(false);
  this->SetDepthSlabs(1);
}

void vtkSPTVolumeMapper::SetSamplingToDefault()
{
  // The members' initial values.
  this->SetRepetitionsPerPass(256);
  this->SetEstimator(VISIBILITY_ESTIMATOR);
  this->SetStratifiedSampling(true);
  this->SetExactCoverage(true);
  this->SetDepthSlabs(1);
}

vtkSPTFrameStatistics* vtkSPTVolumeMapper::GetFrameStatistics()
{
  return this->FrameStatistics;
}

bool vtkSPTVolumeMapper::RenderAcrossRanks(vtkRenderer*, const SharedVolumeList&)
{
  return false;
}

void vtkSPTVolumeMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  vtkInternals& internals = *this->Internals;
  internals.Buffers->ReleaseGraphicsResources(window);
  internals.Table->ReleaseGraphicsResources(window);
  internals.DepthKeys->ReleaseGraphicsResources(window);
  internals.Compute->ReleaseGraphicsResources(window);
  internals.CoverageDrawn = false;
  internals.Target.Restart(false); // keeps the noise per repetition, which all ranks share
  this->Superclass::ReleaseGraphicsResources(window);
}

void vtkSPTVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RepetitionsPerPass: " << this->RepetitionsPerPass << "\n";
  os << indent << "SmallCellSize: " << this->SmallCellSize << "\n";
  const char* const computeModes[] = { "Off", "On", "Auto" };
  os << indent << "ComputeTraversal: " << computeModes[this->ComputeTraversal] << "\n";
  os << indent << "StratifiedSampling: " << (this->StratifiedSampling ? "On" : "Off") << "\n";
  os << indent << "ExactCoverage: " << (this->ExactCoverage ? "On" : "Off") << "\n";
  os << indent << "DepthSlabs: " << this->DepthSlabs << "\n";
  os << indent
     << "Estimator: " << (this->Estimator == SURVIVOR_ESTIMATOR ? "Survivor" : "Visibility")
     << "\n";
  os << indent << "TargetError: " << this->TargetError << "\n";
  os << indent << "ReuseNoiseEstimate: " << (this->ReuseNoiseEstimate ? "On" : "Off") << "\n";
  os << indent << "EstimatedError: " << this->EstimatedError << "\n";
  os << indent << "GPUMemorySize: " << this->GetGPUMemorySize() << "\n";
  os << indent << "FrameStatistics:\n";
  this->FrameStatistics->PrintSelf(os, indent.GetNextIndent());
}
