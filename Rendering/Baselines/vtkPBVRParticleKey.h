/**
 * @class   vtkPBVRParticleKey
 * @brief   what a PBVR particle set was generated for, and which views it serves
 *
 * PBVR's particles follow the opacity (their density) and the cross-section of the pixels
 * they are drawn into: a set made for a cross-section S serves every view that needs S to 2 S
 * (the surplus is thinned when drawn); beyond that, or below S, particles are made again. A
 * generation that failed (too many particles for the memory bound) is not tried again until a
 * view needs particles larger by a quarter, fewer sets or more memory.
 *
 * Private helper of SPT::RenderingBaselines, used by vtkPBVRVolumeMapper; not wrapped.
 */

#ifndef vtkPBVRParticleKey_h
#define vtkPBVRParticleKey_h

#include "vtkPBVRParticleGenerator.h" // For the generator's settings

// The generator's settings, and the mesh and opacity they were applied to.
struct vtkPBVRParticleKey : vtkPBVRParticleGenerator::Settings
{
  // Particles serve views whose cross-section is at most this multiple of theirs.
  static constexpr double LargestFootprintRatio = 2.0;
  // After a failed generation, a view must need particles this much larger to try again.
  static constexpr double RetryFootprintRatio = 1.25;

  vtkMTimeType MeshBuild = 0;
  vtkMTimeType OpacityChange = 0;

  // Whether both keys describe the same density of particles.
  bool SameModel(const vtkPBVRParticleKey& o) const
  {
    return this->MeshBuild == o.MeshBuild && this->OpacityChange == o.OpacityChange &&
      this->Seed == o.Seed && this->SamplingMode == o.SamplingMode;
  }

  // Whether particles generated for this key serve a view that needs a cross-section `needed`
  // and `sets` particle sets within the memory of `wanted`.
  bool Serves(const vtkPBVRParticleKey& wanted, double needed, int sets, size_t particles) const
  {
    return this->SameModel(wanted) && needed >= this->Footprint &&
      needed <= LargestFootprintRatio * this->Footprint && this->Sets >= sets &&
      particles <= wanted.MaximumParticles;
  }

  // Whether a generation for `wanted` fails again as the one for this key did: it can only
  // succeed with larger particles, fewer sets or more memory.
  bool FailsAgain(const vtkPBVRParticleKey& wanted) const
  {
    return this->SameModel(wanted) && this->Sets <= wanted.Sets &&
      wanted.Footprint <= RetryFootprintRatio * this->Footprint &&
      this->MaximumParticles >= wanted.MaximumParticles;
  }
};

#endif
