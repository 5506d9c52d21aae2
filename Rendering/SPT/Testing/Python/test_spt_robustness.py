"""vtkSPTVolumeMapper on bad and unusual input: a correct image or a clear error, never a crash,
and the input is never modified. Also: repeated renders, and images wider than 3D textures. The
cases that every mapper meets alike (empty grids, bad input, values that are not finite, vector
arrays, mixed, 2D and degenerate cells, extreme coordinates, transfer functions of no or one
point, input changed between renders, releases, resizes and a second window) are
test_mapper_robustness.py's, for SPT too."""

import numpy as np
import pytest
import vtk

from spt import data, metrics, render

from robustness_support import (ONE, UNIT_TETRAHEDRON, property_for, tetrahedra, watch,
                                watched_render, with_constant_scalars)

SIZE = (96, 96)


def draw(grid, prop=None, mapper=None, repetitions=8):
    """Render and return (image, mapper, messages); the input must not change."""
    mapper = mapper or render.spt_mapper(repetitions, seed=1)
    rendering, messages = watched_render(mapper, grid, prop, SIZE)
    return rendering.image, mapper, messages


def test_one_tetrahedron_renders():
    image, mapper, messages = draw(ONE)
    assert not messages.errors
    assert mapper.GetNumberOfTetrahedra() == 1
    assert image[..., 3].max() > 0.2


def test_short_global_ids_are_a_clear_error():
    grid = tetrahedra(UNIT_TETRAHEDRON + [(1, 1, 1)], [(0, 1, 2, 3), (1, 2, 3, 4)],
                      [0.0, 0.3, 0.6, 1.0, 0.5])
    ids = vtk.vtkIdTypeArray()
    ids.SetName("ids")
    ids.InsertNextValue(7)
    grid.GetCellData().SetGlobalIds(ids)
    image, _, messages = draw(grid)
    assert len(messages.errors) == 1, messages.errors
    assert "GlobalIds array 'ids' has 1 values for 2 cells" in messages.errors[0]
    assert image.max() == 0.0


def test_constant_field_matches_the_reference():
    grid = with_constant_scalars(data.make_default_mesh())
    prop = property_for(0.0, 1.0, unit=0.3, opacity=0.5)
    image, _, messages = draw(grid, prop, repetitions=64)
    reference = render.reference(grid, prop, render.View(30, 30), SIZE).image
    assert not messages.errors
    assert metrics.rmse(image, reference) < 0.05


@pytest.mark.parametrize("sampling", [render.PAPER_SAMPLING, {}])
def test_opacity_one_everywhere(sampling):
    """Opacity 1 over a tenth of the tetrahedron's size: the paper's estimator keeps the
    nearest segment in every repetition, so almost every covered pixel is opaque at once; the
    default's exact coverage is the reference's, opaque inside and fractional only at the
    silhouette, where a ray crosses little of the cell."""
    prop = property_for(opacity=1.0, unit=0.01)
    image, _, messages = draw(ONE, prop, render.spt_mapper(4, seed=1, **sampling))
    assert not messages.errors
    covered = image[..., 3] > 0
    assert covered.sum() > 50
    if sampling:
        assert np.mean(image[..., 3][covered] > 0.99) > 0.9
    else:
        exact = render.reference(ONE, prop, render.View(30, 30), SIZE).image[..., 3]
        assert np.mean(image[..., 3][exact > 0.999] > 0.99) > 0.97
        assert np.abs(image[..., 3] - exact).mean() < 0.01


def test_repeated_renders_are_identical_and_do_not_accumulate():
    """The ensemble is cleared every frame, also for a viewport away from the window's origin
    (the renderer's scissor box must not keep the clear from reaching it)."""
    window, renderer = render.make_window(2 * SIZE[0], SIZE[1])
    renderer.SetViewport(0.5, 0.0, 1.0, 1.0)
    grid = data.make_default_mesh()
    render.add_volume(renderer, grid, data.default_transfer_function(grid),
                      render.spt_mapper(8, seed=1))
    window.Render()
    first = render.read_rgba(window)
    for _ in range(3):
        window.Render()
    assert first[..., 3].max() > 0.2
    assert np.array_equal(render.read_rgba(window), first)


def test_an_image_wider_than_3d_textures_draws_the_same_image():
    """The depth keys of several repetitions and the compute traversal's sums are 3D textures
    of (repetition, sample), at most GL_MAX_3D_TEXTURE_SIZE per side (2048 on llvmpipe). A wider
    image draws one repetition per traversal pair, with the depth test, and rasterizes every
    cell: the image of RepetitionsPerPass 1, with a warning. The error target needs the keys:
    a clear error there."""
    grid = data.make_default_mesh()
    prop = data.default_transfer_function(grid)
    size = (2100, 48)
    view = render.View(30, 30, zoom=4.0)
    grouped = render.spt_mapper(4, seed=1)
    grouped.SetComputeTraversal(grouped.COMPUTE_TRAVERSAL_ON)
    messages = watch(grouped)
    image = render.render(grid, prop, grouped, view, size).image
    single = render.render(grid, prop, render.spt_mapper(4, seed=1, per_pass=1), view, size).image
    assert not messages.errors, messages.errors
    assert image[..., 3].max() > 0.2, "the image is (almost) empty"
    assert np.abs(image - single).max() <= 1.0 / 255.0 + 1e-6
    if not messages.warnings:
        pytest.skip("this OpenGL's 3D textures hold 2100 texels per side")
    assert len(messages.warnings) == 1 and "GL_MAX_3D_TEXTURE_SIZE" in messages.warnings[0]
    target = render.spt_mapper(16, seed=1, target_error=0.01)
    target_messages = watch(target)
    blank = render.render(grid, prop, target, view, size).image
    assert target_messages.errors and "GL_MAX_3D_TEXTURE_SIZE" in target_messages.errors[0]
    assert blank.max() == 0.0
