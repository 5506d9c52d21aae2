// Unit test of the PBVR particle generator on one tetrahedron, against closed forms:
// - constant attenuation: the count of every set is Poisson with mean tau V / S, and the
//   particles are uniform in the tetrahedron (inside it, mean at its centroid);
// - attenuation proportional to a linear scalar: rejection sampling keeps the density tau(s),
//   so the particles' mean scalar is E[s^2] / E[s] = 0.4 for a scalar 0, 0, 0, 1;
// - a thin opacity peak inside the cell: rejection sampling finds it with the exact expected
//   count; the papers' cell-average density (mean scalar 0.25) draws no particle;
// - cell-average counts are tau V / S rounded stochastically (only the two nearest integers);
// - the same seed gives the same particles, another seed others; the memory cap and invalid
//   settings fail with a message and no particles.

#include "vtkPBVRParticleGenerator.h"
#include "vtkPBVRVolumeMapper.h"
#include "vtkTetrahedralMesh.h"

#include "vtkDoubleArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkUnstructuredGrid.h"

#include "SPTTestChecks.h"

#include <glm/glm.hpp>

#include <array>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

namespace
{
// The mesh of the unit corner tetrahedron (volume 1/6; its normalized coordinates are the
// same, shifted) with the point scalars.
void SetTetrahedron(vtkTetrahedralMesh* mesh, const std::array<double, 4>& scalars)
{
  vtkNew<vtkUnstructuredGrid> grid;
  vtkNew<vtkPoints> points;
  vtkNew<vtkDoubleArray> values;
  values->SetName("s");
  for (int i = 0; i < 4; ++i)
  {
    points->InsertNextPoint(i == 1, i == 2, i == 3);
    values->InsertNextValue(scalars[i]);
  }
  grid->SetPoints(points);
  const vtkIdType ids[4] = { 0, 1, 2, 3 };
  grid->InsertNextCell(VTK_TETRA, 4, ids);
  grid->GetPointData()->SetScalars(values);
  mesh->Update(grid, vtkTetrahedralMesh::ScalarSelection());
}

std::vector<double> Sample(const std::function<double(double)>& tau, int n = 4001)
{
  std::vector<double> samples(n);
  for (int i = 0; i < n; ++i)
  {
    samples[i] = tau(double(i) / (n - 1));
  }
  return samples;
}

struct Particle
{
  glm::dvec3 Position; // normalized model coordinates
  double Scalar;
};

std::vector<Particle> Decode(const vtkPBVRParticleGenerator* generator)
{
  const std::vector<unsigned short>& raw = generator->GetParticles();
  std::vector<Particle> particles(raw.size() / 4);
  for (size_t i = 0; i < particles.size(); ++i)
  {
    const unsigned short* q = &raw[4 * i];
    particles[i].Position = glm::dvec3(q[0], q[1], q[2]) / 65535.0 - 0.5;
    particles[i].Scalar = q[3] / 65535.0;
  }
  return particles;
}

constexpr double Volume = 1.0 / 6.0;
constexpr double Footprint = 1.0e-3;

// Generation settings with the tests' footprint: `sets` sets, `seed`, at most `maximum`
// particles.
vtkPBVRParticleGenerator::Settings MakeSettings(
  int sets, unsigned int seed, size_t maximum = 10000000)
{
  vtkPBVRParticleGenerator::Settings settings;
  settings.Footprint = Footprint;
  settings.Sets = sets;
  settings.Seed = seed;
  settings.MaximumParticles = maximum;
  return settings;
}

// A failure unless the generator's particle count is within 5 standard deviations of a
// Poisson count of mean `expected`.
void CheckCount(const vtkPBVRParticleGenerator* generator, double expected, const std::string& what,
  SPTTestChecks::FailureCount& failures)
{
  const double count = double(generator->GetNumberOfParticles());
  std::cout << what << ": " << count << " particles, expected " << expected << "\n";
  failures.Check(std::abs(count - expected) < 5.0 * std::sqrt(expected), what + ": count");
}

void TestConstantDensity(vtkTetrahedralMesh* mesh, SPTTestChecks::FailureCount& failures)
{
  SetTetrahedron(mesh, { 0.0, 0.3, 0.6, 1.0 });
  vtkNew<vtkPBVRParticleGenerator> generator;
  vtkPBVRParticleGenerator::Settings settings = MakeSettings(1000, 7);
  const double tau = 2.0;
  failures.Check(generator->Generate(mesh, Sample([=](double) { return tau; }), settings),
    "constant density: generation succeeds");
  CheckCount(generator, tau * Volume / Footprint * settings.Sets, "constant density", failures);

  double sum = 0.0, sum2 = 0.0;
  for (int set = 0; set < settings.Sets; ++set)
  {
    const double count = double(generator->GetSetOffset(set + 1) - generator->GetSetOffset(set));
    failures.Check(count >= 0.0, "set offsets are ordered");
    sum += count;
    sum2 += count * count;
  }
  const double mean = sum / settings.Sets;
  const double variance = (sum2 - sum * mean) / (settings.Sets - 1);
  std::cout << "  per set: mean " << mean << ", variance / mean " << variance / mean << "\n";
  // Poisson counts: dispersion 1, standard error sqrt(2 / (sets - 1)) = 0.045.
  failures.Check(std::abs(variance / mean - 1.0) < 0.2, "constant density: counts are Poisson");

  const glm::dvec3 corner(-0.5);
  glm::dvec3 centroid(0.0);
  int outside = 0;
  const std::vector<Particle> particles = Decode(generator);
  for (const Particle& p : particles)
  {
    const glm::dvec3 b = p.Position - corner; // barycentric weights of vertices 1, 2, 3
    const double margin = 2.0 / 65535.0;
    outside += b.x < -margin || b.y < -margin || b.z < -margin || b.x + b.y + b.z > 1.0 + margin;
    centroid += p.Position;
  }
  centroid /= double(particles.size());
  failures.Check(outside == 0, "every particle is inside the tetrahedron");
  failures.Check(glm::length(centroid - (corner + glm::dvec3(0.25))) < 0.005,
    "constant density: particles are uniform (their mean is the centroid)");
  failures.Check(generator->GetNumberOfCandidates() == generator->GetNumberOfParticles(),
    "constant density: no candidate is rejected");
}

void TestRejection(vtkTetrahedralMesh* mesh, SPTTestChecks::FailureCount& failures)
{
  SetTetrahedron(mesh, { 0.0, 0.0, 0.0, 1.0 });
  vtkNew<vtkPBVRParticleGenerator> generator;
  vtkPBVRParticleGenerator::Settings settings = MakeSettings(500, 11);
  // tau(s) = 2 s; s is Beta(1, 3) in the cell: E[s] = 1/4, E[s^2] = 1/10.
  failures.Check(generator->Generate(mesh, Sample([](double s) { return 2.0 * s; }), settings),
    "ramp: generation succeeds");
  CheckCount(generator, settings.Sets * Volume / Footprint * 2.0 * 0.25, "ramp", failures);
  double meanScalar = 0.0;
  for (const Particle& p : Decode(generator))
  {
    meanScalar += p.Scalar;
  }
  meanScalar /= double(generator->GetNumberOfParticles());
  std::cout << "ramp: mean scalar " << meanScalar << " (expected 0.4)\n";
  failures.Check(std::abs(meanScalar - 0.4) < 0.004, "ramp: the density follows the scalar");

  // A thin peak at s = 0.5 (+-0.02, height 50): expected count from the cell's scalar law.
  auto peak = [](double s) { return std::max(0.0, 50.0 * (1.0 - std::abs(s - 0.5) / 0.02)); };
  const std::vector<double> samples = Sample(peak);
  double expectedTau = 0.0;
  const int steps = 200000;
  for (int i = 0; i < steps; ++i)
  {
    const double s = (i + 0.5) / steps;
    expectedTau += 3.0 * (1.0 - s) * (1.0 - s) * peak(s) / steps;
  }
  failures.Check(generator->Generate(mesh, samples, settings), "peak: generation succeeds");
  CheckCount(
    generator, settings.Sets * Volume / Footprint * expectedTau, "thin peak, rejection", failures);
  settings.SamplingMode = vtkPBVRVolumeMapper::CELL_AVERAGE;
  failures.Check(generator->Generate(mesh, samples, settings), "peak, cell average: succeeds");
  std::cout << "thin peak, cell average: " << generator->GetNumberOfParticles() << " particles\n";
  failures.Check(
    generator->GetNumberOfParticles() == 0, "peak, cell average: the feature is missed");
}

void TestCellAverageRounding(vtkTetrahedralMesh* mesh, SPTTestChecks::FailureCount& failures)
{
  SetTetrahedron(mesh, { 0.0, 0.3, 0.6, 1.0 });
  vtkNew<vtkPBVRParticleGenerator> generator;
  vtkPBVRParticleGenerator::Settings settings = MakeSettings(2000, 0);
  settings.SamplingMode = vtkPBVRVolumeMapper::CELL_AVERAGE;
  const double tau = 2.5 * Footprint / Volume; // 2.5 particles per set
  failures.Check(generator->Generate(mesh, Sample([=](double) { return tau; }), settings),
    "cell average: succeeds");
  bool twoOrThree = true;
  for (int set = 0; set < settings.Sets; ++set)
  {
    const vtkIdType count = generator->GetSetOffset(set + 1) - generator->GetSetOffset(set);
    twoOrThree = twoOrThree && (count == 2 || count == 3);
  }
  const double mean = double(generator->GetNumberOfParticles()) / settings.Sets;
  std::cout << "cell average: " << mean << " particles per set (expected 2.5)\n";
  failures.Check(twoOrThree, "cell average: counts are 2 or 3");
  failures.Check(std::abs(mean - 2.5) < 5.0 * 0.5 / std::sqrt(double(settings.Sets)),
    "cell average: mean count");
}

void TestSeedsLimitsAndErrors(vtkTetrahedralMesh* mesh, SPTTestChecks::FailureCount& failures)
{
  SetTetrahedron(mesh, { 0.0, 0.3, 0.6, 1.0 });
  const std::vector<double> samples = Sample([](double s) { return 1.0 + s; });
  vtkNew<vtkPBVRParticleGenerator> first, second;
  vtkPBVRParticleGenerator::Settings settings = MakeSettings(16, 3, 1000000);
  first->Generate(mesh, samples, settings);
  second->Generate(mesh, samples, settings);
  failures.Check(
    first->GetParticles() == second->GetParticles() && first->GetNumberOfParticles() > 0,
    "the same seed gives the same particles");
  settings.Seed = 4;
  second->Generate(mesh, samples, settings);
  failures.Check(
    first->GetParticles() != second->GetParticles(), "another seed gives other particles");

  settings.MaximumParticles = 100;
  failures.Check(!second->Generate(mesh, samples, settings), "over the cap: generation fails");
  std::cout << "over the cap: " << second->GetLastError() << "\n";
  failures.Check(second->GetLastError().find("would not fit") != std::string::npos,
    "over the cap: the error says so");
  failures.Check(second->GetNumberOfParticles() == 0 && second->GetParticles().empty(),
    "over the cap: no particles are left");
  settings.MaximumParticles = 1000000;
  settings.Footprint = 0.0;
  failures.Check(!second->Generate(mesh, samples, settings) && !second->GetLastError().empty(),
    "a zero footprint is an error");
  settings.Footprint = Footprint;
  settings.Sets = 0;
  failures.Check(!second->Generate(mesh, samples, settings), "zero sets is an error");
  settings.Sets = 1;
  failures.Check(second->Generate(mesh, samples, settings), "valid settings succeed after errors");
  second->ReleaseParticles();
  failures.Check(second->GetParticles().empty() && second->GetNumberOfParticles() > 0,
    "ReleaseParticles frees the particles and keeps their count");
}
}

int TestPBVRParticleGenerator(int, char*[])
{
  vtkNew<vtkTetrahedralMesh> mesh;
  SPTTestChecks::FailureCount failures;
  TestConstantDensity(mesh, failures);
  TestRejection(mesh, failures);
  TestCellAverageRounding(mesh, failures);
  TestSeedsLimitsAndErrors(mesh, failures);
  return failures.ExitStatus();
}
