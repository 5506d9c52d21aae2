/**
 * @class   vtkStochasticVolumeMapper
 * @brief   abstract base of the module's stochastic (ensemble-averaged) volume mappers
 *
 * vtkStochasticVolumeMapper owns what vtkSPTVolumeMapper and vtkPBVRVolumeMapper share, after
 * KVS's StochasticRendererBase: the number of repetitions averaged into one image (the papers'
 * L_R), the subpixel level of each repetition (L_S), the seed of the random numbers, and the
 * ensemble buffer that the repetitions are summed in and resolved from.
 *
 * @sa
 * vtkTetrahedralVolumeMapper vtkSPTVolumeMapper vtkPBVRVolumeMapper
 */

#ifndef vtkStochasticVolumeMapper_h
#define vtkStochasticVolumeMapper_h

#include "SPTRenderingModule.h" // For export macro
#include "vtkSmartPointer.h"    // For the ensemble
#include "vtkTetrahedralVolumeMapper.h"

class vtkEnsembleBuffer;

class SPTRENDERING_EXPORT vtkStochasticVolumeMapper : public vtkTetrahedralVolumeMapper
{
public:
  vtkTypeMacro(vtkStochasticVolumeMapper, vtkTetrahedralVolumeMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Number of independent repetitions (stochastic passes, or particle sets) averaged into one
   * image (the papers' L_R). The noise falls as 1 / sqrt(RepetitionLevel). Range 1 to 65536,
   * default 32.
   */
  vtkSetClampMacro(RepetitionLevel, int, 1, 65536);
  vtkGetMacro(RepetitionLevel, int);
  ///@}

  ///@{
  /**
   * Supersampling: each repetition is drawn at SubpixelLevel times the width and the height
   * and averaged down (the papers' L_S), which multiplies the samples per pixel by
   * SubpixelLevel^2 for the memory of that many pixels. Range 1 to 8, default 1.
   */
  vtkSetClampMacro(SubpixelLevel, int, 1, 8);
  vtkGetMacro(SubpixelLevel, int);
  ///@}

  ///@{
  /**
   * Seed of the random numbers. The same seed, input and camera give the same image; change
   * it for an independent image. Default 0.
   */
  vtkSetMacro(Seed, unsigned int);
  vtkGetMacro(Seed, unsigned int);
  ///@}

  /**
   * Release every GPU resource this mapper holds for the window.
   */
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkStochasticVolumeMapper();
  ~vtkStochasticVolumeMapper() override;

  /// The framebuffers the repetitions are summed in and resolved from.
  vtkEnsembleBuffer* GetEnsemble() const;

  int RepetitionLevel = 32;
  int SubpixelLevel = 1;
  unsigned int Seed = 0;

private:
  vtkStochasticVolumeMapper(const vtkStochasticVolumeMapper&) = delete;
  void operator=(const vtkStochasticVolumeMapper&) = delete;

  vtkSmartPointer<vtkEnsembleBuffer> Ensemble;
};

#endif
