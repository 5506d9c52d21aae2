"""The HAVS-like and PBVR baselines with vtkAbstractMapper's clipping planes, against the exact
reference of the clipped volume (spt.raycast with the same planes and the volume's matrix).

HAVS cuts each segment between two of a pixel's sorted fragments where the ray crosses a
plane: a cut tetrahedron is drawn exactly (within the 8-bit read-back), and a clipped mesh is
as close to its reference as the unclipped mesh is to its own over the same pixels (1.5 times,
as test_havs.py's margins), in perspective and in parallel projection. PBVR keeps the
particles on the kept side of every plane: its bias against the clipped reference is that of
the unclipped scene to within four standard errors, measured from two seeds. Seven planes, or a
plane that is not finite, give an error and nothing drawn.
"""

import pytest

from spt import metrics, render

from clipping_support import (CASES, check_bad_planes, check_clipped_is_unbiased, image,
                              keep_images, reference, unclipped_name)

SIZE = 128
PBVR_LEVEL = 64
CLIPPED = ["one oblique", "two, moved", "coarse, two"]


@pytest.mark.parametrize("parallel", [False, True])
def test_havs_draws_a_cut_tetrahedron_exactly(parallel):
    name = "one tetrahedron, one"
    expected = reference(name, SIZE, parallel=parallel)
    drawn = image(render.havs_mapper(), CASES[name], SIZE, parallel=parallel)
    keep_images(f"havs clipping one tetrahedron {parallel}", [drawn, expected])
    assert metrics.rmse(drawn, expected) <= 1.2 * metrics.read_back_floor(expected)
    assert metrics.rmse(expected, reference(unclipped_name(name), SIZE, parallel=parallel)) > 0.02


@pytest.mark.parametrize("parallel", [False, True])
@pytest.mark.parametrize("name", CLIPPED)
def test_havs_clipped_is_as_close_as_unclipped(name, parallel):
    other = unclipped_name(name)
    clipped = image(render.havs_mapper(), CASES[name], SIZE, parallel=parallel)
    unclipped = image(render.havs_mapper(), CASES[other], SIZE, parallel=parallel)
    expected = reference(name, SIZE, parallel=parallel)
    expected_unclipped = reference(other, SIZE, parallel=parallel)
    keep_images(f"havs clipping {name} {parallel}", [clipped, expected])
    # Over the same pixels, the unclipped footprint (HAVS's few wrong pixels on silhouettes,
    # where the k-buffer sees grazing faces, are the same with and without the planes).
    pixels = metrics.footprint(unclipped, expected_unclipped)
    error = metrics.rmse(clipped, expected, pixels)
    unclipped_error = metrics.rmse(unclipped, expected_unclipped, pixels)
    assert error <= 1.5 * unclipped_error, (error, unclipped_error)
    error = metrics.rmse(clipped, expected)
    assert error <= 0.008
    ignored = metrics.rmse(clipped, expected_unclipped)
    assert ignored > 5.0 * error, f"{name}: the planes changed too little ({ignored:.4f})"


@pytest.mark.parametrize("name", CLIPPED)
def test_pbvr_clipped_is_unbiased(name):
    check_clipped_is_unbiased("pbvr", lambda seed: render.pbvr_mapper(PBVR_LEVEL, seed=seed),
                              name, SIZE, PBVR_LEVEL)


@pytest.mark.parametrize("mapper", ["havs", "pbvr"])
def test_more_than_six_planes_or_a_nan_plane_is_an_error(mapper):
    check_bad_planes(render.havs_mapper() if mapper == "havs"
                     else render.pbvr_mapper(8, seed=1), SIZE)
