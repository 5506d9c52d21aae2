"""Tetrahedra drawn as points (vtkSPTVolumeMapper's SmallCellSize) against tetrahedra drawn as
the outline of their projection, and the points' traversals in a compute pass
(ComputeTraversal) against the points themselves.

A point is a square over its cell's projection, the outline one or two triangles; the
fragments of both clip their own view ray by the cell's four face planes, and the random
numbers follow the pixel and the cell, not the primitive. So with the same seed the two are
the same image, up to the samples that lie on an edge two cells share (each primitive decides
those with its own arithmetic).

The compute pass runs one invocation per cell over the samples of its square, with the points'
fragment code, in the keys traversal and in the color traversal. The depth keys are atomic
minima, so they are the same; what the fragments add by blending (the exact coverage's terms,
the colors, the second half's colors) is added in fixed point (2^-16 per term). So with the
same seed the two images may differ only by that rounding, at most one 8-bit level, and the
compute pass's image is the same from one render to the next.

The tests compare the images pixel by pixel on the test scenes and in every mode that changes
the fragment code (POINT_CASES, COMPUTE_CASES), and check where points are not used (the camera
inside the mesh, cells whose projection would fill little of their square) and where the
compute pass is not.
"""

from functools import lru_cache
from typing import NamedTuple

import numpy as np
import pytest

from spt import render
from spt import vtkSPTVolumeMapper

from robustness_support import tetrahedra, volume_property
from scene_support import draw_once, opaque_plane, scene, window_with, with_cell_scalars

SIZE = 128
#: Most cells of the test scenes are at most 64 pixels across at 128 x 128: drawn as points.
ALL_SMALL = 64.0
#: The seeds of the points' and of the compute pass's comparisons.
POINTS_SEED, COMPUTE_SEED = 5, 3
ON, OFF, AUTO = (vtkSPTVolumeMapper.COMPUTE_TRAVERSAL_ON, vtkSPTVolumeMapper.COMPUTE_TRAVERSAL_OFF,
                 vtkSPTVolumeMapper.COMPUTE_TRAVERSAL_AUTO)

#: Where two cells share an edge, the points and the triangles may give a sample to different
#: cells. Measured: at most 0.01 % of the pixels (zoomed in) differ by more than one 8-bit
#: level, and none by more than two.
EDGE_PIXELS = 0.002
#: One 8-bit level, with room for the rounding of the read-back.
ONE_LEVEL = 1.5 / 255.0

#: The mapper's settings of the cases that change them. "paper": one repetition per traversal
#: with the depth test, so the points write their depth.
CASE_SETTINGS = {"paper": dict(render.PAPER_SAMPLING, per_pass=1),
                 "survivor": {"estimator": "survivor"},
                 "error target": {"target_error": 0.004},
                 "depth slabs": {"depth_slabs": 8}}
#: The modes that change the fragment code: "zoomed", the mesh crosses the viewport's edges
#: (squares are cut to the viewport); "cell scalars", the point scalars' cell means, drawn
#: with the point scalars' transfer functions; "opaque", an opaque plane across the mesh.
POINT_CASES = ["parallel", "zoomed", "cell scalars", "opaque", "paper"]
COMPUTE_CASES = ["cell scalars", "opaque", "zoomed", "parallel", "survivor", "error target",
                 "depth slabs"]


def _cases(modes):
    """(scene, case) of each test scene as it is, and of the default scene in each mode."""
    return [(name, "") for name in ("default", "spx", "bluntfin")] + [
        ("default", mode) for mode in modes]


class Drawn(NamedTuple):
    """A render and what its frame statistics and mapper report."""

    image: np.ndarray
    points: int  # cells drawn as points
    computed: int  # cells whose points the compute pass visited
    estimate: float
    tetrahedra: int


@lru_cache(maxsize=None)
def _render(name, seed, small_cell_size=ALL_SMALL, compute=AUTO, case="", level=16, size=SIZE):
    """The named scene in a case of POINT_CASES or COMPUTE_CASES ("": none), through a mapper
    with ``seed``; ``small_cell_size`` None keeps the mapper's default."""
    s = scene(name)
    grid = with_cell_scalars(s.grid) if case == "cell scalars" else s.grid
    view = s.view
    if case in ("zoomed", "parallel"):
        view = render.View(view.azimuth, view.elevation, zoom=2.5 if case == "zoomed" else 1.0,
                           parallel=case == "parallel")
    mapper = render.spt_mapper(level, seed=seed, **CASE_SETTINGS.get(case, {}))
    if small_cell_size is not None:
        mapper.SetSmallCellSize(small_cell_size)
    mapper.SetComputeTraversal(compute)
    actors = (opaque_plane(grid),) if case == "opaque" else ()
    image = render.render(grid, s.property, mapper, view, (size, size), actors=actors).image
    statistics = mapper.GetFrameStatistics()
    return Drawn(image, statistics.GetPointCellCount(), statistics.GetComputedCellCount(),
                 mapper.GetEstimatedError(), mapper.GetNumberOfTetrahedra())


@pytest.mark.parametrize("name, case", _cases(POINT_CASES))
def test_points_and_triangles_draw_the_same_image(name, case):
    level = 8 if case == "paper" else 16
    points = _render(name, POINTS_SEED, case=case, level=level)
    triangles = _render(name, POINTS_SEED, 0.0, case=case, level=level)
    assert triangles.points == 0, "SmallCellSize 0 draws no cell as a point"
    # The Blunt Fin's needles and slivers stay triangles (about three quarters of its cells).
    assert points.points > 0.2 * points.tetrahedra, (
        f"only {points.points} of {points.tetrahedra} cells drawn as points")
    assert triangles.image[..., 3].max() > 0.2, "the image is empty"
    difference = np.abs(points.image - triangles.image).max(axis=-1)
    assert (difference > 1.5 / 255.0).mean() < EDGE_PIXELS
    assert difference.mean() < 1e-3


@pytest.mark.parametrize("name, case", _cases(COMPUTE_CASES))
def test_compute_and_points_draw_the_same_image(name, case):
    computed = _render(name, COMPUTE_SEED, compute=ON, case=case)
    points = _render(name, COMPUTE_SEED, compute=OFF, case=case)
    assert computed.points > 0 and computed.points == points.points, "the scene draws no points"
    assert computed.computed == computed.points, (
        "the keys traversal did not visit the points in a compute pass")
    assert points.computed == 0, "ComputeTraversal off still computes"
    assert points.image[..., 3].max() > 0.2, "the image is empty"
    difference = np.abs(computed.image - points.image).max(axis=-1)
    assert difference.max() <= ONE_LEVEL, f"{name}, {case}: {difference.max() * 255} levels"
    assert difference.mean() < 1e-4
    # The error target's estimate compares the two halves' sums (the second target).
    assert computed.estimate == pytest.approx(points.estimate, rel=1e-3)


def test_points_need_the_mesh_in_front_of_the_near_plane():
    """With the camera inside the mesh every cell is drawn as triangles (their clipped path),
    and a smaller SmallCellSize draws fewer cells as points."""
    s = scene("default")
    mapper = render.spt_mapper(4)
    mapper.SetSmallCellSize(ALL_SMALL)
    window, renderer = window_with(mapper, SIZE, prop=s.property)
    renderer.GetActiveCamera().Dolly(12.0)
    renderer.ResetCameraClippingRange(s.grid.GetBounds())
    image = draw_once(window)
    assert image[..., 3].mean() > 0.05, "the view from inside is empty"
    assert mapper.GetFrameStatistics().GetPointCellCount() == 0
    small = _render("default", POINTS_SEED, 1.0)
    most = _render("default", POINTS_SEED)
    assert small.points < most.points <= most.tetrahedra


def test_needles_are_drawn_as_triangles():
    """A cell whose mean projection fills little of the square of its longest edge (a
    needle) is drawn as triangles however small; a regular one of the same size as a point.
    Both are drawn."""
    regular = [(0, 0, 0), (1, 0, 0), (0.5, 0.866, 0), (0.5, 0.289, 0.816)]
    needle = [(2, 0, 0), (3, 0, 0), (2, 0.05, 0), (2, 0, 0.05)]
    grid = tetrahedra(regular + needle, [(0, 1, 2, 3), (4, 5, 6, 7)],
                      [float(i % 4) / 3.0 for i in range(8)])
    prop = volume_property([], [(0.0, 0.5), (1.0, 0.9)], unit=0.05)
    mapper = render.spt_mapper(4)
    mapper.SetSmallCellSize(ALL_SMALL)
    image = render.render(grid, prop, mapper, render.View(azimuth=30.0, elevation=20.0),
                          (SIZE, SIZE)).image
    assert mapper.GetFrameStatistics().GetPointCellCount() == 1
    covered = image[..., 3] > 0.05
    columns = np.nonzero(covered.any(axis=0))[0]
    assert columns.size > 0, "nothing drawn"
    # Two separate footprints, the regular cell's and the needle's.
    assert np.any(np.diff(columns) > 1), "the two cells are not both drawn"


def test_compute_images_repeat():
    """The fixed-point sums do not depend on the order of the invocations: a second mapper
    (not the cached render) draws the same image."""
    first = _render("spx", COMPUTE_SEED, compute=ON)
    again = _render.__wrapped__("spx", COMPUTE_SEED, compute=ON)
    assert again.computed > 0
    np.testing.assert_array_equal(first.image, again.image)


def test_one_repetition_computes_where_most_cells_are_computed():
    """One repetition is a group of one, with keys, where the compute pass takes most of the
    cells (here every cell is a point): the image of the depth test's survivor without it."""
    computed = _render("default", COMPUTE_SEED, compute=ON, level=1)
    points = _render("default", COMPUTE_SEED, compute=OFF, level=1)
    assert computed.points > 0.5 * scene("default").grid.GetNumberOfCells()
    assert computed.computed == computed.points and points.computed == 0
    assert computed.image[..., 3].max() > 0.2
    assert np.abs(computed.image - points.image).max() <= ONE_LEVEL


def test_one_repetition_needs_no_keys():
    """Where the compute pass would take few of the cells (SPX's few hundred points at
    256 x 256), one repetition finds its survivor by the depth test: no keys to compute."""
    s = scene("spx")
    mapper = render.spt_mapper(1, seed=COMPUTE_SEED)
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


def test_two_volumes_share_the_compute_traversal():
    """Two interpenetrating volumes in one renderer: both volumes' points go through the
    compute pass into the same keys and sums."""
    s = scene("default")
    bounds = s.grid.GetBounds()
    shift = 0.3 * (bounds[1] - bounds[0])
    union = list(bounds)
    union[1] += shift
    images = []
    for compute in (ON, OFF):
        window, renderer = render.make_window(SIZE, SIZE)
        mappers = [render.spt_mapper(16, seed=COMPUTE_SEED) for _ in range(2)]
        for mapper, offset in zip(mappers, (0.0, shift)):
            mapper.SetSmallCellSize(ALL_SMALL)
            mapper.SetComputeTraversal(compute)
            render.add_volume(renderer, s.grid, s.property, mapper).SetPosition(offset, 0.0, 0.0)
        render.place_camera(renderer, union, s.view)
        images.append(draw_once(window))
        counts = [m.GetFrameStatistics().GetComputedCellCount() for m in mappers]
        points = [m.GetFrameStatistics().GetPointCellCount() for m in mappers]
        if compute == ON:
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


def test_automatic_computes_where_small_points_are_many():
    """The default computes the points about 4 pixels across or less on a software rasterizer,
    where they are at least a quarter as many as the samples: the default mesh's 47,700 points
    at 128 x 128 (16,384 samples), and the same image as without the compute pass to a level."""
    assert vtkSPTVolumeMapper().GetComputeTraversal() == AUTO
    automatic, off = (_render("default", COMPUTE_SEED, None, mode) for mode in (AUTO, OFF))
    assert automatic.points > 0 and automatic.points == off.points and off.computed == 0
    if _software_rasterizer():
        assert 0.25 * SIZE * SIZE <= automatic.computed <= automatic.points
    else:
        assert automatic.computed == 0
    assert off.image[..., 3].max() > 0.2, "the image is empty"
    assert np.abs(automatic.image - off.image).max() <= ONE_LEVEL


@pytest.mark.parametrize("name", ["default", "spx"])
def test_automatic_leaves_large_or_few_points_to_the_rasterizer(name):
    """At 256 x 256 the default mesh's points are larger than 4 pixels, and SPX has a few
    hundred points: nothing to compute."""
    automatic = _render(name, COMPUTE_SEED, None, AUTO, size=256)
    assert automatic.points > 0 and automatic.computed == 0
