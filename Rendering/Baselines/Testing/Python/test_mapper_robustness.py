"""The HAVS-like and PBVR mappers on bad and unusual input, and SPT on the cases that every
mapper meets alike (ALL_KINDS; SPT's own: test_spt_robustness.py): each case gives an image
close to the reference or a clear error that names the problem, never a crash or a silently
wrong image, and the input is left exactly as it was.
Then: the input changed between renders, released resources, several windows, resizes and a
zero-size viewport.

HAVS is deterministic and sorted: it is compared with the exact reference directly. PBVR is
stochastic: two renders with different seeds give its bias against the reference without its
noise (image_statistics), and a fixed seed gives the same image for the same input, so that
"the same picture as a fresh mapper" is an exact comparison for both.
"""

import math

import numpy as np
import pytest
import vtk
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy

from spt import metrics, render

import image_statistics
from robustness_support import (ONE, UNIT_TETRAHEDRON, named_array, property_for, split_box,
                                tetrahedra, volume_property, watch, watched_render,
                                with_constant_scalars, with_point_scalars)
from scene_support import draw_once

SIZE = (64, 64)
VIEW = render.View(30, 30)
KINDS = ["havs", "pbvr"]
#: For the cases that every mapper meets alike, among them those the fuzz test found
#: (test_fuzz.py). SPT's own cases: test_spt_robustness.py.
ALL_KINDS = ["spt"] + KINDS
PBVR_LEVEL = 64  # repetitions of the renders compared with the reference
Z = 4.0  # standard errors


def make_mapper(kind, seed=1):
    if kind == "spt":
        return render.spt_mapper(8, seed=seed)
    return render.havs_mapper(6) if kind == "havs" else render.pbvr_mapper(PBVR_LEVEL, seed=seed)


def draw(kind, grid, prop=None, mapper=None, seed=1):
    """Render with a fresh mapper of `kind` (or `mapper`); returns (image, mapper, messages).
    The input must be unchanged afterwards."""
    mapper = mapper or make_mapper(kind, seed)
    rendering, messages = watched_render(mapper, grid, prop, SIZE, VIEW)
    assert np.isfinite(rendering.image).all()
    return rendering.image, mapper, messages


def assert_matches_reference(kind, grid, prop, havs_rmse, pbvr_bias):
    """HAVS within `havs_rmse` of the exact reference; PBVR's bias (its noise removed) within
    `pbvr_bias`. Both without an error, and the reference is not empty. Returns the mapper."""
    reference = render.reference(grid, prop, VIEW, SIZE).image
    assert reference[..., 3].max() > 0.1, "the reference is (almost) empty"
    first, mapper, messages = draw(kind, grid, prop, seed=1)
    assert not messages.errors, messages.errors
    if kind == "havs":
        error = metrics.rmse(first, reference)
        assert error <= havs_rmse, f"RMSE {error:.4f} against the reference"
    else:
        second, _, _ = draw(kind, grid, prop, seed=2)
        e = image_statistics.estimate(first, second, reference, PBVR_LEVEL)
        # The squared bias within Z standard errors of pbvr_bias^2 or less.
        assert e.bias2 <= pbvr_bias ** 2 + Z * e.bias2_error, (
            f"bias {e.bias:.4f} (squared {e.bias2:.2g} +- {e.bias2_error:.2g}) against the "
            f"reference")
    return mapper


def assert_same_picture(kind, image, expected, havs_rmse=0.0):
    """HAVS, and SPT (its random numbers follow the pixel and the cell): the same image (or
    within havs_rmse). PBVR, whose particles may have been made for another view and thinned,
    or for other tetrahedra: the same total coverage within Z standard errors of its noise
    (each pixel's alpha is a mean of PBVR_LEVEL Bernoulli trials), and no pixel far off."""
    if kind != "pbvr":
        assert metrics.rmse(image, expected) <= havs_rmse if havs_rmse else \
            np.array_equal(image, expected)
        return
    alpha = np.clip(expected[..., 3], 0.0, 1.0)
    sigma = math.sqrt(2.0 * np.sum(alpha * (1.0 - alpha)) / PBVR_LEVEL)
    difference = float(image[..., 3].sum() - expected[..., 3].sum())
    assert abs(difference) <= Z * sigma + 1.0, f"coverage differs by {difference:.1f} pixels"
    assert metrics.rmse(image, expected) <= 0.2


class Scene:
    """One mapper in one window, drawn again and again: ``grid`` with ``prop`` (by default
    property_for() of opacity 0.6), ``bounds`` (by default the grid's) framed from VIEW."""

    def __init__(self, kind, grid, prop=None, bounds=None):
        self.kind, self.grid = kind, grid
        self.prop = prop or property_for(0.0, 1.0, unit=1.0, opacity=0.6)
        self.mapper = make_mapper(kind)
        self.messages = watch(self.mapper)
        self.window, self.renderer = render.make_window(*SIZE)
        self.volume = render.add_volume(self.renderer, grid, self.prop, self.mapper)
        render.place_camera(self.renderer, bounds or grid.GetBounds(), VIEW)

    def draw(self):
        self.window.Render()
        assert not self.messages.errors, self.messages.errors
        return render.read_rgba(self.window)

    def fresh(self):
        """What a new mapper draws for a deep copy of the input with this scene's camera."""
        copy = vtk.vtkUnstructuredGrid()
        copy.DeepCopy(self.grid)
        window, renderer = render.make_window(*self.window.GetSize())
        render.add_volume(renderer, copy, self.prop, make_mapper(self.kind))
        renderer.SetActiveCamera(self.renderer.GetActiveCamera())
        return draw_once(window)


def field_grid():
    """A small box split into tetrahedra with a smooth point field and a cell field."""
    grid = split_box((3, 3, 3),
                     lambda p: 0.5 + 0.5 * np.sin(p[:, 0] + 0.7 * p[:, 1] - 0.4 * p[:, 2]))
    grid.GetCellData().AddArray(named_array(np.arange(grid.GetNumberOfCells()) % 5 / 4.0, "c"))
    return grid


def cell_scalars_grid():
    """field_grid() with its cell field as the scalars."""
    grid = field_grid()
    grid.GetPointData().SetActiveScalars(None)
    grid.GetCellData().SetActiveScalars("c")
    return grid


def _cells_without_points():
    grid = vtk.vtkUnstructuredGrid()
    grid.InsertNextCell(vtk.VTK_TETRA, 4, [0, 1, 2, 3])
    grid.GetCellData().SetScalars(named_array(np.array([0.5]), "c"))
    return grid


def _pyramid_of_four_points():
    """mixed_cells() and a pyramid given four points: its split would read a fifth."""
    grid = mixed_cells()
    grid.InsertNextCell(vtk.VTK_PYRAMID, 4, [0, 1, 2, 3])
    return grid


def _select_point_array(mapper):
    mapper.SetScalarModeToUsePointFieldData()
    mapper.SelectScalarArray("pressure")


def _select_component_3(mapper):
    mapper.SetVectorModeToComponent()
    mapper.SetVectorComponent(3)


# Bad input that every mapper refuses with one clear error and draws nothing: the input, a
# change to the mapper, a change to the property (property_for()), and the words of the error.
BAD_INPUT = {
    "no scalars": (lambda: tetrahedra(UNIT_TETRAHEDRON, [(0, 1, 2, 3)]), None, None,
                   ["no scalars"]),
    "missing array": (lambda: ONE, _select_point_array, None, ["'pressure'"]),
    "point id 7": (lambda: tetrahedra(UNIT_TETRAHEDRON, [(0, 1, 2, 3), (0, 1, 2, 7)],
                                      [0.0, 0.3, 0.6, 1.0]), None, None, ["point id 7"]),
    "point id -1": (lambda: tetrahedra(UNIT_TETRAHEDRON, [(0, 1, 2, 3), (0, 1, -1, 3)],
                                       [0.0, 0.3, 0.6, 1.0]), None, None, ["point id -1"]),
    "cells without points": (_cells_without_points, None, None, ["point id 0", "0 points"]),
    "a pyramid of 4 points": (_pyramid_of_four_points, None, None,
                              ["has 4 points; that type has 5"]),
    "component 3": (lambda: ONE, _select_component_3, None, ["Component 3"]),
    "dependent components": (lambda: ONE, None, lambda prop: prop.IndependentComponentsOff(),
                             ["IndependentComponents"]),
    "unit distance 0": (lambda: ONE, None, lambda prop: prop.SetScalarOpacityUnitDistance(0.0),
                        ["ScalarOpacityUnitDistance"]),
}


# --- One tetrahedron, empty and incomplete input ----------------------------------------------

@pytest.mark.parametrize("kind", ALL_KINDS)
@pytest.mark.parametrize("points", [0, 4])
def test_empty_grid_draws_nothing_without_error(kind, points):
    grid = tetrahedra(UNIT_TETRAHEDRON[:points], [], [0.1] * points) if points else \
        vtk.vtkUnstructuredGrid()
    image, mapper, messages = draw(kind, grid)
    assert not messages.errors and mapper.GetNumberOfTetrahedra() == 0
    assert image.max() == 0.0


@pytest.mark.parametrize("kind", ALL_KINDS)
@pytest.mark.parametrize("case", BAD_INPUT)
def test_bad_input_is_a_clear_error(kind, case):
    """One error that names the problem (a bad property is reported at each of its checks),
    and nothing drawn."""
    make_grid, change_mapper, change_property, words = BAD_INPUT[case]
    mapper, prop = make_mapper(kind), property_for()
    if change_mapper:
        change_mapper(mapper)
    if change_property:
        change_property(prop)
    image, _, messages = draw(kind, make_grid(), prop, mapper)
    assert len(set(messages.errors)) == 1, messages.errors
    assert all(word in messages.errors[0] for word in words), messages.errors
    assert image.max() == 0.0


@pytest.mark.parametrize("kind", ALL_KINDS)
@pytest.mark.parametrize("where", ["point", "cell"])
def test_arrays_shorter_than_the_grid_are_a_clear_error(kind, where):
    """The selected array too short is named; another array too short (which VTK's own split
    into tetrahedra would read out of bounds) does not matter."""
    grid = mixed_cells()
    attributes = grid.GetPointData() if where == "point" else grid.GetCellData()
    attributes.AddArray(named_array(np.zeros(2), "short"))
    image, _, messages = draw(kind, grid)  # the point scalars "s" are fine
    assert not messages.errors and image[..., 3].max() > 0.1
    mapper = make_mapper(kind)
    mapper.SetScalarModeToUsePointFieldData() if where == "point" else \
        mapper.SetScalarModeToUseCellFieldData()
    mapper.SelectScalarArray("short")
    image, _, messages = draw(kind, grid, mapper=mapper)
    count = grid.GetNumberOfPoints() if where == "point" else grid.GetNumberOfCells()
    assert messages.errors
    assert f"'short' has 2 values, but the grid has {count} {where}s" in messages.errors[0]
    assert image.max() == 0.0


@pytest.mark.parametrize("kind", ALL_KINDS)
def test_a_camera_that_is_not_finite_is_a_clear_error(kind):
    window, renderer = render.make_window(*SIZE)
    mapper = make_mapper(kind)
    messages = watch(mapper)
    render.add_volume(renderer, ONE, property_for(), mapper)
    renderer.ResetCamera()
    renderer.GetActiveCamera().SetPosition(math.nan, 0.0, 0.0)
    window.Render()
    assert messages.errors and "not finite" in messages.errors[0]
    window.Finalize()


# --- Values -----------------------------------------------------------------------------------

@pytest.mark.parametrize("kind", ALL_KINDS)
@pytest.mark.parametrize("point, scalar", [((1, 1, 1), math.nan), ((1, 1, 1), math.inf),
                                           ((1, 1, 1), -math.inf), ((math.nan, 1, 1), 0.5)])
def test_non_finite_values_leave_their_cells_out_with_a_warning(kind, point, scalar):
    """The second cell's fifth point, or its scalar, is not finite."""
    grid = tetrahedra(UNIT_TETRAHEDRON + [point], [(0, 1, 2, 3), (1, 2, 3, 4)],
                      [0.0, 0.3, 0.6, 1.0, scalar])
    image, mapper, messages = draw(kind, grid)
    assert not messages.errors
    assert mapper.GetNumberOfTetrahedra() == 1 and mapper.GetNumberOfSkippedCells() == 1
    assert messages.warnings and "not finite" in messages.warnings[0]
    assert image[..., 3].max() > 0.1


@pytest.mark.parametrize("kind", ALL_KINDS)
def test_only_non_finite_scalars_draw_nothing_with_a_warning(kind):
    grid = tetrahedra(UNIT_TETRAHEDRON, [(0, 1, 2, 3)], [math.nan] * 4)
    image, mapper, messages = draw(kind, grid)
    assert not messages.errors and mapper.GetNumberOfSkippedCells() == 1
    assert messages.warnings and image.max() == 0.0


RAMP = np.array([0.2, 0.5, 0.8, 1.0])
#: Arrays of several components on the unit tetrahedron (a tuple per point, times RAMP), the
#: component rendered (None: the magnitude), and the factor of RAMP that is the same single
#: array. Nine components are a tensor (VTK 9.2's vtkVolume::GetRedrawMTime() crashes on more
#: than four; SPT used to call it).
COMPONENTS = {"tensor magnitude": (np.full(9, 1.0 / 3.0), None, 1.0),
              "vector magnitude": ([3.0, 4.0, 0.0], None, 5.0),
              "vector component 1": ([3.0, 4.0, 0.0], 1, 4.0)}


@pytest.mark.parametrize("kind", ALL_KINDS)
@pytest.mark.parametrize("case", COMPONENTS)
def test_arrays_of_several_components(kind, case):
    """The magnitude, or one component, is rendered: the same image as that single array."""
    per_point, component, factor = COMPONENTS[case]
    grid = with_point_scalars(tetrahedra(UNIT_TETRAHEDRON, [(0, 1, 2, 3)]),
                              np.outer(RAMP, per_point), "v")
    mapper = make_mapper(kind)
    if component is not None:
        mapper.SetVectorModeToComponent()
        mapper.SetVectorComponent(component)
    prop = property_for(0.0, 5.0, opacity=0.9)
    image, _, messages = draw(kind, grid, prop, mapper)
    expected, _, _ = draw(kind, tetrahedra(UNIT_TETRAHEDRON, [(0, 1, 2, 3)], factor * RAMP), prop)
    assert not messages.errors and image[..., 3].max() > 0.1
    assert np.array_equal(image, expected)


def test_havs_refuses_cell_scalars_clearly():
    image, _, messages = draw("havs", cell_scalars_grid())
    assert len(messages.errors) == 1
    assert "point scalars" in messages.errors[0] and "vtkCellDataToPointData" in messages.errors[0]
    assert image.max() == 0.0


# --- Cells ------------------------------------------------------------------------------------

def mixed_cells(with_2d=False):
    """A hexahedron, a pyramid on top, a wedge and a tetrahedron beside it; optionally a
    triangle (2D cells hold no volume and are left out)."""
    points = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1),
              (0, 1, 1), (0.5, 0.5, 1.8), (2, 0, 0), (2, 1, 0), (2, 0, 1), (2, 1, 1),
              (2.8, 0.5, 0.5)]
    x = np.array(points)
    grid = tetrahedra(points, [], 0.5 + 0.5 * np.sin(1.3 * x[:, 0] + x[:, 2]))
    grid.InsertNextCell(vtk.VTK_HEXAHEDRON, 8, list(range(8)))
    grid.InsertNextCell(vtk.VTK_PYRAMID, 5, [4, 5, 6, 7, 8])
    grid.InsertNextCell(vtk.VTK_WEDGE, 6, [1, 9, 5, 2, 10, 6])
    grid.InsertNextCell(vtk.VTK_TETRA, 4, [9, 10, 11, 13])
    if with_2d:
        grid.InsertNextCell(vtk.VTK_TRIANGLE, 3, [0, 1, 2])
    return grid


@pytest.mark.parametrize("kind", ALL_KINDS)
def test_mixed_cells_are_split_and_2d_cells_left_out(kind):
    """The hexahedron, pyramid, wedge and tetrahedron give at least 5 + 2 + 3 + 1 tetrahedra;
    the triangle adds none, and nothing to the image."""
    with_triangle, mapper, messages = draw(kind, mixed_cells(with_2d=True))
    without, _, _ = draw(kind, mixed_cells())
    assert not messages.errors and mapper.GetNumberOfTetrahedra() >= 11
    assert with_triangle[..., 3].max() > 0.2
    assert np.array_equal(with_triangle, without)


def quadratic_tetrahedron():
    corners = np.array(UNIT_TETRAHEDRON, dtype=float)
    edges = [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]
    points = np.vstack([corners] + [[(corners[a] + corners[b]) / 2.0] for a, b in edges])
    # A field linear in the coordinates: the quadratic cell is then exactly a linear one.
    scalars = points @ np.array([0.3, 0.5, 0.2])
    return tetrahedra(points, [list(range(10))], scalars, cell_type=vtk.VTK_QUADRATIC_TETRA)


@pytest.mark.parametrize("kind", KINDS)
def test_quadratic_cells_are_linearized(kind):
    """A quadratic tetrahedron with a linear field: the same picture as the linear one
    (within the rasterization of its inner faces for HAVS, the noise for PBVR)."""
    grid = quadratic_tetrahedron()
    image, mapper, messages = draw(kind, grid)
    assert not messages.errors and mapper.GetNumberOfTetrahedra() >= 4
    linear = tetrahedra(UNIT_TETRAHEDRON, [(0, 1, 2, 3)],
                        np.array(UNIT_TETRAHEDRON) @ np.array([0.3, 0.5, 0.2]))
    assert_matches_reference(kind, linear, property_for(), havs_rmse=0.005, pbvr_bias=0.012)
    expected, _, _ = draw(kind, linear)
    assert_same_picture(kind, image, expected, havs_rmse=0.002)


def polyhedron_cube():
    """The unit cube as one VTK_POLYHEDRON cell."""
    points = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1),
              (0, 1, 1)]
    faces = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    grid = tetrahedra(points, [], np.array(points, dtype=float) @ np.array([0.2, 0.3, 0.5]))
    ids = vtk.vtkIdList()
    # The face stream: the number of faces, then each face's size and point ids.
    for i in [len(faces)] + [n for face in faces for n in (len(face), *face)]:
        ids.InsertNextId(i)
    grid.InsertNextCell(vtk.VTK_POLYHEDRON, ids)
    return grid


#: Input that HAVS and PBVR draw as the exact reference does: the grid, the opacity of
#: property_for(), the kinds, and the fewest tetrahedra made of it. Measured: HAVS RMSE 0.0011
#: on each; PBVR bias 0.0000, 0.0063, 0.0067, 0.0056 and 0.0000 (squared: -4e-6 +- 4.5e-5,
#: 4.0e-5 +- 3.1e-5, 4.5e-5 +- 5.5e-5, 3.1e-5 +- 3.3e-5, -3.4e-5 +- 3.3e-5).
MATCHES_REFERENCE = {
    "one tetrahedron": (lambda: ONE, 0.8, KINDS, 1),
    "constant field": (lambda: with_constant_scalars(field_grid()), 0.5, KINDS, 1),  # range 0
    "mixed linear cells": (mixed_cells, 0.6, KINDS, 4),
    "polyhedron": (polyhedron_cube, 0.6, KINDS, 5),  # a cube as one polyhedron cell
    "cell scalars": (cell_scalars_grid, 0.6, ["pbvr"], 1),  # HAVS refuses them, see below
}


@pytest.mark.parametrize("case, kind", [(case, kind) for case, (_, _, kinds, _)
                                        in MATCHES_REFERENCE.items() for kind in kinds])
def test_input_matches_the_reference(case, kind):
    make_grid, opacity, _, tetrahedra_count = MATCHES_REFERENCE[case]
    mapper = assert_matches_reference(kind, make_grid(), property_for(opacity=opacity),
                                      havs_rmse=0.005, pbvr_bias=0.012)
    assert mapper.GetNumberOfTetrahedra() >= tetrahedra_count
    if kind == "havs" and case == "one tetrahedron":
        assert (mapper.GetNumberOfFaces(), mapper.GetNumberOfBoundaryFaces()) == (4, 4)


@pytest.mark.parametrize("kind", ALL_KINDS)
def test_degenerate_inverted_and_duplicate_tetrahedra(kind):
    """Inverted tetrahedra draw as the others; flat ones hold no volume and add nothing; a
    listed twice adds its opacity twice (two cells)."""
    points = UNIT_TETRAHEDRON + [(0.5, 0.5, 0)]
    scalars = [0.0, 0.3, 0.6, 1.0, 0.5]
    upright, _, _ = draw(kind, tetrahedra(points, [(0, 1, 2, 3)], scalars))
    inverted, _, messages = draw(kind, tetrahedra(points, [(0, 2, 1, 3)], scalars))
    assert not messages.errors
    assert_same_picture(kind, inverted, upright, havs_rmse=0.002)
    flat, mapper, messages = draw(kind, tetrahedra(points, [(0, 1, 2, 3), (0, 1, 2, 4),
                                                            (3, 3, 3, 3)], scalars))
    assert not messages.errors and mapper.GetNumberOfTetrahedra() == 3
    assert_same_picture(kind, flat, upright, havs_rmse=0.002)
    twice, _, messages = draw(kind, tetrahedra(points, [(0, 1, 2, 3), (0, 1, 2, 3)], scalars))
    assert not messages.errors
    assert twice[..., 3].mean() >= upright[..., 3].mean()


# --- Scale and transfer functions ------------------------------------------------------------

def scaled_image(kind, grid, prop, scale):
    """The image of ``grid`` and ``prop`` with the coordinates and the unit distance
    multiplied by ``scale`` (deep copies), seen from the camera of the unscaled data scaled
    by ``scale``. VTK's own ResetCameraClippingRange fails at 1e30 and 1e-30 (it returns
    1.8e-21..1.8e-18), so the camera is set by hand."""
    scaled = vtk.vtkUnstructuredGrid()
    scaled.DeepCopy(grid)
    coordinates = vtk_to_numpy(scaled.GetPoints().GetData()).astype(np.float64) * scale
    scaled.GetPoints().SetData(numpy_to_vtk(coordinates, deep=True))
    scaled_prop = vtk.vtkVolumeProperty()
    scaled_prop.DeepCopy(prop)
    scaled_prop.SetScalarOpacityUnitDistance(prop.GetScalarOpacityUnitDistance() * scale)
    scene = Scene(kind, scaled, scaled_prop, grid.GetBounds())
    camera = scene.renderer.GetActiveCamera()
    camera.SetPosition([x * scale for x in camera.GetPosition()])
    camera.SetFocalPoint([x * scale for x in camera.GetFocalPoint()])
    camera.SetClippingRange([x * scale for x in camera.GetClippingRange()])
    return scene.draw()


@pytest.mark.parametrize("kind", ALL_KINDS)
@pytest.mark.parametrize("scale", [1e30, 1e-30])
def test_extreme_coordinates_give_the_same_image(kind, scale):
    """Coordinates and unit distance scaled together: the same picture."""
    grid, prop = field_grid(), property_for(0.0, 1.0, unit=1.0, opacity=0.6)
    expected = scaled_image(kind, grid, prop, 1.0)
    assert expected[..., 3].max() > 0.2
    image = scaled_image(kind, grid, prop, scale)
    assert metrics.rmse(image, expected) < (0.03 if kind == "pbvr" else 0.01)


@pytest.mark.parametrize("kind", ALL_KINDS)
@pytest.mark.parametrize("points", [0, 1])
def test_transfer_functions_with_no_or_one_point(kind, points):
    prop = volume_property([(0.5, 1.0, 0.5, 0.0)][:points], [(0.5, 0.7)][:points])
    image, _, messages = draw(kind, ONE, prop)
    assert not messages.errors
    if points:  # one point: constant over the range, as VTK's transfer functions clamp
        constant = property_for(opacity=0.7)
        constant.GetRGBTransferFunction().RemoveAllPoints()
        constant.GetRGBTransferFunction().AddRGBPoint(0.0, 1.0, 0.5, 0.0)
        expected, _, _ = draw(kind, ONE, constant)
        assert image[..., 3].max() > 0.2
        assert_same_picture(kind, image, expected, havs_rmse=0.002)
    else:
        assert image.max() == 0.0


@pytest.mark.parametrize("kind", KINDS)
def test_opacity_one_everywhere(kind):
    image, _, messages = draw(kind, ONE, property_for(opacity=1.0, unit=0.01))
    assert not messages.errors
    covered = image[..., 3] > 0
    assert covered.sum() > 50 and np.mean(image[..., 3][covered] > 0.99) > 0.8


# --- Changes between renders, windows, viewports ---------------------------------------------

@pytest.mark.parametrize("kind", ALL_KINDS)
def test_input_changes_between_renders(kind):
    """Points moved, cells removed and added, the array swapped: each render is what a new
    mapper draws of the changed input."""
    scene = Scene(kind, field_grid())
    first = scene.draw()
    assert first[..., 3].max() > 0.2
    moved = vtk_to_numpy(scene.grid.GetPoints().GetData())
    moved[:, 2] *= 0.6
    scene.grid.GetPoints().Modified()
    image = scene.draw()
    assert not np.array_equal(image, first)
    assert np.array_equal(image, scene.fresh())
    # Fewer cells, then more cells than at first.
    cells = vtk_to_numpy(scene.grid.GetCells().GetConnectivityArray()).reshape(-1, 4)
    fewer = tetrahedra(vtk_to_numpy(scene.grid.GetPoints().GetData()), cells[::2])
    fewer.GetPointData().ShallowCopy(scene.grid.GetPointData())
    scene.grid.ShallowCopy(fewer)
    image = scene.draw()
    assert scene.mapper.GetNumberOfTetrahedra() == len(cells[::2])
    assert np.array_equal(image, scene.fresh())
    for cell in cells[1::2]:
        scene.grid.InsertNextCell(vtk.VTK_TETRA, 4, [int(i) for i in cell])
    scene.grid.InsertNextCell(vtk.VTK_TETRA, 4, [int(i) for i in cells[1]])
    scene.grid.Modified()
    image = scene.draw()
    assert scene.mapper.GetNumberOfTetrahedra() == len(cells) + 1
    assert np.array_equal(image, scene.fresh())
    # Another array as the scalars.
    with_point_scalars(scene.grid, np.linspace(0.0, 1.0, scene.grid.GetNumberOfPoints()), "ramp")
    image = scene.draw()
    assert np.array_equal(image, scene.fresh())


@pytest.mark.parametrize("kind", ALL_KINDS)
def test_release_windows_resizes_and_empty_viewports(kind):
    """Released resources (PBVR's particles too), resizes, an empty viewport and a second
    window: each render as a fresh mapper's; repeated renders leave nothing behind (HAVS's
    k-buffer is cleared); a turned camera changes the image."""
    scene = Scene(kind, field_grid())
    first = scene.draw()
    assert first[..., 3].max() > 0.2 and scene.mapper.GetGPUMemorySize() > 0
    scene.mapper.ReleaseGraphicsResources(scene.window)
    assert scene.mapper.GetGPUMemorySize() == 0
    if kind == "pbvr":
        assert scene.mapper.GetNumberOfParticles() == 0
    assert np.array_equal(scene.draw(), first), "a render after a release differs"
    # Resizes: each is what a new mapper draws at that size.
    for size in [(SIZE[0] + 17, SIZE[1] + 5), (SIZE[0] // 2, SIZE[1] + 9), SIZE]:
        scene.window.SetSize(*size)
        image = scene.draw()
        assert image.shape[:2] == (size[1], size[0])
        assert_same_picture(kind, image, scene.fresh())
    # A zero-size viewport draws nothing, and the next render is as before.
    scene.renderer.SetViewport(0.2, 0.2, 0.2, 0.2)
    scene.draw()
    scene.renderer.SetViewport(0.0, 0.0, 1.0, 1.0)
    assert_same_picture(kind, scene.draw(), first)
    # The same volume in a second window, in turns with the first.
    other, other_renderer = render.make_window(*SIZE)
    other_renderer.AddVolume(scene.volume)
    other_renderer.SetActiveCamera(scene.renderer.GetActiveCamera())
    for _ in range(2):
        other.Render()
        assert np.array_equal(render.read_rgba(other), first)
        assert np.array_equal(scene.draw(), first)
    other_renderer.RemoveVolume(scene.volume)
    other.Finalize()
    scene.renderer.GetActiveCamera().Azimuth(40.0)
    assert not np.array_equal(scene.draw(), first), "the image ignores the camera"
