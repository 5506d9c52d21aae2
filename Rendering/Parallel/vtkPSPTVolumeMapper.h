/**
 * @class   vtkPSPTVolumeMapper
 * @brief   vtkSPTVolumeMapper across the MPI ranks of a parallel render
 *
 * Each rank draws its own piece of the data set as it is (any shape, interleaved, with
 * overlapping bounds), with no redistribution and no compositing in visibility order: the
 * ranks' depth keys are combined by a global minimum and their sums by a global sum, and rank
 * 0 resolves the image of the whole over its own scene, and marks the volume's pixels at the
 * near plane of its depth buffer, so that a depth compositor (ParaView's IceT) keeps them; the
 * other ranks draw nothing of the volume. Without a controller it is vtkSPTVolumeMapper.
 *
 * The random numbers follow the cells' global ids (the input's cell-data GlobalIds, which the
 * mapper uses with or without a controller whenever the input has them), so the image is that
 * of one process rendering the whole with the same seed. Every process must render every
 * frame, with the same settings, image size and scalars (an array of the same name and number
 * of components); otherwise rank 0 reports the first rank that differs and nothing is drawn.
 * TargetError, ProgressiveRefinement and AutoAdjustRepetitions apply as in one process: rank 0
 * estimates the noise of the whole image and every rank follows its estimate; the ranks
 * continue an accumulation only if all do, and draw the fewest repetitions any rank's time
 * budget allows. Every SPT volume of the renderer is combined. A renderer's frustum culler
 * would skip the render of a rank whose piece lies outside the view while the others wait for
 * it: remove it (renderer->GetCullers()->RemoveAllItems(), as ParaView's parallel rendering
 * does; a warning says so). Needs image load/store (OpenGL 4.4) on every process.
 *
 * This module overrides vtkSPTVolumeMapper in VTK's object factory: where it is loaded (the
 * Python package spt, the ParaView plugin, a program that initializes the module),
 * vtkSPTVolumeMapper::New() makes a vtkPSPTVolumeMapper.
 *
 * @sa
 * vtkSPTVolumeMapper vtkMultiProcessController
 */

#ifndef vtkPSPTVolumeMapper_h
#define vtkPSPTVolumeMapper_h

#include "SPTRenderingParallelModule.h" // For export macro
#include "vtkSPTVolumeMapper.h"

#include <memory> // For the internals

class vtkMultiProcessController;

class SPTRENDERINGPARALLEL_EXPORT vtkPSPTVolumeMapper : public vtkSPTVolumeMapper
{
public:
  static vtkPSPTVolumeMapper* New();
  vtkTypeMacro(vtkPSPTVolumeMapper, vtkSPTVolumeMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The processes of a parallel render, each with its own piece of the data set; null (the
  /// default): this process renders alone. Every process must render every frame with the
  /// same settings, image size and scalars; rank 0 shows the image of the whole.
  void SetController(vtkMultiProcessController* controller);
  vtkMultiProcessController* GetController();
  ///@}

protected:
  vtkPSPTVolumeMapper();
  ~vtkPSPTVolumeMapper() override;

  bool RenderAcrossRanks(vtkRenderer* ren, const SharedVolumeList& shared) override;

private:
  vtkPSPTVolumeMapper(const vtkPSPTVolumeMapper&) = delete;
  void operator=(const vtkPSPTVolumeMapper&) = delete;

  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif
