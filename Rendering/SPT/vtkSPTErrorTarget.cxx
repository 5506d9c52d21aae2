#include "vtkSPTErrorTarget.h"

#include <algorithm>
#include <cmath>

namespace
{
// How far beyond the target a step with a measured noise aims, in variance: a step costs a
// traversal pair whatever its repetitions (up to a group), and the estimate is itself noisy:
// aiming at the target exactly falls short about half the time, and a step of a few
// repetitions more costs another pair.
constexpr double StepMargin = 1.25;

// The repetitions to add to each half for the noise to fall from `estimate` to StepMargin below
// `target` in variance, if it falls as one over the square root of the repetitions: at least
// one, at most 16 times what each half holds.
int RepetitionsToTarget(int half, double estimate, double target)
{
  const double ratio = estimate / target;
  const double more = std::ceil(half * (StepMargin * ratio * ratio - 1.0));
  return static_cast<int>(std::max(1.0, std::min(more, 16.0 * half)));
}

// The repetitions of a first step below which an image's tiles are not worth a step of their
// own: with fewer, the fixed cost of a step (a traversal pair's setup and geometry, and the
// estimate) outweighs the repetitions the quiet tiles are spared.
constexpr int TypicalStepRepetitions = 32;

// The noise of one repetition that the first image of a mapper assumes before it has measured
// any (RMSE of premultiplied RGBA): a little above the largest measured on the benchmark's
// scenes at their defaults (0.025 on the torus, 0.020 to 0.023 on the Oxygen Post and the
// drill; 0.004 to 0.006 on Blunt Fin and SPX). At the default target of 0.005 it draws 16 + 16.
constexpr double FirstImageNoisePerRepetition = 0.0275;

// The repetitions per half of an image's first step: as many as the noise of one repetition
// predicts for the target, times `margin` in variance, at least one and at most `most`. A
// measured noise gets the margin of every step (StepMargin); the first image's assumed one none,
// as the assumption is already a pessimistic one. A target of 0 (one below the rounding) draws
// `most`.
int FirstHalfToTarget(double noisePerRepetition, double target, double margin, int most)
{
  if (!(target > 0.0))
  {
    return most;
  }
  const double ratio = noisePerRepetition / target;
  const double half = std::ceil(0.5 * margin * ratio * ratio);
  return static_cast<int>(std::max(1.0, std::min(half, double(most))));
}
}

int vtkSPTErrorTarget::FirstHalfOfImage(const State& state, double target, int most)
{
  const int largest = FirstHalfToTarget(state.NoisePerRepetition, target, StepMargin, most);
  if (state.TypicalNoisePerRepetition <= 0.0)
  {
    return largest;
  }
  // Aimed at the median tile, the first step leaves about half of the tiles for the later
  // steps, which draw only those: worth a step's fixed cost (its traversals' setup and
  // geometry, and the estimate) where the largest tile asks for at least twice as many
  // repetitions, and for more than a group of TypicalStepRepetitions.
  const int typical = FirstHalfToTarget(state.TypicalNoisePerRepetition, target, StepMargin, most);
  return largest >= 2 * typical && 2 * largest > TypicalStepRepetitions ? typical : largest;
}

int vtkSPTErrorTarget::StepToTarget(
  const Steps& steps, int first, int count, int perPass, bool coverage, double target, State& state)
{
  if (!state.Balanced)
  {
    // A lone repetition went to the first half: its noise is no longer estimated.
    return steps.Draw(first, count, coverage, false) ? count : -1;
  }
  if (state.HalfCount > 0 && state.Estimate <= target)
  {
    return 0; // the image meets the target (or shows nothing)
  }
  // Each step aims beyond the target. The first of an image aims with the noise per
  // repetition of the images before it (the noise changes little with the view, and any
  // shortfall takes one more step); the first image's first step aims with an assumed noise
  // per repetition, in at most one traversal pair.
  if (state.HalfCount == 0 && state.FirstHalf == 0 && count >= 2)
  {
    state.FirstHalf = state.NoisePerRepetition > 0.0
      ? FirstHalfOfImage(state, target, count / 2)
      : FirstHalfToTarget(
          FirstImageNoisePerRepetition, target, 1.0, std::max(1, std::min(perPass, count) / 2));
  }
  return StepInPairs(steps, first, count, coverage, target, state);
}

int vtkSPTErrorTarget::StepInPairs(
  const Steps& steps, int first, int count, bool coverage, double target, State& state)
{
  int drawn = 0;
  int half = state.HalfCount > 0 ? RepetitionsToTarget(state.HalfCount, state.Estimate, target)
                                 : state.FirstHalf;
  while (count - drawn >= 2)
  {
    half = std::min(half, (count - drawn) / 2);
    if (!steps.Draw(first + drawn, 2 * half, coverage && drawn == 0, true))
    {
      return -1;
    }
    drawn += 2 * half;
    state.HalfCount += half;
    const bool firstEstimate = state.HalfCount == half;
    double median = -1.0;
    if (!steps.Estimate(state.HalfCount, state.Estimate, median))
    {
      return -1;
    }
    if (state.Estimate > 0.0)
    {
      state.NoisePerRepetition = state.Estimate * std::sqrt(2.0 * state.HalfCount);
    }
    if (firstEstimate && median > 0.0)
    {
      // Every tile holds the same repetitions only at an image's first estimate.
      state.TypicalNoisePerRepetition = median * std::sqrt(2.0 * state.HalfCount);
    }
    if (state.Estimate <= target)
    {
      break; // met, or nothing to see (negative)
    }
    half = RepetitionsToTarget(state.HalfCount, state.Estimate, target);
  }
  if (drawn == 0)
  {
    // Room for one repetition only (the cap or the time budget).
    if (!steps.Draw(first, 1, coverage, false))
    {
      return -1;
    }
    state.Balanced = false;
    state.Estimate = -1.0;
    drawn = 1;
  }
  return drawn;
}

double vtkSPTErrorTarget::ChooseTiles(
  const std::vector<double>& tileNoise, double target, std::vector<bool>& active, double& median)
{
  active.assign(tileNoise.size(), false);
  std::vector<double> shown;
  for (size_t tile = 0; tile < tileNoise.size(); ++tile)
  {
    active[tile] = tileNoise[tile] > target;
    if (tileNoise[tile] >= 0.0)
    {
      shown.push_back(tileNoise[tile]);
    }
  }
  if (shown.empty())
  {
    median = -1.0;
    return -1.0;
  }
  std::nth_element(shown.begin(), shown.begin() + shown.size() / 2, shown.end());
  median = shown[shown.size() / 2];
  return *std::max_element(shown.begin(), shown.end());
}
