"""The SPT paper's experiment "Accuracy of stochastic volume rendering".

Along one viewing ray, N segments have opacities alpha_i ~ U(0, a_max) and luminosities
c_i ~ U(0, 1). Front-to-back compositing gives the exact brightness

    B = sum_i c_i alpha_i prod_{j<i} (1 - alpha_j).

Stochastic rendering estimates B without sorting-dependent blending: in one repetition the
segments are visited front to back and segment i is kept with probability alpha_i (a uniform
u_i < alpha_i); the first kept segment is the visible one and contributes c_i (nothing when
none is kept). The average of L independent repetitions is an unbiased estimate of B whose
error falls like 1/sqrt(L).

Run ``python -m spt.experiments.accuracy out.png`` to reproduce the plot.
"""

from __future__ import annotations

import argparse
import math
import pathlib
from typing import Dict, Optional, Sequence, Tuple, Union

import numpy as np

from . import plots
from ..progress import Progress

#: Repetition levels L of the default experiment: 1, 2, 4, ..., 4096.
DEFAULT_LEVELS: Tuple[int, ...] = tuple(2 ** k for k in range(13))

# Upper bound on the number of uniform variates drawn at once.
_CHUNK_ELEMENTS = 1 << 22


def random_rays(n_rays: int, n_segments: int, max_alpha: float, rng: np.random.Generator
                ) -> Tuple[np.ndarray, np.ndarray]:
    """``n_rays`` rays of ``n_segments`` segments: (alpha, color), each of shape (n_rays,
    n_segments), with alpha ~ U(0, max_alpha) and color ~ U(0, 1)."""
    if not 0.0 < max_alpha <= 1.0:
        raise ValueError("max_alpha must be in (0, 1]")
    alpha = rng.uniform(0.0, max_alpha, size=(n_rays, n_segments))
    color = rng.uniform(0.0, 1.0, size=(n_rays, n_segments))
    return alpha, color


def exact_brightness(alpha: np.ndarray, color: np.ndarray) -> np.ndarray:
    """Front-to-back composited brightness of each ray (last axis = segments, front first)."""
    alpha = np.asarray(alpha, dtype=float)
    transmit = np.cumprod(1.0 - alpha, axis=-1)
    before = np.concatenate([np.ones_like(transmit[..., :1]), transmit[..., :-1]], axis=-1)
    return np.sum(np.asarray(color) * alpha * before, axis=-1)


def _walk(alpha: np.ndarray, color: np.ndarray, repetitions: int, rng: np.random.Generator
          ) -> np.ndarray:
    """Sum over ``repetitions`` stochastic walks of each ray's visible luminosity; alpha and
    color have shape (n_rays, n_segments)."""
    u = rng.random((alpha.shape[0], repetitions, alpha.shape[1]))
    kept = u < alpha[:, None, :]
    first = np.argmax(kept, axis=-1)               # first kept segment
    visible = np.take_along_axis(color, first, axis=-1)
    hit = np.any(kept, axis=-1)
    return np.sum(np.where(hit, visible, 0.0), axis=-1)


def stochastic_brightness(alpha: np.ndarray, color: np.ndarray, repetitions: int,
                          rng: np.random.Generator) -> np.ndarray:
    """Stochastic estimate of each ray's brightness averaged over ``repetitions`` independent
    walks. A walk draws one uniform per segment and takes the first segment with u_i <
    alpha_i; drawing all uniforms up front and taking the first hit is the same distribution
    as stopping the walk at the first kept segment. Work is split into chunks to bound
    memory."""
    alpha = np.atleast_2d(np.asarray(alpha, dtype=float))
    color = np.atleast_2d(np.asarray(color, dtype=float))
    if repetitions < 1:
        raise ValueError("repetitions must be >= 1")
    n_rays, n_segments = alpha.shape
    reps_per_chunk = max(1, min(repetitions, _CHUNK_ELEMENTS // max(1, n_segments)))
    rays_per_chunk = max(1, _CHUNK_ELEMENTS // (reps_per_chunk * max(1, n_segments)))
    total = np.zeros(n_rays)
    for start in range(0, n_rays, rays_per_chunk):
        rays = slice(start, start + rays_per_chunk)
        done = 0
        while done < repetitions:
            count = min(reps_per_chunk, repetitions - done)
            total[rays] += _walk(alpha[rays], color[rays], count, rng)
            done += count
    return total / repetitions


def fit_slope(levels: Sequence[float], errors: Sequence[float]) -> Tuple[float, float]:
    """(slope, intercept) of the least-squares line log(error) = slope * log(L) + intercept,
    natural logarithms."""
    slope, intercept = np.polyfit(np.log(np.asarray(levels, dtype=float)),
                                  np.log(np.asarray(errors, dtype=float)), 1)
    return float(slope), float(intercept)


def run(n_segments: int = 16, levels: Sequence[int] = DEFAULT_LEVELS, n_rays: int = 1000,
        max_alpha: float = 0.5, seed: int = 2009, progress: Optional[Progress] = None
        ) -> Dict[str, object]:
    """Mean absolute error of the stochastic estimate versus repetitions: for every level L,
    ``n_rays`` fresh random rays, each estimated with L repetitions. Returns ``levels`` (int
    array), ``error`` (mean absolute error per level), ``stderr`` (its standard error),
    ``slope`` and ``intercept`` of the log-log fit, and the parameters ``n_segments``,
    ``n_rays``, ``max_alpha``, ``seed``."""
    rng = np.random.default_rng(seed)
    levels = np.asarray(sorted(int(level) for level in levels))
    errors, stderrs = [], []
    for level in levels:
        alpha, color = random_rays(n_rays, n_segments, max_alpha, rng)
        deviation = np.abs(stochastic_brightness(alpha, color, level, rng)
                           - exact_brightness(alpha, color))
        errors.append(deviation.mean())
        stderrs.append(deviation.std(ddof=1) / math.sqrt(n_rays) if n_rays > 1 else math.nan)
        if progress is not None:
            progress.step(f"L={level}")
    slope, intercept = fit_slope(levels, errors)
    return {"levels": levels, "error": np.asarray(errors), "stderr": np.asarray(stderrs),
            "slope": slope, "intercept": intercept, "n_segments": n_segments, "n_rays": n_rays,
            "max_alpha": max_alpha, "seed": seed}


def check_unbiased(n_segments: int = 16, repetitions: int = 4, n_trials: int = 20000,
                   n_rays: int = 8, max_alpha: float = 0.5, seed: int = 7) -> Dict[str, object]:
    """Monte Carlo check that the estimator's mean is the exact brightness: ``n_rays`` random
    rays are each estimated ``n_trials`` times with ``repetitions`` repetitions; each ray's
    z-score is (mean - exact) / standard error. Returns the arrays ``exact``, ``mean``,
    ``stderr``, ``z`` (per ray) and ``max_abs_z``."""
    rng = np.random.default_rng(seed)
    alpha, color = random_rays(n_rays, n_segments, max_alpha, rng)
    exact = exact_brightness(alpha, color)
    estimates = stochastic_brightness(np.repeat(alpha, n_trials, axis=0),
                                      np.repeat(color, n_trials, axis=0), repetitions,
                                      rng).reshape(n_rays, n_trials)
    mean = estimates.mean(axis=1)
    stderr = estimates.std(axis=1, ddof=1) / math.sqrt(n_trials)
    z = (mean - exact) / np.maximum(stderr, np.finfo(float).tiny)
    return {"exact": exact, "mean": mean, "stderr": stderr, "z": z,
            "max_abs_z": float(np.max(np.abs(z)))}


def plot(result: Dict[str, object], path: Union[str, pathlib.Path]) -> None:
    """Write a log-log PNG of mean absolute error versus repetitions L, with the least-squares
    fit and a 1/sqrt(L) reference line."""
    levels = np.asarray(result["levels"], dtype=float)
    error = np.asarray(result["error"], dtype=float)
    slope, intercept = float(result["slope"]), float(result["intercept"])
    anchor = math.exp(float(np.mean(np.log(error) + 0.5 * np.log(levels))))
    figure = plots.figure(6.0, 4.5)
    axes = figure.add_subplot(1, 1, 1)
    axes.errorbar(levels, error, yerr=result.get("stderr"), fmt="o", color="tab:blue",
                  label="stochastic estimate")
    axes.plot(levels, np.exp(intercept) * levels ** slope, "-", color="tab:blue", alpha=0.6,
              label=f"least-squares fit, slope {slope:.3f}")
    axes.plot(levels, anchor / np.sqrt(levels), "--", color="tab:red",
              label=r"reference $\propto 1/\sqrt{L}$")
    axes.set_xscale("log", base=2)
    axes.set_yscale("log")
    plots.finish_axes(axes, "repetitions L", "mean absolute error of brightness",
                      "Accuracy of stochastic volume rendering\n"
                      f"{result['n_segments']} segments, alpha ~ U(0, "
                      f"{result['max_alpha']}), {result['n_rays']} rays per L")
    plots.save(figure, path)


def main(argv: Optional[Sequence[str]] = None) -> int:
    """Command line: run the experiment, print the table, write the plot."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("output", help="PNG file to write")
    parser.add_argument("--segments", type=int, default=16)
    parser.add_argument("--rays", type=int, default=1000)
    parser.add_argument("--max-alpha", type=float, default=0.5)
    parser.add_argument("--max-level", type=int, default=4096)
    parser.add_argument("--seed", type=int, default=2009)
    args = parser.parse_args(argv)
    levels = [2 ** k for k in range(int(math.log2(args.max_level)) + 1)]
    result = run(args.segments, levels, args.rays, args.max_alpha, args.seed)
    for level, error in zip(result["levels"], result["error"]):
        print(f"L = {level:5d}  mean abs error = {error:.5f}")
    print(f"slope = {result['slope']:.4f} (expected -0.5)")
    plot(result, args.output)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
