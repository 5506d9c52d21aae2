"""The tests' scenes and their exact references, made once per test process, and the opaque
planes put in them."""

from functools import lru_cache

import numpy as np
import vtk

from spt import data, render, scenes

from spt_pytest_fixtures import load_or_skip


@lru_cache(maxsize=None)
def scene(name: str) -> scenes.Scene:
    """A scene of spt.scenes; a skip when its data set is not in SPT_DATA_DIR."""
    if name != "default":
        load_or_skip(name)
    return scenes.scene(name)


def scene_image(name: str, mapper, size: int, **options) -> np.ndarray:
    """The named scene through ``mapper`` from its view at size x size pixels
    (spt.render.render with ``options``)."""
    s = scene(name)
    return render.render(s.grid, s.property, mapper, s.view, (size, size), **options).image


@lru_cache(maxsize=None)
def reference(name: str, size: int):
    """The exact reference image of the scene at size x size pixels."""
    s = scene(name)
    return render.reference(s.grid, s.property, s.view, (size, size)).image


def with_cell_scalars(grid):
    """A copy of ``grid`` whose scalars are its point scalars averaged per cell."""
    to_cells = vtk.vtkPointDataToCellData()
    to_cells.SetInputData(grid)
    to_cells.Update()
    cells = vtk.vtkUnstructuredGrid()
    cells.ShallowCopy(to_cells.GetOutput())
    cells.GetPointData().SetActiveScalars(None)
    return cells


def plane_actor(origin, point1, point2) -> vtk.vtkActor:
    """An opaque actor of the parallelogram with corners ``origin``, ``point1`` and
    ``point2``."""
    plane = vtk.vtkPlaneSource()
    plane.SetOrigin(*origin)
    plane.SetPoint1(*point1)
    plane.SetPoint2(*point2)
    plane_mapper = vtk.vtkPolyDataMapper()
    plane_mapper.SetInputConnection(plane.GetOutputPort())
    actor = vtk.vtkActor()
    actor.SetMapper(plane_mapper)
    return actor


def opaque_plane(grid):
    """An opaque plane actor through the middle of the mesh, across the view."""
    b = grid.GetBounds()
    x = 0.5 * (b[0] + b[1])
    return plane_actor((x, b[2] - 1, b[4] - 1), (x, b[3] + 1, b[4] - 1), (x, b[2] - 1, b[5] + 1))


def gray_plane() -> vtk.vtkActor:
    """An unlit gray plane at height 0.2, large enough to fill the view of the default mesh."""
    actor = plane_actor((-50.0, -50.0, 0.2), (50.0, -50.0, 0.2), (-50.0, 50.0, 0.2))
    actor.GetProperty().SetColor(0.5, 0.5, 0.5)
    actor.GetProperty().LightingOff()
    return actor


def moved_copy(grid, offset):
    """A copy of ``grid`` with its points moved by ``offset``."""
    transform = vtk.vtkTransform()
    transform.Translate(*offset)
    moved = vtk.vtkTransformFilter()
    moved.SetInputData(grid)
    moved.SetTransform(transform)
    moved.Update()
    return moved.GetOutput()


def with_moved_copy(grid, offset):
    """``grid`` and a copy of it moved by ``offset``, appended into one grid: the union that
    two volumes of ``grid`` show when the second's vtkVolume is moved by ``offset``."""
    union = vtk.vtkAppendFilter()
    union.AddInputData(grid)
    union.AddInputData(moved_copy(grid, offset))
    union.Update()
    return union.GetOutput()


def union_offset(grid):
    """Where the tests' second volume of ``grid`` is moved by its vtkVolume: 0.35, 0.2 and 0.1
    of the grid's extent along x, y and z, into the first."""
    b = grid.GetBounds()
    return (0.35 * (b[1] - b[0]), 0.2 * (b[3] - b[2]), 0.1 * (b[5] - b[4]))


@lru_cache(maxsize=None)
def union(name: str):
    """The named scene's mesh and its copy moved by union_offset(), as one grid: what the
    scene's mesh shows as two volumes, the second moved."""
    s = scene(name)
    return with_moved_copy(s.grid, union_offset(s.grid))


@lru_cache(maxsize=None)
def union_reference(name: str, size: int):
    """The exact reference image of union(name) in the scene's view at size x size pixels."""
    s = scene(name)
    return render.reference(union(name), s.property, s.view, (size, size)).image


def window_with(mapper, size: int, name: str = "default", prop=None, view=None):
    """A size x size window showing the named scene through ``mapper`` from its view (or
    ``view``), with ``prop`` or else a property of its own (the tests change it)."""
    s = scene(name)
    window, renderer = render.make_window(size, size)
    if prop is None:
        prop = data.default_transfer_function(s.grid)
    render.add_volume(renderer, s.grid, prop, mapper)
    render.place_camera(renderer, s.grid.GetBounds(), view or s.view)
    return window, renderer


def draw_once(window):
    """Render ``window`` once and return its image; the window is finalized."""
    window.Render()
    image = render.read_rgba(window)
    window.Finalize()
    return image


def render_at_still_rate(window) -> None:
    """Render as a vtkRenderWindowInteractor does once interaction ends: at its still update
    rate."""
    interactor = vtk.vtkRenderWindowInteractor()  # Not attached: the window may have no X.
    window.SetDesiredUpdateRate(interactor.GetStillUpdateRate())
    window.Render()


def bilinear_upsampled(image, factor: int):
    """Bilinear interpolation of an image to ``factor`` times its size, as the mappers' resolve
    does: each pixel center of the larger image placed in the smaller one, its four neighbors
    mixed, the indices clamped at the borders."""
    height, width = image.shape[:2]

    def axis(n):
        position = (np.arange(n * factor) + 0.5) / factor - 0.5
        low = np.floor(position).astype(int)
        weight = position - low
        return np.clip(low, 0, n - 1), np.clip(low + 1, 0, n - 1), weight

    y0, y1, wy = axis(height)
    x0, x1, wx = axis(width)
    wx = wx[None, :, None]
    top = image[y0][:, x0] * (1 - wx) + image[y0][:, x1] * wx
    bottom = image[y1][:, x0] * (1 - wx) + image[y1][:, x1] * wx
    return top * (1 - wy[:, None, None]) + bottom * wy[:, None, None]
