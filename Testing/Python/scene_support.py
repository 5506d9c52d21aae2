"""The tests' scenes and their exact references, made once per test process."""

from functools import lru_cache

import vtk

from spt import data, render, scenes

from spt_pytest_fixtures import load_or_skip


@lru_cache(maxsize=None)
def scene(name: str) -> scenes.Scene:
    """A scene of spt.scenes; a skip when its data set is not in SPT_DATA_DIR."""
    if name != "default":
        load_or_skip(name)
    return scenes.scene(name)


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


def opaque_plane(grid):
    """An opaque plane actor through the middle of the mesh, across the view."""
    bounds = grid.GetBounds()
    plane = vtk.vtkPlaneSource()
    cx = 0.5 * (bounds[0] + bounds[1])
    plane.SetOrigin(cx, bounds[2] - 1, bounds[4] - 1)
    plane.SetPoint1(cx, bounds[3] + 1, bounds[4] - 1)
    plane.SetPoint2(cx, bounds[2] - 1, bounds[5] + 1)
    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputConnection(plane.GetOutputPort())
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    return actor


def with_moved_copy(grid, offset):
    """``grid`` and a copy of it moved by ``offset``, appended into one grid: the union that
    two volumes of ``grid`` show when the second's vtkVolume is moved by ``offset``."""
    transform = vtk.vtkTransform()
    transform.Translate(*offset)
    moved = vtk.vtkTransformFilter()
    moved.SetInputData(grid)
    moved.SetTransform(transform)
    union = vtk.vtkAppendFilter()
    union.AddInputData(grid)
    union.AddInputConnection(moved.GetOutputPort())
    union.Update()
    return union.GetOutput()


def window_with(mapper, size: int, name: str = "default"):
    """A window showing the named scene through ``mapper``, with a property of its own (the
    tests change it)."""
    s = scene(name)
    window, renderer = render.make_window(size, size)
    render.add_volume(renderer, s.grid, data.default_transfer_function(s.grid), mapper)
    render.place_camera(renderer, s.grid.GetBounds(), s.view)
    return window, renderer


def render_at_still_rate(window) -> None:
    """Render as a vtkRenderWindowInteractor does once interaction ends: at its still update
    rate."""
    interactor = vtk.vtkRenderWindowInteractor()  # Not attached: the window may have no X.
    window.SetDesiredUpdateRate(interactor.GetStillUpdateRate())
    window.Render()
