#include "vtkStochasticVolumeMapper.h"

#include "vtkAbstractVolumeMapper.h"
#include "vtkDataSet.h"
#include "vtkNew.h"
#include "vtkPropCollection.h"
#include "vtkRenderer.h"
#include "vtkSPTOpenGL.h"
#include "vtkTimerLog.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include "vtkEnsembleBuffer.h"
#include "vtkGPUFrameTimer.h"

#include <algorithm>

namespace
{
// When the prop last changed in a way that changes what it draws. vtkVolume::GetRedrawMTime()
// of VTK 9.2 dereferences a null transfer function for point scalars of more than four
// components (it asks the property for one per component), so volumes are handled here.
vtkMTimeType RedrawTime(vtkProp* prop)
{
  vtkVolume* volume = vtkVolume::SafeDownCast(prop);
  if (!volume)
  {
    return prop->GetRedrawMTime();
  }
  vtkMTimeType time = volume->GetMTime();
  if (vtkVolumeProperty* property = volume->GetProperty())
  {
    time = std::max(time, property->GetMTime()); // includes its transfer functions
  }
  if (vtkAbstractVolumeMapper* mapper = volume->GetMapper())
  {
    time = std::max(time, mapper->GetMTime());
    if (vtkDataSet* input = mapper->GetDataSetInput())
    {
      time = std::max(time, input->GetMTime());
    }
  }
  return time;
}

// The time budget (AutoAdjustRepetitions). A traversal that draws several repetitions costs
// little more than one that draws one (llvmpipe, 48,000 tetrahedra at 200 x 200: 1 repetition
// 0.58 s, 16 repetitions 1.5 s), so cutting a group short saves little: the budget is spent in
// whole groups, and when not even one group fits, in single-repetition passes, the cheapest
// frame there is (0.36 s there), as many as fit and at least one.
struct RepetitionBudget
{
  double TimePerGroup = 0.0;      // seconds per traversal group of several repetitions
  double TimePerSinglePass = 0.0; // seconds per repetition drawn one per traversal

  // How many repetitions to draw, and how many per traversal (perPass may drop to 1).
  int Choose(double allotted, int level, int& perPass) const
  {
    int most = level;
    if (perPass > 1)
    {
      const int groups = (level + perPass - 1) / perPass;
      if (this->TimePerGroup <= 0.0 || allotted >= groups * this->TimePerGroup)
      {
        return level;
      }
      if (allotted >= this->TimePerGroup)
      {
        return std::min(level, static_cast<int>(allotted / this->TimePerGroup) * perPass);
      }
      most = std::min(level, perPass);
      perPass = 1;
      if (this->TimePerSinglePass <= 0.0)
      {
        return 1; // measured by this frame
      }
    }
    if (this->TimePerSinglePass <= 0.0 || allotted >= most * this->TimePerSinglePass)
    {
      return most;
    }
    return std::max(1, static_cast<int>(allotted / this->TimePerSinglePass));
  }

  void Measure(double seconds, int count, int perPass)
  {
    if (perPass > 1)
    {
      this->TimePerGroup = seconds / ((count + perPass - 1) / perPass);
    }
    else
    {
      this->TimePerSinglePass = seconds / count;
    }
  }
};
}

class vtkStochasticVolumeMapper::vtkSchedule
{
public:
  std::vector<double> Signature; // what the accumulated image was drawn from
  int Accumulated = 0;           // repetitions in it
  RepetitionBudget Budget;
  vtkGPUFrameTimer Timer;
  vtkNew<vtkTimerLog> Clock;
  bool Timed = false; // by the GPU timer
};

vtkStochasticVolumeMapper::vtkStochasticVolumeMapper()
  : Ensemble(vtkSmartPointer<vtkEnsembleBuffer>::New())
  , Schedule(new vtkSchedule)
{
}

vtkStochasticVolumeMapper::~vtkStochasticVolumeMapper() = default;

vtkEnsembleBuffer* vtkStochasticVolumeMapper::GetEnsemble() const
{
  return this->Ensemble;
}

int vtkStochasticVolumeMapper::ChooseRepetitions(vtkVolume* vol, int level, int& perPass) const
{
  return this->AutoAdjustRepetitions
    ? this->Schedule->Budget.Choose(vol->GetAllocatedRenderTime(), level, perPass)
    : level;
}

int vtkStochasticVolumeMapper::ContinueAccumulation(std::vector<double> signature, int& count)
{
  vtkSchedule& schedule = *this->Schedule;
  int first = 0;
  if (this->ProgressiveRefinement && signature == schedule.Signature && schedule.Accumulated > 0)
  {
    first = schedule.Accumulated;
    count = std::min(count, this->MaximumProgressiveRepetitions - first);
  }
  schedule.Signature = std::move(signature);
  return first;
}

void vtkStochasticVolumeMapper::ResetAccumulation()
{
  this->Schedule->Accumulated = 0;
}

void vtkStochasticVolumeMapper::ForgetAccumulation()
{
  this->Schedule->Accumulated = 0;
  this->Schedule->Signature.clear();
}

int vtkStochasticVolumeMapper::GetAccumulatedRepetitions() const
{
  return this->Schedule->Accumulated;
}

void vtkStochasticVolumeMapper::AppendSceneSignature(
  vtkRenderer* ren, const int viewport[4], std::vector<double>& signature)
{
  signature.insert(signature.end(), viewport, viewport + 4);
  vtkMTimeType redraw = 0;
  vtkPropCollection* props = ren->GetViewProps();
  vtkCollectionSimpleIterator it;
  props->InitTraversal(it);
  while (vtkProp* prop = props->GetNextProp(it))
  {
    redraw = std::max(redraw, prop->GetVisibility() ? RedrawTime(prop) : 0);
  }
  signature.push_back(double(redraw));
}

void vtkStochasticVolumeMapper::StartTiming()
{
  vtkSchedule& schedule = *this->Schedule;
  schedule.Timed = this->AutoAdjustRepetitions && schedule.Timer.Start();
  schedule.Clock->StartTimer();
}

double vtkStochasticVolumeMapper::StopTiming()
{
  vtkSchedule& schedule = *this->Schedule;
  if (schedule.Timed)
  {
    schedule.Timed = false;
    return schedule.Timer.Stop();
  }
  if (!this->AutoAdjustRepetitions)
  {
    return -1.0;
  }
  glFinish();
  schedule.Clock->StopTimer();
  return schedule.Clock->GetElapsedTime();
}

void vtkStochasticVolumeMapper::AddRepetitions(int drawn, int perPass, double seconds)
{
  vtkSchedule& schedule = *this->Schedule;
  if (seconds >= 0.0 && drawn > 0)
  {
    this->TimePerRepetition = seconds / drawn;
    schedule.Budget.Measure(seconds, drawn, perPass);
  }
  schedule.Accumulated += drawn;
  this->LastRepetitionCount = schedule.Accumulated;
}

void vtkStochasticVolumeMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Ensemble->ReleaseGraphicsResources(window);
  vtkSchedule& schedule = *this->Schedule;
  schedule.Signature.clear();
  schedule.Accumulated = 0;
  schedule.Budget = RepetitionBudget();
  schedule.Timer.Release(window != nullptr);
  this->Superclass::ReleaseGraphicsResources(window);
}

void vtkStochasticVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RepetitionLevel: " << this->RepetitionLevel << "\n";
  os << indent << "SubpixelLevel: " << this->SubpixelLevel << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "ProgressiveRefinement: " << (this->ProgressiveRefinement ? "On" : "Off") << "\n";
  os << indent << "MaximumProgressiveRepetitions: " << this->MaximumProgressiveRepetitions << "\n";
  os << indent << "AutoAdjustRepetitions: " << (this->AutoAdjustRepetitions ? "On" : "Off") << "\n";
  os << indent << "LastRepetitionCount: " << this->LastRepetitionCount << "\n";
  os << indent << "TimePerRepetition: " << this->TimePerRepetition << "\n";
}
