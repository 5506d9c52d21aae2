"""SPT against the reference, statistically: fixed seeds, tolerances from the repetition count.

For every scene, two independent SPT renders (seeds 1 and 2) per repetition level give the noise
and the bias against the reference (spt.statistics). The tests check that
- the noise is Monte Carlo noise: L x noise is the same at every level L;
- the alpha noise is that of keeping each segment with probability alpha: a (1 - a) / L;
- the bias floor is small, and the RMSE falls as expected towards it (about halving per 4x);
- the mapper's default (the visibility estimator with exact coverage) is unbiased too, with
  exact alpha and a fraction of the paper's noise;
- at 1024 repetitions SPT (as users get it: the defaults) is at least as close to the
  reference as VTK's projected tetrahedra.
Statistical tolerances are four standard errors of the estimates, estimated from the pixels.
The reference is the project's exact ray caster (spt.raycast); where an opaque plane cuts the
volume, VTK's ray caster.
"""

from functools import lru_cache

import numpy as np
import pytest

from spt import metrics, render, statistics

from scene_support import reference, scene
from robustness_support import opaque_plane
from statistics_checks import (Z, check_alpha_noise_is_bernoulli,
                               check_noise_falls_as_one_over_repetitions,
                               check_rmse_falls_to_a_small_bias_floor)

SIZE = 128
LEVELS = {"default": (4, 16, 64), "spx": (4, 16, 64, 256), "bluntfin": (4, 16), "post": (4, 16)}
SCENES = list(LEVELS)


def _scene(name):
    return scene(name)


def _reference(name):
    return reference(name, SIZE)


@lru_cache(maxsize=None)
def _projected_tetrahedra_rmse(name):
    s = _scene(name)
    pt = render.render(s.grid, s.property, render.projected_tetrahedra_mapper(), s.view,
                       (SIZE, SIZE)).image
    return metrics.rmse(pt, _reference(name))


#: "paper": the paper's sampling, whose noise model the tests check; "default": the mapper
#: as users get it; "independent": the default estimator with independent thresholds, so
#: that its repetitions are independent and its noise falls exactly as 1 / L.
MODES = {"paper": render.PAPER_SAMPLING, "default": {}, "independent": {"stratified": False}}


@lru_cache(maxsize=None)
def _spt(name, level, seed, mode="paper"):
    s = _scene(name)
    return render.render(s.grid, s.property, render.spt_mapper(level, seed=seed, **MODES[mode]),
                         s.view, (SIZE, SIZE)).image


@lru_cache(maxsize=None)
def _estimate(name, level, mode="paper"):
    return statistics.estimate(_spt(name, level, 1, mode), _spt(name, level, 2, mode),
                               _reference(name), level)


@pytest.mark.parametrize("name", SCENES)
def test_images_are_volumes(name, have_display):
    reference = _reference(name)
    image = _spt(name, LEVELS[name][-1], 1)
    covered = metrics.footprint(image, reference)
    assert covered.mean() > 0.05, "the images are (almost) empty"
    assert image[..., 3].max() > 0.2 and reference[..., 3].max() > 0.2


def _estimates(name):
    return [_estimate(name, level) for level in LEVELS[name]]


@pytest.mark.parametrize("name", SCENES)
def test_noise_falls_as_one_over_repetitions(name, have_display):
    check_noise_falls_as_one_over_repetitions(_estimates(name))


@pytest.mark.parametrize("name", SCENES)
def test_alpha_noise_is_bernoulli(name, have_display):
    check_alpha_noise_is_bernoulli(_estimates(name))


@pytest.mark.parametrize("name", SCENES)
def test_rmse_falls_to_a_small_bias_floor(name, have_display):
    check_rmse_falls_to_a_small_bias_floor(_estimates(name))


DEFAULT_LEVELS = (1, 4)


@pytest.mark.parametrize("name", SCENES)
def test_default_estimator_is_unbiased(name, have_display):
    """The visibility estimator with exact coverage, independent thresholds: unbiased (the
    control variate's coefficient does not depend on the random numbers), so its RMSE falls
    to the same small bias floor, with noise falling as 1 / L (its repetitions are
    independent)."""
    estimates = [_estimate(name, level, "independent") for level in DEFAULT_LEVELS]
    check_noise_falls_as_one_over_repetitions(estimates)
    assert estimates[-1].bias <= 0.012, f"bias {estimates[-1].bias:.4f}"


@pytest.mark.parametrize("name", SCENES)
def test_default_estimator_has_exact_alpha_and_less_noise(name, have_display):
    """Exact coverage: two seeds give the same alpha (to 8-bit rounding); the colour noise
    left is a fraction of the paper's estimator's at the same repetitions (measured 5-60 %
    of its RMSE at 4 to 256 repetitions on these scenes; required: under half its noise)."""
    first, second = (_spt(name, 4, seed, "independent") for seed in (1, 2))
    assert np.abs(first[..., 3] - second[..., 3]).max() <= 1.0 / 255.0 + 1e-6
    default, paper = _estimate(name, 4, "independent"), _estimate(name, 4)
    assert default.alpha_noise <= 1e-6
    assert default.noise < 0.5 * paper.noise, (
        f"noise at L=4: default {default.noise:.3g}, paper {paper.noise:.3g}")


@pytest.mark.parametrize("name", ["spx", "bluntfin", "post"])
def test_at_1024_repetitions_as_close_as_vtk_projected_tetrahedra(name, have_display):
    """The mapper as users get it (the defaults) at 1024 repetitions, measured, against VTK's
    projected tetrahedra; and better than the prediction for the paper's sampling. (The
    survivor estimator alone, stratified, did not get there on the Oxygen Post: 0.0056
    against VTK PT's 0.0044, many thin layers per pixel making the nearest survivor random.)"""
    pt_rmse = _projected_tetrahedra_rmse(name)
    measured = metrics.rmse(_spt(name, 1024, 3, "default"), _reference(name))
    assert measured <= pt_rmse, f"SPT at 1024 {measured:.4f}, VTK PT {pt_rmse:.4f}"
    paper = _estimate(name, LEVELS[name][-1]).predicted_rmse(1024)
    assert measured < paper, (
        f"the default {measured:.4f} is no better than the paper's sampling {paper:.4f}")


def _block_mean(image, factor):
    h, w, c = image.shape
    return image.reshape(h // factor, factor, w // factor, factor, c).mean(axis=(1, 3))


def test_subpixel_level_averages_subpixels(have_display):
    """SubpixelLevel 2: the expectation is the 2x2 box filter of the reference at twice the
    resolution, and the alpha noise is the subpixels' a (1 - a) / (4 L)."""
    s = _scene("default")
    level, size = 16, SIZE // 2
    fine = render.reference(s.grid, s.property, s.view, (2 * size, 2 * size)).image
    reference = _block_mean(fine, 2)
    first, second = (render.render(
        s.grid, s.property, render.spt_mapper(level, 2, seed, **render.PAPER_SAMPLING), s.view,
        (size, size)).image for seed in (1, 2))
    e = statistics.estimate(first, second, reference, level)
    mask = metrics.footprint(first, reference) | metrics.footprint(second, reference)
    coverage = np.clip(fine[..., 3], 0.0, 1.0)
    expected = _block_mean((coverage * (1.0 - coverage))[..., None], 2)[..., 0][mask].mean() / (
        4 * level)
    assert abs(e.alpha_noise - expected) <= Z * e.alpha_noise_error + 0.1 * expected, (
        f"alpha noise {e.alpha_noise:.4g}, expected {expected:.4g}")
    assert e.bias <= 0.012, f"bias {e.bias:.4f} against the box-filtered reference"


def test_opaque_geometry_hides_and_cuts_the_volume(have_display):
    """An opaque plane through the middle of the volume: SPT and the reference (which stops its
    rays at the z-buffer) agree within the noise, and the plane is really in the picture. The
    plane fills the view, so that no edge of it (rasterized at the reference's double
    resolution) is in the picture."""
    s = _scene("default")
    actor = opaque_plane()
    reference = render.reference(s.grid, s.property, s.view, (SIZE, SIZE), method="vtk",
                                 actors=[actor]).image
    level = 64
    first, second = (render.render(s.grid, s.property, render.spt_mapper(level, seed=seed),
                                   s.view, (SIZE, SIZE), actors=[actor]).image
                     for seed in (1, 2))
    without = _spt("default", LEVELS["default"][-1], 1)
    plane_pixels = np.isclose(reference[..., :3], 0.5, atol=0.02).all(axis=-1)
    assert plane_pixels.mean() > 0.3, "the plane is not in the picture"
    assert metrics.rmse(first, without) > 0.05, "the plane changes nothing"
    e = statistics.estimate(first, second, reference, level)
    assert e.bias <= 0.015, f"bias {e.bias:.4f} against the reference with the plane"
