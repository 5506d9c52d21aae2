"""The statistical checks that the stochastic mappers (SPT, PBVR) share, on the estimates of
spt.statistics at several repetition levels: tolerances are Z standard errors of the
estimates, estimated from the pixels."""

from __future__ import annotations

import math
from typing import Sequence

from spt import statistics

Z = 4.0  # standard errors


def check_noise_falls_as_one_over_repetitions(estimates: Sequence[statistics.Estimate]) -> None:
    """L x noise (the variance of one pass) is the same at every level L."""
    first = estimates[0]
    for e in estimates[1:]:
        difference = e.level * e.noise - first.level * first.noise
        tolerance = Z * math.hypot(e.level * e.noise_error, first.level * first.noise_error)
        assert abs(difference) <= tolerance, (
            f"L x noise: {first.level * first.noise:.4g} at L={first.level}, "
            f"{e.level * e.noise:.4g} at L={e.level} (tolerance {tolerance:.3g})")


def check_alpha_noise_is_bernoulli(estimates: Sequence[statistics.Estimate]) -> None:
    """The alpha noise is that of one keep-or-discard per pass: a (1 - a) / L. The reference's
    coverage stands in for the expected coverage: the tolerance allows for the bias."""
    for e in estimates:
        tolerance = Z * e.alpha_noise_error + 2.0 * e.bias * math.sqrt(e.bernoulli_alpha_noise)
        assert abs(e.alpha_noise - e.bernoulli_alpha_noise) <= tolerance, (
            f"L={e.level}: alpha noise {e.alpha_noise:.4g}, "
            f"a(1-a)/L {e.bernoulli_alpha_noise:.4g}")


def check_rmse_falls_to_a_small_bias_floor(estimates: Sequence[statistics.Estimate],
                                           bias_floor: float = 0.012) -> None:
    """The RMSE falls from level to level as bias^2 + noise / L predicts, to a bias floor of at
    most `bias_floor`; at noise-dominated levels it about halves for each 4x."""
    last = estimates[-1]
    assert last.bias <= bias_floor, f"bias floor {last.bias:.4f}"
    for low, high in zip(estimates, estimates[1:]):
        expected = high.predicted_rmse(low.level) / high.predicted_rmse(high.level)
        measured = low.rmse / high.rmse
        # Relative standard error of one RMSE over n pixels is about 1 / sqrt(2 n).
        tolerance = Z * expected * math.sqrt(2.0 / (2.0 * min(low.pixels, high.pixels)))
        assert abs(measured - expected) <= tolerance + 0.05 * expected, (
            f"RMSE {low.rmse:.4f} at L={low.level}, {high.rmse:.4f} at L={high.level}: "
            f"ratio {measured:.3f}, expected {expected:.3f}")
    assert estimates[0].rmse / estimates[1].rmse > 1.6
