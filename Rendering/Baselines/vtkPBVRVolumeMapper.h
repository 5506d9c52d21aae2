/**
 * @class   vtkPBVRVolumeMapper
 * @brief   particle-based volume rendering (PBVR) of unstructured grids
 *
 * vtkPBVRVolumeMapper volume renders a vtkUnstructuredGrid (any linear or quadratic 3D cells,
 * split into tetrahedra once per input change) with opaque particles and no sorting, as in
 *
 *   N. Sakamoto, J. Nonaka, K. Koyamada and S. Tanaka, "Particle-based volume rendering",
 *   Asia-Pacific Symposium on Visualization (APVIS), 2007;
 *   N. Sakamoto, T. Kawamura, K. Koyamada and K. Nozaki, "Improvement of particle-based volume
 *   rendering for visualizing irregular volume data sets", Computers & Graphics 34(1), 2010.
 *
 * It is the particle-based counterpart of vtkSPTVolumeMapper and renders the same optical
 * model (that of vtkUnstructuredGridLinearRayIntegrator: attenuation tau = opacity /
 * ScalarOpacityUnitDistance, emission = color x tau, lengths in the data's own coordinates).
 *
 * Particles are generated cell by cell on the CPU: a particle covers one pixel (one subpixel
 * at SubpixelLevel > 1), whose cross-section S at the particle's depth is measured in the
 * data's coordinates, and particles scattered with density rho = tau(s) / S, i.e.
 * -ln(1 - alpha) / (S x unit length) for the opacity alpha of a unit length, cover a ray of
 * length d with probability 1 - exp(-tau d). Inside a tetrahedron the density follows the
 * interpolated scalar (rejection sampling against the cell's largest density, Poisson counts),
 * or, with SamplingMode CELL_AVERAGE, is the density of the cell's mean scalar, as in the
 * papers (see vtkPBVRParticleGenerator). Each particle carries its scalar; its color is looked
 * up in the color transfer function when it is drawn.
 *
 * Under perspective the pixel's cross-section grows with depth. The particles are generated
 * for the smallest cross-section over the data's bounding sphere (its nearest point) and each
 * is drawn with probability S_generated / S(its own depth), which thins the particles exactly
 * to the density its depth needs. The camera may be anywhere, inside the data too: nothing is
 * generated for a depth nearer than the data's bounding radius (or the near plane), and a
 * particle nearer than that is drawn as a square point of S_generated / S(its depth) pixels,
 * which covers the same expected share of the pixels. The particles are regenerated only
 * when the data, the opacity transfer function, the seed or the sampling mode change, when a
 * view needs smaller particles than they were made for, or when it needs particles more than
 * twice as large (too many particles would be thrown away); also when RepetitionLevel grows
 * beyond the sets that were generated (fewer repetitions draw fewer of the sets).
 *
 * RepetitionLevel independent particle sets are drawn, each opaque with the depth test into
 * the same float ensemble buffer as SPT, and averaged; the noise falls as
 * 1 / sqrt(RepetitionLevel x SubpixelLevel^2). Opaque geometry drawn before the volume hides
 * it. The time budget (AutoAdjustRepetitions) and
 * progressive refinement count particle sets: a render draws the sets that fit the time
 * allotted, and progressive refinement adds the next ones, up to the sets generated.
 * AutoAdjustRepetitions is off by default for PBVR: every render draws RepetitionLevel sets.
 *
 * The particles need GPU memory in proportion to RepetitionLevel x SubpixelLevel^2 and to the
 * opacity: 8 bytes each. Generation fails with an error, and nothing is drawn, when they would
 * exceed MaximumParticleMemory.
 *
 * @sa
 * vtkSPTVolumeMapper vtkUnstructuredGridVolumeRayCastMapper
 */

#ifndef vtkPBVRVolumeMapper_h
#define vtkPBVRVolumeMapper_h

#include "SPTRenderingBaselinesModule.h" // For export macro
#include "vtkStochasticVolumeMapper.h"

#include <memory> // For the internals

class vtkRenderer;
class vtkVolume;
class vtkWindow;

class SPTRENDERINGBASELINES_EXPORT vtkPBVRVolumeMapper : public vtkStochasticVolumeMapper
{
public:
  static vtkPBVRVolumeMapper* New();
  vtkTypeMacro(vtkPBVRVolumeMapper, vtkStochasticVolumeMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum SamplingModeType
  {
    REJECTION = 0,
    CELL_AVERAGE = 1
  };

  ///@{
  /**
   * How the particle density varies inside a tetrahedron. REJECTION (default): it follows the
   * interpolated scalar exactly (rejection sampling, Poisson counts). CELL_AVERAGE: it is the
   * density of the mean of the cell's vertex scalars, with the count rounded stochastically,
   * as in the original papers; it misses features thinner than a cell.
   */
  vtkSetClampMacro(SamplingMode, int, REJECTION, CELL_AVERAGE);
  vtkGetMacro(SamplingMode, int);
  void SetSamplingModeToRejection() { this->SetSamplingMode(REJECTION); }
  void SetSamplingModeToCellAverage() { this->SetSamplingMode(CELL_AVERAGE); }
  ///@}

  ///@{
  /**
   * The most memory, in MiB, that the particles may take (8 bytes each, on the GPU). If they
   * would take more, nothing is drawn and an error says how many were needed.
   * Range 1 to 65536, default 2048.
   */
  vtkSetClampMacro(MaximumParticleMemory, int, 1, 65536);
  vtkGetMacro(MaximumParticleMemory, int);
  ///@}

  ///@{
  /**
   * What the mapper holds after the last render: the particles of all generated sets, the
   * number of sets, the side of a particle's square cross-section (data units) at the nearest
   * point of the data, and the bytes held on the GPU (particles, color table and ensemble
   * framebuffers).
   */
  vtkIdType GetNumberOfParticles();
  int GetNumberOfParticleSets();
  double GetParticleSize();
  vtkIdType GetGPUMemorySize() override;
  ///@}

  ///@{
  /**
   * How often the particles were generated since the mapper was made, and the wall time of
   * the last generation in seconds (GetNumberOfParticles() / GetGenerationTime() is the
   * generation rate).
   */
  vtkIdType GetGenerationCount();
  double GetGenerationTime();
  ///@}

  /// Render the volume. Called by vtkVolume; not meant to be called directly.
  void Render(vtkRenderer* ren, vtkVolume* vol) override;

  /**
   * Release every GPU resource this mapper holds for the window (the particles are generated
   * again at the next render).
   */
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkPBVRVolumeMapper();
  ~vtkPBVRVolumeMapper() override;

  int SamplingMode = REJECTION;
  int MaximumParticleMemory = 2048;

private:
  vtkPBVRVolumeMapper(const vtkPBVRVolumeMapper&) = delete;
  void operator=(const vtkPBVRVolumeMapper&) = delete;

  bool PrepareParticles(vtkRenderer* ren, vtkVolume* vol, int passWidth, int passHeight);
  // Draw particle sets [first, first + count) into the ensemble and resolve it.
  void DrawSets(int x, int y, int first, int count);

  class vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
};

#endif
