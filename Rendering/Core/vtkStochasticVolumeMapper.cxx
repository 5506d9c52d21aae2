#include "vtkStochasticVolumeMapper.h"

#include "vtkAbstractVolumeMapper.h"
#include "vtkDataSet.h"
#include "vtkNew.h"
#include "vtkOpenGLLoader.h"
#include "vtkPropCollection.h"
#include "vtkRenderer.h"
#include "vtkTimerLog.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include "vtkEnsembleBuffer.h"
#include "vtkGPUFrameTimer.h"

#include <algorithm>
#include <cmath>

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
}

class vtkStochasticVolumeMapper::vtkSchedule
{
public:
  // The time budget (AutoAdjustRepetitions). A traversal that draws several repetitions costs
  // little more than one that draws one (llvmpipe, 48,000 tetrahedra at 200 x 200: 1 repetition
  // 0.58 s, 16 repetitions 1.5 s), so cutting a group short saves little: the budget is spent in
  // whole groups. When not even one group fits, one repetition at a time: in pairs of traversals
  // where the mapper has them and one fits (SPT's visibility estimator, about two single passes,
  // with an error some 40 times smaller than a single pass's on SPX), else in single passes, the
  // cheapest frame there is (0.36 s there); as many as fit and at least one.
  struct RepetitionBudget
  {
    double TimePerGroup = 0.0;      // seconds per traversal group of several repetitions
    double TimePerPair = 0.0;       // seconds per repetition drawn one per pair of traversals
    double TimePerSinglePass = 0.0; // seconds per repetition drawn one per traversal

    // How many repetitions to draw, how many per traversal (perPass may drop to 1), and how.
    int Choose(double allotted, int level, int& perPass, Traversal& kind) const
    {
      int most = level;
      const bool belowGroups = perPass > 1;
      if (belowGroups)
      {
        const int groups = (level + perPass - 1) / perPass;
        if (this->TimePerGroup <= 0.0 || allotted >= groups * this->TimePerGroup)
        {
          kind = Traversal::Group;
          return level;
        }
        if (allotted >= this->TimePerGroup)
        {
          kind = Traversal::Group;
          return std::min(level, static_cast<int>(allotted / this->TimePerGroup) * perPass);
        }
        most = std::min(level, perPass);
        perPass = 1;
      }
      if (belowGroups && kind == Traversal::Pair && this->TimePerPair > 0.0 &&
        allotted < this->TimePerPair)
      {
        kind = Traversal::Single; // not even one pair fits
      }
      const double time = kind == Traversal::Pair ? this->TimePerPair : this->TimePerSinglePass;
      if (time <= 0.0 || allotted >= most * time)
      {
        return time <= 0.0 && belowGroups ? 1 : most; // not timed yet: timed by this frame
      }
      return std::max(1, static_cast<int>(allotted / time));
    }

    // The time of the best frame of one repetition measured, or 0 before one was: a pair of
    // traversals where the mapper draws them (far less noise than a single pass), else a
    // single pass.
    double OneRepetition() const
    {
      return this->TimePerPair > 0.0 ? this->TimePerPair : this->TimePerSinglePass;
    }

    // The times predicted when the image's pixels change by `factor`: a repetition's time is
    // mostly its fragments' (the next render measures it).
    void Scale(double factor)
    {
      this->TimePerGroup *= factor;
      this->TimePerPair *= factor;
      this->TimePerSinglePass *= factor;
    }

    void Measure(double seconds, int count, int perPass, Traversal kind)
    {
      if (kind == Traversal::Group)
      {
        this->TimePerGroup = seconds / ((count + perPass - 1) / perPass);
      }
      else if (kind == Traversal::Pair)
      {
        this->TimePerPair = seconds / count;
      }
      else
      {
        this->TimePerSinglePass = seconds / count;
      }
    }
  };

  std::vector<double> Signature; // what the accumulated image was drawn from
  int Accumulated = 0;           // repetitions in it
  RepetitionBudget Budget;
  vtkGPUFrameTimer Timer;
  vtkNew<vtkTimerLog> Clock;
  bool Timed = false;   // by the GPU timer
  bool Resized = false; // the image's sample distance changed for this render
};

vtkStochasticVolumeMapper::vtkStochasticVolumeMapper()
  : Schedule(new vtkSchedule)
{
}

vtkStochasticVolumeMapper::~vtkStochasticVolumeMapper() = default;

int vtkStochasticVolumeMapper::ChooseRepetitions(
  vtkVolume* vol, int level, int& perPass, Traversal& kind) const
{
  if (!this->AutoAdjustRepetitions)
  {
    kind = perPass > 1 ? Traversal::Group : kind;
    return level;
  }
  return this->Schedule->Budget.Choose(vol->GetAllocatedRenderTime(), level, perPass, kind);
}

double vtkStochasticVolumeMapper::ChooseSampleDistance(vtkVolume* vol)
{
  vtkSchedule::RepetitionBudget& budget = this->Schedule->Budget;
  const double current = this->ImageSampleDistance;
  if (!this->AutoAdjustSampleDistances)
  {
    return this->ImageSampleDistance;
  }
  if (!this->AutoAdjustRepetitions)
  {
    this->ImageSampleDistance = 1.0f; // no render is timed: every pixel
    return 1.0;
  }
  // Predicted at every pixel, one repetition takes the time measured at the current distance
  // times the pixels' ratio; the distance that fits the allotted time is its square root. A
  // coarser image of the best single repetition comes before a noisier way of drawing it.
  // Before one repetition was timed (the first interactive render after still ones, which
  // draw every pixel), a group of the still renders stands for it: it draws more, so that
  // first image is planned no finer than it can afford, not drawn at every pixel blind.
  const double atEveryPixel =
    budget.OneRepetition() > 0.0 ? budget.OneRepetition() * current * current : budget.TimePerGroup;
  const double allotted = vol->GetAllocatedRenderTime();
  double distance = 1.0;
  if (atEveryPixel > 0.0 && allotted > 0.0 && atEveryPixel > allotted)
  {
    distance =
      std::min(double(this->MaximumImageSampleDistance), std::sqrt(atEveryPixel / allotted));
    // Within a tenth of the current distance, keep it: the buffers are sized once.
    distance = std::abs(distance - current) < 0.1 * current ? current : distance;
  }
  if (distance != current)
  {
    // The next render sizes its buffers anew, which its time would count: it keeps the
    // predicted times, and the render after it measures. A group's time that stands for a
    // repetition's stays that of every pixel: scaled, it would let the coarser image draw
    // whole groups.
    if (budget.OneRepetition() > 0.0)
    {
      budget.Scale((current * current) / (distance * distance));
    }
    this->ImageSampleDistance = float(distance);
    this->Schedule->Resized = true;
  }
  return this->ImageSampleDistance;
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

bool vtkStochasticVolumeMapper::IsLastSignature(const std::vector<double>& signature) const
{
  return !signature.empty() && signature == this->Schedule->Signature;
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

void vtkStochasticVolumeMapper::AddRepetitions(
  int drawn, int perPass, Traversal kind, double seconds)
{
  vtkSchedule& schedule = *this->Schedule;
  if (seconds >= 0.0 && drawn > 0 && !schedule.Resized)
  {
    this->TimePerRepetition = seconds / drawn;
    schedule.Budget.Measure(seconds, drawn, perPass, kind);
  }
  schedule.Resized = false;
  schedule.Accumulated += drawn;
  this->LastRepetitionCount = schedule.Accumulated;
}

void vtkStochasticVolumeMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Ensemble->ReleaseGraphicsResources(window);
  this->ForgetAccumulation();
  this->Schedule->Budget = vtkSchedule::RepetitionBudget();
  this->Schedule->Timer.Release(window != nullptr);
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
  os << indent << "AutoAdjustSampleDistances: " << (this->AutoAdjustSampleDistances ? "On" : "Off")
     << "\n";
  os << indent << "ImageSampleDistance: " << this->ImageSampleDistance << "\n";
  os << indent << "MaximumImageSampleDistance: " << this->MaximumImageSampleDistance << "\n";
  os << indent << "LastRepetitionCount: " << this->LastRepetitionCount << "\n";
  os << indent << "TimePerRepetition: " << this->TimePerRepetition << "\n";
}
