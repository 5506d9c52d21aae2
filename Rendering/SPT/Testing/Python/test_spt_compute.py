"""The traversals of the cells drawn as points in a compute pass (vtkSPTVolumeMapper's
ComputeTraversal) against the points themselves.

One invocation per cell visits the samples of its square and runs the points' fragment code
there, in the keys traversal and in the color traversal. The depth keys are atomic minima, so
they are the same; what the fragments add by blending (the exact coverage's terms, the colors,
the second half's colors) is added in fixed point (2^-16 per term). So with the same seed the
two images may differ only by that rounding, at most one 8-bit level, and the compute pass's
image is the same from one render to the next. The tests compare them pixel by pixel on the
test scenes and in every mode that changes the fragment code (cell scalars, opaque geometry, a
zoom that cuts squares at the viewport, parallel projection, the survivor estimator, the error
target's two halves, depth slabs, whose control variate adds negative terms, two volumes in one
view), and check where the compute pass is not used.
"""

from functools import lru_cache

import numpy as np
import pytest

from spt import render
from spt import vtkSPTVolumeMapper

from scene_support import opaque_plane, scene, with_cell_scalars

SIZE = 128
#: Most cells of the test scenes are at most 64 pixels across at 128 x 128: drawn as points.
ALL_SMALL = 64.0
#: One 8-bit level, with room for the rounding of the read-back.
ONE_LEVEL = 1.5 / 255.0


@lru_cache(maxsize=None)
def _render(name, compute, case="", level=16):
    s = scene(name)
    grid = with_cell_scalars(s.grid) if case == "cell scalars" else s.grid
    view = s.view
    if case == "zoomed":
        view = render.View(view.azimuth, view.elevation, zoom=2.5)
    if case == "parallel":
        view = render.View(view.azimuth, view.elevation, parallel=True)
    options = {"survivor": {"estimator": "survivor"},
               "error target": {"target_error": 0.004},
               "depth slabs": {"depth_slabs": 8}}.get(case, {})
    mapper = render.spt_mapper(level, seed=3, **options)
    mapper.SetSmallCellSize(ALL_SMALL)
    mapper.SetComputeTraversal(compute)
    actors = (opaque_plane(grid),) if case == "opaque" else ()
    image = render.render(grid, s.property, mapper, view, (SIZE, SIZE), actors=actors).image
    statistics = mapper.GetFrameStatistics()
    return (image, statistics.GetPointCellCount(), statistics.GetComputedCellCount(),
            mapper.GetEstimatedError())


def _check_same_image(name, case="", level=16):
    image, points, computed, estimate = _render(name, True, case, level)
    other, other_points, none, other_estimate = _render(name, False, case, level)
    assert points > 0 and points == other_points, "the scene draws no points"
    assert computed == points, "the keys traversal did not visit the points in a compute pass"
    assert none == 0, "ComputeTraversal off still computes"
    assert other[..., 3].max() > 0.2, "the image is empty"
    difference = np.abs(image - other).max(axis=-1)
    assert difference.max() <= ONE_LEVEL, f"{name}, {case}: {difference.max() * 255} levels"
    assert difference.mean() < 1e-4
    # The error target's estimate compares the two halves' sums (the second target).
    assert estimate == pytest.approx(other_estimate, rel=1e-3)


@pytest.mark.parametrize("name", ["default", "spx", "bluntfin"])
def test_compute_and_points_draw_the_same_image(name, have_display):
    _check_same_image(name)


@pytest.mark.parametrize("case", ["cell scalars", "opaque", "zoomed", "parallel", "survivor",
                                  "error target", "depth slabs"])
def test_compute_draws_the_same_image_in_every_mode(case, have_display):
    _check_same_image("default", case)


def test_compute_images_repeat(have_display):
    """The fixed-point sums do not depend on the order of the invocations."""
    first = _render("spx", True)[0]
    s = scene("spx")
    mapper = render.spt_mapper(16, seed=3)
    mapper.SetSmallCellSize(ALL_SMALL)
    mapper.ComputeTraversalOn()
    again = render.render(s.grid, s.property, mapper, s.view, (SIZE, SIZE)).image
    assert mapper.GetFrameStatistics().GetComputedCellCount() > 0
    np.testing.assert_array_equal(first, again)


def test_one_repetition_computes_where_most_cells_are_computed(have_display):
    """One repetition is a group of one, with keys, where the compute pass takes most of the
    cells (here every cell is a point): the image of the depth test's survivor without it."""
    image, points, computed, _ = _render("default", True, level=1)
    other, other_points, none, _ = _render("default", False, level=1)
    assert points > 0.5 * scene("default").grid.GetNumberOfCells()
    assert computed == points and none == 0
    assert image[..., 3].max() > 0.2
    assert np.abs(image - other).max() <= ONE_LEVEL


def test_one_repetition_needs_no_keys(have_display):
    """Where the compute pass would take few of the cells (SPX's few hundred points at
    256 x 256), one repetition finds its survivor by the depth test: no keys to compute."""
    s = scene("spx")
    mapper = render.spt_mapper(1, seed=3)
    mapper.ComputeTraversalOn()
    image = render.render(s.grid, s.property, mapper, s.view, (256, 256)).image
    points = mapper.GetFrameStatistics().GetPointCellCount()
    assert 0 < points < 0.5 * s.grid.GetNumberOfCells()
    assert mapper.GetFrameStatistics().GetComputedCellCount() == 0
    assert image[..., 3].max() > 0.2
    mapper.SetRepetitionLevel(2)
    render.render(s.grid, s.property, mapper, s.view, (256, 256))
    computed = mapper.GetFrameStatistics().GetComputedCellCount()
    assert computed == points, "a group computes every point"


def test_two_volumes_share_the_compute_traversal(have_display):
    """Two interpenetrating volumes in one renderer: both volumes' points go through the
    compute pass into the same keys and sums."""
    s = scene("default")
    bounds = s.grid.GetBounds()
    shift = 0.3 * (bounds[1] - bounds[0])
    images = []
    for compute in (True, False):
        window, renderer = render.make_window(SIZE, SIZE)
        mappers = []
        for offset in (0.0, shift):
            mapper = render.spt_mapper(16, seed=3)
            mapper.SetSmallCellSize(ALL_SMALL)
            mapper.SetComputeTraversal(compute)
            render.add_volume(renderer, s.grid, s.property, mapper).SetPosition(offset, 0.0, 0.0)
            mappers.append(mapper)
        union = list(bounds)
        union[1] += shift
        render.place_camera(renderer, union, s.view)
        window.Render()
        images.append(render.read_rgba(window))
        counts = [m.GetFrameStatistics().GetComputedCellCount() for m in mappers]
        points = [m.GetFrameStatistics().GetPointCellCount() for m in mappers]
        window.Finalize()
        if compute:
            assert all(p > 0 for p in points) and counts == points
        else:
            assert counts == [0, 0]
    assert images[1][..., 3].max() > 0.2, "the image is empty"
    assert np.abs(images[0] - images[1]).max() <= ONE_LEVEL


def _software_rasterizer():
    window, _ = render.make_window(16, 16)
    window.Render()
    capabilities = window.ReportCapabilities()
    window.Finalize()
    return any(name in capabilities for name in ("llvmpipe", "softpipe", "SwiftShader"))


def _automatic(name, size):
    s = scene(name)
    counts = []
    images = []
    for mode in (vtkSPTVolumeMapper.COMPUTE_TRAVERSAL_AUTO,
                 vtkSPTVolumeMapper.COMPUTE_TRAVERSAL_OFF):
        mapper = render.spt_mapper(16, seed=3)
        mapper.SetComputeTraversal(mode)
        images.append(render.render(s.grid, s.property, mapper, s.view, (size, size)).image)
        statistics = mapper.GetFrameStatistics()
        counts.append((statistics.GetPointCellCount(), statistics.GetComputedCellCount()))
    return counts, images


def test_automatic_computes_where_small_points_are_many(have_display):
    """The default computes the points about 4 pixels across or less on a software rasterizer,
    where they are at least a quarter as many as the samples: the default mesh's 47,700 points
    at 128 x 128 (16,384 samples), and the same image as without the compute pass to a level."""
    assert vtkSPTVolumeMapper().GetComputeTraversal() == \
        vtkSPTVolumeMapper.COMPUTE_TRAVERSAL_AUTO
    counts, images = _automatic("default", SIZE)
    (points, computed), (off_points, none) = counts
    assert points > 0 and points == off_points and none == 0
    if _software_rasterizer():
        assert 0.25 * SIZE * SIZE <= computed <= points
    else:
        assert computed == 0
    assert images[1][..., 3].max() > 0.2, "the image is empty"
    assert np.abs(images[0] - images[1]).max() <= ONE_LEVEL


@pytest.mark.parametrize("name", ["default", "spx"])
def test_automatic_leaves_large_or_few_points_to_the_rasterizer(name, have_display):
    """At 256 x 256 the default mesh's points are larger than 4 pixels, and SPX has a few
    hundred points: nothing to compute."""
    (points, computed), _ = _automatic(name, 256)[0]
    assert points > 0 and computed == 0
