"""Statistics of stochastic images against a reference: noise, bias and their errors.

Two renders that differ only in their seed are independent estimates of the same expected
image, so half their squared difference measures the noise of one render without the reference,
and the difference of their mean to the reference what is left: the bias. For an estimator that
averages L independent passes, L x noise is a constant (the variance of one pass); for the alpha
channel, one pass is 0 or 1 with P(1) = coverage a, so that constant is a (1 - a) per pixel.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from spt import metrics


@dataclasses.dataclass
class Estimate:
    """What two independent renders at one repetition level say against a reference.

    Squared quantities are means over the footprint pixels and the four RGBA channels (alpha
    alone where named); `*_error` are their standard errors over pixels.
    """

    level: int
    noise: float             # variance of one render (per pixel and channel)
    noise_error: float
    alpha_noise: float
    alpha_noise_error: float
    bernoulli_alpha_noise: float  # mean a (1 - a) / L of the reference's coverage a
    bias2: float             # squared bias (noise removed), may come out slightly negative
    bias2_error: float
    rmse: float              # footprint RMSE of the first render
    pixels: int

    @property
    def bias(self) -> float:
        """The bias RMSE, zero where noise hides it."""
        return math.sqrt(max(self.bias2, 0.0))

    def predicted_rmse(self, level: int) -> float:
        """RMSE of one render at another repetition level: bias^2 + noise scaled by 1/L."""
        return math.sqrt(max(self.bias2, 0.0) + self.noise * self.level / level)


def _mean_and_error(values: np.ndarray) -> tuple:
    values = np.asarray(values, dtype=np.float64)
    return float(values.mean()), float(values.std(ddof=1) / math.sqrt(values.size))


def estimate(first: np.ndarray, second: np.ndarray, reference: np.ndarray,
             level: int) -> Estimate:
    """Noise and bias of renders at `level` repetitions from two independent renders, over
    the footprint of either."""
    first, second = metrics.as_float(first), metrics.as_float(second)
    reference = metrics.as_float(reference)
    mask = metrics.footprint(first, reference) | metrics.footprint(second, reference)
    a, b, r = first[mask], second[mask], reference[mask]
    half_square = 0.5 * (a - b) ** 2
    noise, noise_error = _mean_and_error(half_square.mean(axis=1))
    alpha_noise, alpha_noise_error = _mean_and_error(half_square[:, 3])
    # E[(mean - r)^2] = bias^2 + noise / 2, and E[(a - b)^2 / 4] = noise / 2.
    excess = (0.5 * (a + b) - r) ** 2 - 0.5 * half_square
    bias2, bias2_error = _mean_and_error(excess.mean(axis=1))
    coverage = np.clip(r[:, 3], 0.0, 1.0)
    return Estimate(level=level, noise=noise, noise_error=noise_error, alpha_noise=alpha_noise,
                    alpha_noise_error=alpha_noise_error,
                    bernoulli_alpha_noise=float(np.mean(coverage * (1.0 - coverage)) / level),
                    bias2=bias2, bias2_error=bias2_error,
                    rmse=metrics.rmse(first, reference, mask), pixels=int(mask.sum()))
