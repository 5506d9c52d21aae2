"""SPT with vtkAbstractMapper's clipping planes, against the exact reference of the clipped
volume, statistically: two independent renders (seeds 1 and 2) give the noise and the bias
(image_statistics). Each segment is cut exactly where its ray crosses a plane, so the clipped
image is as unbiased as the unclipped one: its bias is the unclipped scene's to within four
standard errors, and its alpha noise is that of keeping each (cut) segment with probability
alpha. The cases: one oblique plane; two planes with the volume moved, rotated and scaled by
its matrix; the near plane cutting the mesh (segments cut by it too); the compute
traversal. A plane changed in place (as PyVista's plane widget changes it) restarts
progressive refinement; seven planes, or a plane that is not finite, give an error and
nothing drawn.
"""

import numpy as np
import pytest

import spt
from spt import metrics, render

from clipping_support import (CASES, check_bad_planes, check_clipped_is_unbiased, estimate_case,
                              image, keep_images, reference, unclipped_name, window_with)
from statistics_checks import BIAS_FLOOR, check_alpha_noise_is_bernoulli

SIZE = 128
LEVEL = 32
#: The camera dollied in until the near plane cuts the mesh.
NEAR_PLANE_CUTTING = 8.0


def _mapper(seed, compute=False):
    mapper = render.spt_mapper(LEVEL, seed=seed, **render.PAPER_SAMPLING)
    if compute:
        mapper.SetComputeTraversal(spt.vtkSPTVolumeMapper.COMPUTE_TRAVERSAL_ON)
    return mapper


def test_the_planes_cut_the_references():
    """The clipped references differ from the unclipped one, by more than any mapper's error
    here (so a mapper that ignored the planes would fail)."""
    for name, case in CASES.items():
        if case.planes:
            clipped = reference(name, SIZE)
            assert clipped[..., 3].max() > 0.2, f"{name}: the clipped reference is empty"
            assert metrics.rmse(clipped, reference(unclipped_name(name), SIZE)) > 0.02, (
                f"{name}: the planes cut nothing")


def test_a_cut_tetrahedron_is_exact():
    """One tetrahedron, one segment per ray: the default estimator (exact coverage) draws it
    without noise, so the cut segments' colours are compared exactly: within the 8-bit
    read-back of the reference (its scalars interpolated at the cut and its thickness
    shortened; the segment's uncut scalars would be 2.5 times further)."""
    name = "one tetrahedron, one"
    expected = reference(name, SIZE)
    first, second = (image(render.spt_mapper(8, seed=seed), CASES[name], SIZE)
                     for seed in (1, 2))
    keep_images("spt clipping one tetrahedron", [first, expected])
    assert np.array_equal(first, second), "one segment per ray should draw without noise"
    assert metrics.rmse(first, expected) <= 1.2 * metrics.read_back_floor(expected)
    assert metrics.rmse(expected, reference(unclipped_name(name), SIZE)) > 0.02


@pytest.mark.parametrize("name", ["one oblique", "two, moved", "coarse, two"])
def test_clipped_volume_is_unbiased(name):
    clipped = check_clipped_is_unbiased("spt", _mapper, name, SIZE, LEVEL)
    check_alpha_noise_is_bernoulli([clipped])


@pytest.mark.parametrize("where", ["near plane cutting", "compute"])
def test_clipped_segments_of_every_path(where):
    """The cells that the near plane cuts and the compute traversal's cells
    are cut by the planes too."""
    dolly, name = (NEAR_PLANE_CUTTING, "the other side") if where == "near plane cutting" \
        else (1.0, "two, moved")
    mappers = [_mapper(seed, compute=where == "compute") for seed in (1, 2)]
    clipped, images = estimate_case(mappers, name, SIZE, LEVEL, dolly)
    if where == "compute":
        computed = mappers[0].GetFrameStatistics().GetComputedCellCount()
        assert computed > 0, "no cell in the compute traversal"
    keep_images(f"spt clipping {where}", [images[0], reference(name, SIZE, dolly)])
    assert clipped.bias <= BIAS_FLOOR, f"{where}: bias {clipped.bias:.4f}"
    check_alpha_noise_is_bernoulli([clipped])
    assert metrics.rmse(reference(name, SIZE, dolly), reference("none", SIZE, dolly)) > 0.02


def test_a_plane_changed_in_place_restarts_refinement():
    """PyVista's add_volume_clip_plane widget moves the vtkPlane it gave AddClippingPlane():
    the next render must draw the new cut, not add to the old one's image."""
    mapper = _mapper(5)
    mapper.ProgressiveRefinementOn()
    w = window_with(mapper, CASES["one oblique"], SIZE)
    w.image()
    w.image()
    assert mapper.GetLastRepetitionCount() == 2 * LEVEL
    w.planes[0].SetOrigin(-0.3, 0.0, 0.0)
    w.planes[0].SetNormal(-1.0, 0.2, 0.1)
    moved = w.image()
    assert mapper.GetLastRepetitionCount() == LEVEL, "a moved plane must restart"
    fresh = w.reference()
    keep_images("spt clipping plane moved", [moved, fresh])
    before = reference("one oblique", SIZE)
    assert metrics.rmse(fresh, before) > 0.02
    assert 4.0 * metrics.rmse(moved, fresh) < metrics.rmse(moved, before)
    w.window.Finalize()


def test_more_than_six_planes_or_a_nan_plane_is_an_error():
    check_bad_planes(_mapper(1), SIZE)
