"""Tetrahedra drawn as points (vtkSPTVolumeMapper's SmallCellSize) against tetrahedra drawn as
the outline of their projection.

A point is a square over its cell's projection, the outline one or two triangles; the
fragments of both clip their own view ray by the cell's four face planes, and the random
numbers follow the pixel and the cell, not the primitive. So with the same seed the two are
the same image, up to the samples that lie on an edge two cells share (each primitive decides
those with its own arithmetic). The tests compare them pixel by pixel, with and without
opaque geometry, in perspective and parallel projection, zoomed in until the mesh crosses the
viewport's edges, with cell scalars and with the paper's single passes; and check where points
are not used: with the camera inside the mesh, and for cells whose projection would fill
little of their square.
"""

from functools import lru_cache

import numpy as np
import pytest

from spt import render

from robustness_support import tetrahedra, volume_property
from scene_support import draw_once, opaque_plane, scene, window_with, with_cell_scalars

SIZE = 128
#: Most cells of the test scenes are at most 64 pixels across at 128 x 128.
ALL_SMALL = 64.0

#: Where two cells share an edge, the points and the triangles may give a sample to different
#: cells. Measured: at most 0.01 % of the pixels (zoomed in) differ by more than one 8-bit
#: level, and none by more than two.
EDGE_PIXELS = 0.002


def _grid(name, cell_scalars=False):
    grid = scene(name).grid
    return with_cell_scalars(grid) if cell_scalars else grid


@lru_cache(maxsize=None)
def _render(name, small_cell_size, view=None, cell_scalars=False, opaque=False, paper=False,
            level=16):
    s = scene(name)
    grid = _grid(name, cell_scalars)
    prop = s.property  # the point scalars' transfer functions, also for their cell means
    sampling = render.PAPER_SAMPLING if paper else {}
    mapper = render.spt_mapper(level, seed=5, **sampling)
    mapper.SetSmallCellSize(small_cell_size)
    if paper:
        mapper.SetRepetitionsPerPass(1)
    actors = (opaque_plane(grid),) if opaque else ()
    result = render.render(grid, prop, mapper, view or s.view, (SIZE, SIZE), actors=actors)
    points = mapper.GetFrameStatistics().GetPointCellCount()
    return result.image, points, mapper.GetNumberOfTetrahedra()


def _check_same_image(points, triangles):
    image, count, tetrahedra = points
    other, none, _ = triangles
    assert none == 0, "SmallCellSize 0 draws no cell as a point"
    # The Blunt Fin's needles and slivers stay triangles (about three quarters of its cells).
    assert count > 0.2 * tetrahedra, f"only {count} of {tetrahedra} cells drawn as points"
    assert other[..., 3].max() > 0.2, "the image is empty"
    difference = np.abs(image - other).max(axis=-1)
    assert (difference > 1.5 / 255.0).mean() < EDGE_PIXELS
    assert difference.mean() < 1e-3


@pytest.mark.parametrize("name", ["default", "spx", "bluntfin"])
def test_points_and_triangles_draw_the_same_image(name, have_display):
    _check_same_image(_render(name, ALL_SMALL), _render(name, 0.0))


@pytest.mark.parametrize("case", ["parallel", "zoomed", "cell scalars", "opaque", "paper"])
def test_points_draw_the_same_image_in_every_mode(case, have_display):
    view = scene("default").view
    options = {
        "parallel": {"view": render.View(view.azimuth, view.elevation, parallel=True)},
        # The mesh crosses the viewport's edges: squares are cut to the viewport.
        "zoomed": {"view": render.View(view.azimuth, view.elevation, zoom=2.5)},
        "cell scalars": {"cell_scalars": True},
        "opaque": {"opaque": True},
        # One repetition per traversal with the depth test: the points write their depth.
        "paper": {"paper": True, "level": 8},
    }[case]
    _check_same_image(_render("default", ALL_SMALL, **options),
                      _render("default", 0.0, **options))


def test_points_need_the_mesh_in_front_of_the_near_plane(have_display):
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
    _, small, tetrahedra = _render("default", 1.0)
    _, most, _ = _render("default", ALL_SMALL)
    assert small < most <= tetrahedra


def test_needles_are_drawn_as_triangles(have_display):
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
