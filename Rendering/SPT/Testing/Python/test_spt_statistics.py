"""SPT against the reference, statistically: fixed seeds, tolerances from the repetition count.

For every scene, two independent SPT renders (seeds 1 and 2) per repetition level give the noise
and the bias against the reference (image_statistics). The tests check that
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

Depth slabs (vtkSPTVolumeMapper::SetDepthSlabs()): each slab has survivors of its own, and its
segments are weighted by the exact transmittance of the slabs in front of it and shifted by its
own control variate. None of that depends on the random numbers, so the expectation must stay
exact front-to-back compositing; what the slabs change is the noise. The tests check that
- with independent thresholds the noise falls as 1 / L and the bias is that of one slab (a
  wrong weight or a segment in the wrong slab shows as a bias of 0.01 or more);
- the alpha is exact, as with one slab;
- the survivor estimator with slabs is unbiased too;
- the noise of a repetition is a fraction of one slab's;
- opaque geometry still hides and cuts the volume;
- one repetition per render, refined progressively, keeps the first render's slab sums;
- a split into any number of slabs gives the same expectation (2, 3 and 8).

The claims of the sorting figure (python3 -m spt figures sorting), checked at 128 x 128.
SPT's RMSE at a repetition level it is not rendered at is predicted from two renders with
different seeds at a low level (image_statistics: bias^2 + noise x L / level); renders at 1024
repetitions measured 2 % (torus) and 12 % (default mesh) below the prediction.
- Where the centroid sort is far from the per-pixel order, the sorted renderer shows
  artifacts and SPT does not: on Blunt Fin, whose thin boundary-layer cells reach the pixels
  up to 27 places out of order, HAVS-like with k = 6 is several times farther from the
  reference than SPT at the figure's 144 repetitions.
- The issue's claim, that on the torus and on the default (non-convex) mesh SPT at 1024
  repetitions is closer to the reference than HAVS-like with k = 2 and than VTK's projected
  tetrahedra, measured against the exact reference with the mapper as users get it (the
  visibility estimator with exact coverage, stratified, 16 repetitions per pass). With the
  paper's survivor estimator (stratified) it held only against HAVS-like k = 2 on the torus:
  its noise at 1024 repetitions (0.0053 on the default mesh) was above the sorted methods'
  error there (HAVS-like k = 2 0.0042, VTK PT 0.0036).
"""

from functools import lru_cache

import numpy as np
import pytest

from spt import metrics, render

from scene_support import reference, scene, scene_image, window_with
from statistics_checks import (BIAS_FLOOR, SCENE_CHECKS, SceneRenders,
                               check_noise_falls_as_one_over_repetitions,
                               check_opaque_geometry_hides_and_cuts_the_volume,
                               check_subpixel_level_averages_subpixels)

SIZE = 128
LEVELS = {"default": (4, 16, 64), "spx": (4, 16, 64, 256), "bluntfin": (4, 16), "post": (4, 16)}
SCENES = list(LEVELS)


@lru_cache(maxsize=None)
def _rmse(name, method):
    """The RMSE of a sorted method's image: HAVS-like with k = 2 or 6, or VTK's projected
    tetrahedra."""
    mapper = {"havs2": lambda: render.havs_mapper(2), "havs6": lambda: render.havs_mapper(6),
              "pt": render.projected_tetrahedra_mapper}[method]()
    return metrics.rmse(scene_image(name, mapper, SIZE), reference(name, SIZE))


#: "paper": the paper's sampling, whose noise model the tests check; "default": the mapper
#: as users get it; "independent": the default estimator with independent thresholds, so
#: that its repetitions are independent and its noise falls exactly as 1 / L.
MODES = {"paper": render.PAPER_SAMPLING, "default": {}, "independent": {"stratified": False}}
RENDERS = {mode: SceneRenders(lambda level, seed, sampling=sampling:
                              render.spt_mapper(level, seed=seed, **sampling), LEVELS, SIZE)
           for mode, sampling in MODES.items()}


@pytest.mark.parametrize("name", SCENES)
@pytest.mark.parametrize("check", SCENE_CHECKS)
def test_scene_statistics(check, name):
    """Each check of statistics_checks.SCENE_CHECKS on each scene, with the paper's sampling."""
    SCENE_CHECKS[check](RENDERS["paper"], name)


DEFAULT_LEVELS = (1, 4)


@pytest.mark.parametrize("name", SCENES)
def test_default_estimator_is_unbiased(name):
    """The visibility estimator with exact coverage, independent thresholds: unbiased (the
    control variate's coefficient does not depend on the random numbers), so its RMSE falls
    to the same small bias floor, with noise falling as 1 / L (its repetitions are
    independent)."""
    estimates = [RENDERS["independent"].estimate(name, level) for level in DEFAULT_LEVELS]
    check_noise_falls_as_one_over_repetitions(estimates)
    assert estimates[-1].bias <= BIAS_FLOOR, f"bias {estimates[-1].bias:.4f}"


@pytest.mark.parametrize("name", SCENES)
def test_default_estimator_has_exact_alpha_and_less_noise(name):
    """Exact coverage: two seeds give the same alpha (to 8-bit rounding); the colour noise
    left is a fraction of the paper's estimator's at the same repetitions (measured 5-60 %
    of its RMSE at 4 to 256 repetitions on these scenes; required: under half its noise)."""
    first, second = (RENDERS["independent"].image(name, 4, seed) for seed in (1, 2))
    assert np.abs(first[..., 3] - second[..., 3]).max() <= 1.0 / 255.0 + 1e-6
    default, paper = RENDERS["independent"].estimate(name, 4), RENDERS["paper"].estimate(name, 4)
    assert default.alpha_noise <= 1e-6
    assert default.noise < 0.5 * paper.noise, (
        f"noise at L=4: default {default.noise:.3g}, paper {paper.noise:.3g}")


def _spt_1024_rmse(name):
    """The RMSE of the mapper as users get it (the defaults) at 1024 repetitions."""
    return metrics.rmse(RENDERS["default"].image(name, 1024, 3), reference(name, SIZE))


@pytest.mark.parametrize("name", ["spx", "bluntfin", "post"])
def test_at_1024_repetitions_as_close_as_vtk_projected_tetrahedra(name):
    """Measured against VTK's projected tetrahedra; and better than the prediction for the
    paper's sampling. (The survivor estimator alone, stratified, did not get there on the
    Oxygen Post: 0.0056 against VTK PT's 0.0044, many thin layers per pixel making the nearest
    survivor random.)"""
    pt_rmse, measured = _rmse(name, "pt"), _spt_1024_rmse(name)
    assert measured <= pt_rmse, f"SPT at 1024 {measured:.4f}, VTK PT {pt_rmse:.4f}"
    paper = RENDERS["paper"].estimate(name, LEVELS[name][-1]).predicted_rmse(1024)
    assert measured < paper, (
        f"the default {measured:.4f} is no better than the paper's sampling {paper:.4f}")


@pytest.mark.parametrize("name, method", [("torus", "havs2"), ("torus", "pt"),
                                          ("default", "havs2"), ("default", "pt")])
def test_spt_at_1024_repetitions_is_closer_than_sorted_methods(name, method):
    measured, other = _spt_1024_rmse(name), _rmse(name, method)
    assert measured < other, f"SPT at 1024 {measured:.4f}, {method} {other:.4f}"


def test_sorting_artifacts_on_thin_cells_that_spt_does_not_have():
    """Blunt Fin: measured HAVS-like k=6 0.083 and SPT (144) 0.026 at 256 x 256."""
    spt_144 = RENDERS["paper"].estimate("bluntfin", 16).predicted_rmse(144)
    havs = _rmse("bluntfin", "havs6")
    assert havs > 2.0 * spt_144, f"HAVS-like k=6 {havs:.4f}, SPT at 144 {spt_144:.4f}"
    assert _rmse("bluntfin", "havs2") > havs, "k = 2 repairs less of the order than k = 6"


def test_subpixel_level_averages_subpixels():
    check_subpixel_level_averages_subpixels(
        lambda level, subpixels, seed: render.spt_mapper(level, subpixels, seed,
                                                         **render.PAPER_SAMPLING), SIZE // 2)


@pytest.mark.parametrize("slabs", [None, 8], ids=["one slab", "8 slabs"])
def test_opaque_geometry_hides_and_cuts_the_volume(slabs):
    check_opaque_geometry_hides_and_cuts_the_volume(
        lambda level, subpixels, seed: render.spt_mapper(level, subpixels, seed,
                                                         depth_slabs=slabs), SIZE)


SLABS = 8
SLAB_SCENES = ["default", "spx", "post"]
#: The bias that a repetition level of 16 leaves hidden in the noise, at most (the bias
#: floor of these scenes is 0.001 to 0.004 against the exact reference).
BIAS_SLACK = 0.002


@lru_cache(maxsize=None)
def _slabs(slabs, estimator="visibility") -> SceneRenders:
    """Renders with ``slabs`` depth slabs and independent thresholds."""
    return SceneRenders(lambda level, seed: render.spt_mapper(
        level, seed=seed, stratified=False, estimator=estimator, depth_slabs=slabs), {}, SIZE)


def _check_bias_is_one_slabs(name, slabs, estimator="visibility"):
    split = _slabs(slabs, estimator).estimate(name, 16)
    whole = _slabs(1, estimator).estimate(name, 16)
    assert split.bias <= max(1.5 * whole.bias, whole.bias + BIAS_SLACK), (
        f"{slabs} slabs: bias {split.bias:.4f}, one slab {whole.bias:.4f}")


@pytest.mark.parametrize("name", SLAB_SCENES)
def test_depth_slabs_are_unbiased(name):
    check_noise_falls_as_one_over_repetitions(
        [_slabs(SLABS).estimate(name, level) for level in (1, 4)])
    _check_bias_is_one_slabs(name, SLABS)


@pytest.mark.parametrize("slabs, estimator", [(2, "visibility"), (3, "visibility"),
                                              (SLABS, "survivor")])
def test_any_split_and_the_survivor_estimator_are_unbiased(slabs, estimator):
    _check_bias_is_one_slabs("default", slabs, estimator)


#: The variance of a repetition with 8 slabs as a share of one slab's, at most (measured at
#: 128 x 128: 0.06 on the torus, 0.1 on the drill, 0.2 to 0.4 on these scenes).
NOISE_SHARE = 0.5


@pytest.mark.parametrize("name", SLAB_SCENES)
def test_depth_slabs_keep_the_alpha_exact_with_less_noise(name):
    first, second = (_slabs(SLABS).image(name, 4, seed) for seed in (1, 2))
    assert np.abs(first[..., 3] - second[..., 3]).max() <= 1.0 / 255.0 + 1e-6
    split, whole = _slabs(SLABS).estimate(name, 4), _slabs(1).estimate(name, 4)
    assert split.alpha_noise <= 1e-6
    assert split.noise <= NOISE_SHARE * whole.noise, (
        f"noise at L=4: {SLABS} slabs {split.noise:.3g}, one slab {whole.noise:.3g}")


def test_one_repetition_at_a_time_with_slabs():
    """The survivor estimator one repetition per render, refined progressively: with slabs
    each is a group of one with keys; the first render draws the slabs' sums with the
    coverage, the later ones use them, and the image is as close to the reference as a render
    of all its repetitions at once."""
    mapper = render.spt_mapper(1, seed=1, estimator="survivor", depth_slabs=SLABS)
    mapper.SetProgressiveRefinement(True)
    window, _ = window_with(mapper, SIZE, prop=scene("default").property)
    for _ in range(16):
        window.Render()
    progressive = render.read_rgba(window)
    window.Finalize()
    exact = reference("default", SIZE)
    at_once = _slabs(SLABS, "survivor").image("default", 16, 1)
    e = _slabs(SLABS, "survivor").estimate("default", 16)
    error = np.sqrt(np.mean((progressive - exact) ** 2))
    at_once_error = np.sqrt(np.mean((at_once - exact) ** 2))
    assert error <= at_once_error + 4.0 * np.sqrt(e.noise), (
        f"progressive {error:.4f}, at once {at_once_error:.4f}")
