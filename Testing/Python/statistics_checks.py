"""The statistical checks that the stochastic mappers (SPT, PBVR) share, on the estimates of
image_statistics at several repetition levels: tolerances are Z standard errors of the
estimates, estimated from the pixels. SceneRenders and SCENE_CHECKS give a mapper's tests the
checks of every named scene, through one parametrized test."""

from __future__ import annotations

import math
from functools import lru_cache
from typing import Callable, Dict, List, Sequence

import numpy as np

from spt import metrics, render, scenes

import image_statistics
from scene_support import gray_plane, reference, scene_image

#: A stochastic mapper at a repetition level, subpixel level and seed.
MapperMaker = Callable[[int, int, int], object]
#: A stochastic mapper at a repetition level and seed.
LevelMapperMaker = Callable[[int, int], object]

Z = 4.0  # standard errors
#: The largest bias of a stochastic mapper's image against the exact reference.
BIAS_FLOOR = 0.012


def check_noise_falls_as_one_over_repetitions(
        estimates: Sequence[image_statistics.Estimate]) -> None:
    """L x noise (the variance of one pass) is the same at every level L."""
    first = estimates[0]
    for e in estimates[1:]:
        difference = e.level * e.noise - first.level * first.noise
        tolerance = Z * math.hypot(e.level * e.noise_error, first.level * first.noise_error)
        assert abs(difference) <= tolerance, (
            f"L x noise: {first.level * first.noise:.4g} at L={first.level}, "
            f"{e.level * e.noise:.4g} at L={e.level} (tolerance {tolerance:.3g})")


def check_alpha_noise_is_bernoulli(estimates: Sequence[image_statistics.Estimate]) -> None:
    """The alpha noise is that of one keep-or-discard per pass: a (1 - a) / L. The reference's
    coverage stands in for the expected coverage: the tolerance allows for the bias."""
    for e in estimates:
        tolerance = Z * e.alpha_noise_error + 2.0 * e.bias * math.sqrt(e.bernoulli_alpha_noise)
        assert abs(e.alpha_noise - e.bernoulli_alpha_noise) <= tolerance, (
            f"L={e.level}: alpha noise {e.alpha_noise:.4g}, "
            f"a(1-a)/L {e.bernoulli_alpha_noise:.4g}")


def check_rmse_falls_to_a_small_bias_floor(
        estimates: Sequence[image_statistics.Estimate]) -> None:
    """The RMSE falls from level to level as bias^2 + noise / L predicts, to a bias floor of at
    most BIAS_FLOOR; at noise-dominated levels it about halves for each 4x."""
    last = estimates[-1]
    assert last.bias <= BIAS_FLOOR, f"bias floor {last.bias:.4f}"
    for low, high in zip(estimates, estimates[1:]):
        expected = high.predicted_rmse(low.level) / high.predicted_rmse(high.level)
        measured = low.rmse / high.rmse
        # Relative standard error of one RMSE over n pixels is about 1 / sqrt(2 n).
        tolerance = Z * expected * math.sqrt(2.0 / (2.0 * min(low.pixels, high.pixels)))
        assert abs(measured - expected) <= tolerance + 0.05 * expected, (
            f"RMSE {low.rmse:.4f} at L={low.level}, {high.rmse:.4f} at L={high.level}: "
            f"ratio {measured:.3f}, expected {expected:.3f}")
    assert estimates[0].rmse / estimates[1].rmse > 1.6


def block_mean(image: np.ndarray, factor: int) -> np.ndarray:
    """The mean of each factor x factor block of pixels."""
    h, w, c = image.shape
    return image.reshape(h // factor, factor, w // factor, factor, c).mean(axis=(1, 3))


def check_subpixel_level_averages_subpixels(make: MapperMaker, size: int,
                                            level: int = 16) -> None:
    """SubpixelLevel 2 on the default scene: the expectation is near the 2x2 box filter of the
    reference at twice the resolution, and the alpha noise is the subpixels' a (1 - a) / (4 L)."""
    s = scenes.scene("default")
    fine = render.reference(s.grid, s.property, s.view, (2 * size, 2 * size)).image
    reference = block_mean(fine, 2)
    first, second = (scene_image("default", make(level, 2, seed), size, frames=0)
                     for seed in (1, 2))
    e = image_statistics.estimate(first, second, reference, level)
    mask = metrics.footprint(first, reference) | metrics.footprint(second, reference)
    coverage = np.clip(fine[..., 3], 0.0, 1.0)
    expected = block_mean((coverage * (1.0 - coverage))[..., None], 2)[..., 0][mask].mean() / (
        4 * level)
    assert abs(e.alpha_noise - expected) <= Z * e.alpha_noise_error + 0.1 * expected, (
        f"alpha noise {e.alpha_noise:.4g}, expected {expected:.4g}")
    assert e.bias <= BIAS_FLOOR, f"bias {e.bias:.4f} against the box-filtered reference"


def check_opaque_geometry_hides_and_cuts_the_volume(make: MapperMaker, size: int,
                                                    level: int = 64) -> None:
    """An opaque plane through the middle of the default scene: the mapper and the reference
    (VTK's ray caster, which stops its rays at the z-buffer) agree within the noise, and the
    plane is really in the picture. The plane fills the view, so that no edge of it (rasterized
    at the reference's double resolution) is in the picture."""
    s = scenes.scene("default")
    actor = gray_plane()
    reference = render.reference(s.grid, s.property, s.view, (size, size), method="vtk",
                                 actors=[actor]).image
    first, second = (scene_image("default", make(level, 1, seed), size, actors=[actor],
                                 frames=0) for seed in (1, 2))
    without = scene_image("default", make(level, 1, 1), size, frames=0)
    plane_pixels = np.isclose(reference[..., :3], 0.5, atol=0.02).all(axis=-1)
    assert plane_pixels.mean() > 0.3, "the plane is not in the picture"
    assert metrics.rmse(first, without) > 0.05, "the plane changes nothing"
    e = image_statistics.estimate(first, second, reference, level)
    assert e.bias <= 0.015, f"bias {e.bias:.4f} against the reference with the plane"


class SceneRenders:
    """One stochastic mapper on named scenes of scene_support at size x size pixels: its
    images by repetition level and seed, the exact references, and the estimates from the
    renders with seeds 1 and 2; each made once. ``levels`` gives each scene's repetition
    levels for the checks of SCENE_CHECKS."""

    def __init__(self, make: LevelMapperMaker, levels: Dict[str, Sequence[int]],
                 size: int) -> None:
        self.make = make
        self.levels = levels
        self.size = size

    @lru_cache(maxsize=None)
    def image(self, name: str, level: int, seed: int) -> np.ndarray:
        return scene_image(name, self.make(level, seed), self.size, frames=0)

    @lru_cache(maxsize=None)
    def estimate(self, name: str, level: int) -> image_statistics.Estimate:
        return image_statistics.estimate(self.image(name, level, 1), self.image(name, level, 2),
                                         reference(name, self.size), level)

    def estimates(self, name: str) -> List[image_statistics.Estimate]:
        """The estimates at each of the scene's levels."""
        return [self.estimate(name, level) for level in self.levels[name]]


def _check_images_are_volumes(renders: SceneRenders, name: str) -> None:
    """The image and the reference show a volume: a footprint, and some opacity."""
    image, exact = renders.image(name, renders.levels[name][-1], 1), reference(name, renders.size)
    assert metrics.footprint(image, exact).mean() > 0.05, "the images are (almost) empty"
    assert image[..., 3].max() > 0.2 and exact[..., 3].max() > 0.2


#: The checks of a mapper on each of its scenes, by name, for a test parametrized over both:
#: the images are volumes; the noise falls as 1 / L; the alpha noise is a (1 - a) / L; the
#: RMSE falls to a small bias floor.
SCENE_CHECKS: Dict[str, Callable[[SceneRenders, str], None]] = {
    "images_are_volumes": _check_images_are_volumes,
    "noise_falls_as_one_over_repetitions":
        lambda renders, name: check_noise_falls_as_one_over_repetitions(renders.estimates(name)),
    "alpha_noise_is_bernoulli":
        lambda renders, name: check_alpha_noise_is_bernoulli(renders.estimates(name)),
    "rmse_falls_to_a_small_bias_floor":
        lambda renders, name: check_rmse_falls_to_a_small_bias_floor(renders.estimates(name)),
}
