/**
 * @class   vtkSPTFrameStatistics
 * @brief   what the last render of a vtkSPTVolumeMapper drew
 *
 * vtkSPTVolumeMapper::GetFrameStatistics() returns the mapper's own instance, which every
 * render updates: how many repetitions the image shown averages, its estimated error, how the
 * cells were drawn and what a parallel render exchanged. For benchmarks, tests and
 * interactive displays of progress; nothing in it changes how the mapper renders.
 *
 * @sa
 * vtkSPTVolumeMapper vtkPSPTVolumeMapper
 */

#ifndef vtkSPTFrameStatistics_h
#define vtkSPTFrameStatistics_h

#include "SPTRenderingSPTModule.h" // For export macro
#include "vtkObject.h"

class SPTRENDERINGSPT_EXPORT vtkSPTFrameStatistics : public vtkObject
{
public:
  static vtkSPTFrameStatistics* New();
  vtkTypeMacro(vtkSPTFrameStatistics, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// What a render records (by the mappers, through Record()).
  struct Values
  {
    int RepetitionCount = 0;
    int FewestRepetitionCount = 0;
    double EstimatedError = -1.0;
    int DepthSlabs = 1;
    vtkIdType PointCellCount = 0;
    vtkIdType ComputedCellCount = 0;
    vtkIdType ParallelBytes = 0;
  };

  /// Repetitions averaged into the image shown (all renders of a progressive image).
  int GetRepetitionCount() const { return this->Current.RepetitionCount; }
  /// The repetitions of the image's tiles that hold fewest: an error target stops drawing a
  /// tile once its own error meets the target. RepetitionCount where every tile holds them all.
  int GetFewestRepetitionCount() const { return this->Current.FewestRepetitionCount; }
  /// The image's estimated error (noise and rounding), its largest tile's; -1 without an error
  /// target or estimate.
  double GetEstimatedError() const { return this->Current.EstimatedError; }
  /// Depth slabs the last render drew.
  int GetDepthSlabs() const { return this->Current.DepthSlabs; }
  /// Tetrahedra of this mapper's input drawn as points (see SmallCellSize).
  vtkIdType GetPointCellCount() const { return this->Current.PointCellCount; }
  /// Tetrahedra of this mapper's input visited in compute passes (see ComputeTraversal).
  vtkIdType GetComputedCellCount() const { return this->Current.ComputedCellCount; }
  /// Bytes this process contributed to a parallel render's reductions; 0 in one process.
  vtkIdType GetParallelBytes() const { return this->Current.ParallelBytes; }

  /// All counts back to those of a mapper that has not rendered.
  void Reset();

#ifndef __VTK_WRAP__
  /// Record what a render drew.
  void Record(const Values& values);
#endif

protected:
  vtkSPTFrameStatistics() = default;
  ~vtkSPTFrameStatistics() override = default;

private:
  vtkSPTFrameStatistics(const vtkSPTFrameStatistics&) = delete;
  void operator=(const vtkSPTFrameStatistics&) = delete;

  Values Current;
};

#endif
