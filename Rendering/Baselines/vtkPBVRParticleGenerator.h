/**
 * @class   vtkPBVRParticleGenerator
 * @brief   the particles of particle-based volume rendering, generated cell by cell
 *
 * Generates the opaque particles that vtkPBVRVolumeMapper draws, from the tetrahedra of a
 * vtkTetrahedralMesh and the attenuation of the transfer function, as in Sakamoto et al. 2007
 * and 2010 (the papers vtkPBVRVolumeMapper cites).
 *
 * A particle hides what lies behind it over its cross-section S (the footprint of one pixel or
 * subpixel, normalized model units squared). Particles scattered as a Poisson process of
 * density rho(x) = tau(s(x)) / S, where tau is the attenuation coefficient (opacity / unit
 * distance), leave a ray of length d uncovered with probability exp(-tau d): the opacity of the
 * optical model of the module.
 *
 * Two samplings:
 * - REJECTION (default): the density follows the scalar inside the cell. Candidates are a
 *   Poisson process at the cell's largest density (the largest tau over the cell's scalar
 *   range), uniform in the tetrahedron; each is kept with probability tau(s) / tau_max. The
 *   particles are then exactly a Poisson process of density tau(s(x)) / S.
 * - CELL_AVERAGE: one density per cell, tau at the mean of its vertex scalars, and the count
 *   density x volume rounded stochastically, as KVS's CellByCellUniformSampling does. Faster
 *   and as in the original papers, but it misses features thinner than a cell.
 *
 * All repetitions are generated at once: the candidates of a cell are drawn at Sets times the
 * density and each particle is given a uniformly random set, which splits the Poisson process
 * into Sets independent ones (the splitting theorem). The particles come out ordered by set,
 * then by cell. Each cell has its own random stream (seed, cell id), so the result does not
 * depend on the order or the threads that generate it.
 *
 * A particle is 4 unsigned shorts: its position in the mesh's normalized coordinates, mapped
 * from [-0.5, 0.5] to [0, 65535], and its scalar as a transfer-function coordinate in [0, 1],
 * mapped to [0, 65535]. Positions are exact to 1/131070 of the mesh's largest extent.
 *
 * Private helper of SPT::RenderingBaselines, used by vtkPBVRVolumeMapper; not wrapped.
 */

#ifndef vtkPBVRParticleGenerator_h
#define vtkPBVRParticleGenerator_h

#include "SPTRenderingBaselinesModule.h" // For export macro
#include "vtkObject.h"

#include <string> // For the error
#include <vector> // For the particles

class vtkTetrahedralMesh;

class SPTRENDERINGBASELINES_EXPORT vtkPBVRParticleGenerator : public vtkObject
{
public:
  static vtkPBVRParticleGenerator* New();
  vtkTypeMacro(vtkPBVRParticleGenerator, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  static constexpr int ComponentsPerParticle = 4;
  struct Block; // the particles of a block of cells, before they are ordered by set
  static constexpr size_t BytesPerParticle = ComponentsPerParticle * sizeof(unsigned short);

  struct Settings
  {
    double Footprint = 0.0; // particle cross-section, normalized model units squared
    int Sets = 1;           // independent particle sets (repetitions), at most 65536
    unsigned int Seed = 0;
    int SamplingMode = 0;        // a vtkPBVRVolumeMapper::SamplingModeType (0: REJECTION)
    size_t MaximumParticles = 0; // generation fails rather than exceed it
  };

  /**
   * Generate the particles of the mesh's tetrahedra. `attenuation` is tau in normalized model
   * units (1 / length), sampled at evenly spaced transfer-function coordinates from 0 to 1
   * (at least 2 samples) and interpolated linearly between them. Returns false, with the
   * reason in GetLastError() and no particles, when the settings are invalid or the particles
   * would exceed MaximumParticles.
   */
  bool Generate(const vtkTetrahedralMesh* mesh, const std::vector<double>& attenuation,
    const Settings& settings);
  const std::string& GetLastError() const { return this->LastError; }

  ///@{
  /**
   * What the last Generate() produced: the particles (ComponentsPerParticle values each),
   * ordered by set; the first particle of every set, and the total at GetSetOffset(Sets).
   */
  const std::vector<unsigned short>& GetParticles() const { return this->Particles; }
  vtkIdType GetNumberOfParticles() const { return this->NumberOfParticles; }
  int GetNumberOfSets() const { return static_cast<int>(this->SetOffsets.size()) - 1; }
  vtkIdType GetSetOffset(int set) const { return this->SetOffsets[set]; }
  vtkIdType GetNumberOfCandidates() const { return this->NumberOfCandidates; }
  /// Wall time of the last Generate(), in seconds.
  double GetGenerationTime() const { return this->GenerationTime; }
  ///@}

  /// Free the particles' memory once they are uploaded; the counts and offsets stay.
  void ReleaseParticles();

protected:
  vtkPBVRParticleGenerator();
  ~vtkPBVRParticleGenerator() override;

private:
  vtkPBVRParticleGenerator(const vtkPBVRParticleGenerator&) = delete;
  void operator=(const vtkPBVRParticleGenerator&) = delete;

  bool Fail(const std::string& reason);
  void OrderBySet(std::vector<Block>& blocks, int sets);

  std::string LastError;
  std::vector<unsigned short> Particles;
  std::vector<vtkIdType> SetOffsets = { 0 };
  vtkIdType NumberOfParticles = 0;
  vtkIdType NumberOfCandidates = 0;
  double GenerationTime = 0.0;
};

#endif
