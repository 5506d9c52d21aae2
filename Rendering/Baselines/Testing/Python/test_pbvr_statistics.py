"""PBVR against the reference, statistically: fixed seeds, tolerances from the repetition count,
as test_spt_statistics does for SPT.

For SPX and Blunt Fin (128 x 128), two independent PBVR renders (seeds 1 and 2) per repetition
level give the noise and the bias against the reference (image_statistics). The tests check that
- the noise is Monte Carlo noise: L x noise is the same at every level L;
- the alpha noise is that of one opaque particle or none per pixel and set: a (1 - a) / L;
- the RMSE falls as expected to a small bias floor: PBVR converges to the reference;
- a constant field (optical depth known along every ray) is unbiased inside the footprint, in
  perspective (where the particles are thinned to their depth's pixel size) and in parallel;
- SubpixelLevel 2 averages 2x2 subpixels; opaque geometry hides and cuts the volume;
- with a steep transfer function, exact in-cell density (rejection) keeps the thin features
  that the papers' cell-average density loses.
Tolerances and references are those of test_spt_statistics.
"""

import math

import numpy as np
import pytest
from scipy import ndimage

from spt import data, render, scenes

import image_statistics
from robustness_support import property_for, with_constant_scalars
from spt_pytest_fixtures import load_or_skip
from statistics_checks import (BIAS_FLOOR, SCENE_CHECKS, Z, SceneRenders,
                               check_opaque_geometry_hides_and_cuts_the_volume,
                               check_subpixel_level_averages_subpixels)

SIZE = 128
LEVELS = {"spx": (4, 16, 64, 256), "bluntfin": (4, 16, 64)}
SCENES = list(LEVELS)
PBVR = SceneRenders(lambda level, seed: render.pbvr_mapper(level, seed=seed), LEVELS, SIZE)


@pytest.mark.parametrize("name", SCENES)
@pytest.mark.parametrize("check", SCENE_CHECKS)
def test_scene_statistics(check, name):
    """Each check of statistics_checks.SCENE_CHECKS on each scene."""
    SCENE_CHECKS[check](PBVR, name)


@pytest.mark.parametrize("parallel", [False, True])
def test_constant_field_is_unbiased_inside_the_footprint(parallel):
    """alpha = 1 - exp(-tau d) along every ray. Away from the silhouettes (where a particle
    averages the optical depth over its pixel and the reference samples the pixel centre),
    the mean alpha of PBVR equals the reference's within its standard error, also with the
    camera close (perspective thinning over a wide range of depths)."""
    grid = with_constant_scalars(data.make_default_mesh())
    prop = property_for(0.0, 1.0, unit=0.3, opacity=0.5)
    level = 64
    for zoom in (1.0, 1.8):
        view = render.View(30, 30, zoom=zoom, parallel=parallel)
        reference = render.reference(grid, prop, view, (SIZE, SIZE)).image
        images = [render.render(grid, prop, render.pbvr_mapper(level, seed=seed), view,
                                (SIZE, SIZE), frames=0).image for seed in (1, 2)]
        # Two pixels in from the footprint's edge (3 x 3 neighbourhoods).
        interior = ndimage.binary_erosion(reference[..., 3] > 0.01, np.ones((3, 3)), iterations=2)
        difference = (0.5 * (images[0] + images[1]) - reference)[..., 3][interior]
        noise = (0.5 * (images[0] - images[1]))[..., 3][interior]
        tolerance = Z * noise.std() / math.sqrt(difference.size) + 0.001
        assert interior.sum() > 1000
        assert abs(difference.mean()) <= tolerance, (
            f"zoom {zoom}: mean alpha difference {difference.mean():+.5f} "
            f"(tolerance {tolerance:.5f})")


def test_subpixel_level_averages_subpixels():
    check_subpixel_level_averages_subpixels(
        lambda level, subpixels, seed: render.pbvr_mapper(level, subpixels, seed), SIZE // 2)


def test_opaque_geometry_hides_and_cuts_the_volume():
    check_opaque_geometry_hides_and_cuts_the_volume(
        lambda level, subpixels, seed: render.pbvr_mapper(level, subpixels, seed), SIZE)


def test_rejection_keeps_thin_features_that_the_cell_average_loses():
    """Blunt Fin with a steep transfer function (a thin shell around 30 % of the density
    range): rejection sampling converges to the reference; the cell-average density of the
    papers is biased several times more than the noise at 64 repetitions."""
    grid = load_or_skip("bluntfin")
    prop = data.transfer_function(grid, "steep", steep_center=0.3)
    view = scenes.scene("bluntfin").view
    reference = render.reference(grid, prop, view, (SIZE, SIZE)).image
    level = 64
    biases = {}
    for cell_average in (False, True):
        first, second = (render.render(grid, prop, render.pbvr_mapper(level, seed=seed,
                                                                      cell_average=cell_average),
                                       view, (SIZE, SIZE), frames=0).image
                         for seed in (1, 2))
        biases[cell_average] = image_statistics.estimate(first, second, reference, level)
    exact, average = biases[False], biases[True]
    assert exact.bias <= BIAS_FLOOR, f"rejection: bias {exact.bias:.4f}"
    assert average.bias >= 4.0 * max(exact.bias, 0.005), (
        f"cell average: bias {average.bias:.4f}, rejection {exact.bias:.4f}")
    assert average.bias >= math.sqrt(average.noise), "the cell-average bias is hidden in noise"
