"""Helpers of the robustness tests of every mapper: small grids built from lists, transfer
functions, the errors and warnings a VTK object reports, a check of a setting's default and
clamps, and a check that a render left its input exactly as it was."""

from __future__ import annotations

from typing import Dict, List, Optional, Sequence

import numpy as np
import vtk
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy

from spt import render


def _with_call_data(observer):
    observer.CallDataType = vtk.VTK_STRING
    return observer


class Messages:
    """The errors and warnings an object reported, with their text."""

    def __init__(self):
        self.errors: List[str] = []
        self.warnings: List[str] = []


def watch(obj) -> Messages:
    """Collect the errors and warnings of obj."""
    messages = Messages()
    obj.AddObserver("ErrorEvent", _with_call_data(lambda o, e, text: messages.errors.append(text)))
    obj.AddObserver("WarningEvent",
                    _with_call_data(lambda o, e, text: messages.warnings.append(text)))
    return messages


def check_clamped_setting(obj, name: str, default, low, high) -> None:
    """The setting ``name`` of ``obj`` is ``default``, and a value below ``low`` or above
    ``high`` is clamped to it."""
    get, set_ = getattr(obj, "Get" + name), getattr(obj, "Set" + name)
    assert get() == default, name
    set_(low - 1)
    assert get() == low, name
    set_(high + 1)
    assert get() == high, name


def named_array(values, name: str):
    """A VTK array of ``values`` (one tuple per row), deep-copied, named ``name``."""
    array = numpy_to_vtk(np.asarray(values), deep=True)
    array.SetName(name)
    return array


def with_point_scalars(grid, values, name: str):
    """``grid`` with ``values`` as its point scalars, named ``name``."""
    grid.GetPointData().SetScalars(named_array(values, name))
    return grid


def with_constant_scalars(grid, value: float = 0.25):
    """``grid`` with the point scalars "constant", ``value`` everywhere (a zero range)."""
    return with_point_scalars(grid, np.full(grid.GetNumberOfPoints(), value), "constant")


def tetrahedra(points, cells, scalars=None, name="s", cell_type=vtk.VTK_TETRA):
    """An unstructured grid of tetrahedra (or of `cell_type`) from point and cell lists."""
    grid = vtk.vtkUnstructuredGrid()
    vtk_points = vtk.vtkPoints()
    vtk_points.SetData(numpy_to_vtk(np.asarray(points, dtype=np.float64).reshape(-1, 3),
                                    deep=True))
    grid.SetPoints(vtk_points)
    for cell in cells:
        grid.InsertNextCell(cell_type, len(cell), list(cell))
    if scalars is not None:
        with_point_scalars(grid, np.asarray(scalars, dtype=np.float64), name)
    return grid


def split_image(image: vtk.vtkImageData) -> vtk.vtkUnstructuredGrid:
    """The image data's voxels split into tetrahedra, as a grid of its own (a deep copy)."""
    split = vtk.vtkDataSetTriangleFilter()
    split.SetInputData(image)
    split.TetrahedraOnlyOn()
    split.Update()
    grid = vtk.vtkUnstructuredGrid()
    grid.DeepCopy(split.GetOutput())
    return grid


def split_box(cells: Sequence[int], field, origin=(0.0, 0.0, 0.0), name: str = "f"):
    """A box of cells[0] x cells[1] x cells[2] unit cubes from ``origin``, split into
    tetrahedra, with the point scalars ``field(points)`` (points: an n x 3 array) named
    ``name``."""
    image = vtk.vtkImageData()
    image.SetDimensions(*(n + 1 for n in cells))
    image.SetOrigin(*origin)
    points = np.array([image.GetPoint(i) for i in range(image.GetNumberOfPoints())])
    return split_image(with_point_scalars(image, field(points), name))


def watched_render(mapper, grid, prop=None, size: Sequence[int] = (96, 96),
                   view: Optional[render.View] = None):
    """Render ``grid`` through ``mapper`` (with ``prop``, property_for() by default, from
    ``view``, azimuth and elevation 30 by default): the rendering and the mapper's errors and
    warnings. The input must be exactly as it was (assert_unchanged)."""
    messages = watch(mapper)
    before = snapshot(grid)
    rendering = render.render(grid, prop or property_for(), mapper, view or render.View(30, 30),
                              size)
    assert_unchanged(grid, before)
    return rendering, messages


def volume_property(colors, opacities, unit: float = 1.0) -> vtk.vtkVolumeProperty:
    """A volume property of the color points (x, r, g, b), the opacity points (x, a) and the
    unit distance."""
    color = vtk.vtkColorTransferFunction()
    for point in colors:
        color.AddRGBPoint(*point)
    opacity = vtk.vtkPiecewiseFunction()
    for point in opacities:
        opacity.AddPoint(*point)
    prop = vtk.vtkVolumeProperty()
    prop.SetColor(color)
    prop.SetScalarOpacity(opacity)
    prop.SetScalarOpacityUnitDistance(unit)
    return prop


def property_for(low=0.0, high=1.0, unit=1.0, opacity=0.8):
    """Blue to orange over [low, high], constant opacity, the given unit distance."""
    return volume_property([(low, 0.2, 0.4, 1.0), (high, 1.0, 0.6, 0.2)],
                           [(low, opacity), (high, opacity)], unit)


UNIT_TETRAHEDRON = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
ONE = tetrahedra(UNIT_TETRAHEDRON, [(0, 1, 2, 3)], [0.0, 0.3, 0.6, 1.0])


def snapshot(grid: vtk.vtkDataSet) -> Dict[str, object]:
    """Everything a mapper could change in a grid, copied: MTime, points, cells, arrays."""
    state: Dict[str, object] = {"mtime": grid.GetMTime(),
                                "points": grid.GetNumberOfPoints(),
                                "cells": grid.GetNumberOfCells()}
    if grid.GetNumberOfPoints() and grid.GetPoints() is not None:
        state["coordinates"] = vtk_to_numpy(grid.GetPoints().GetData()).copy()
    if isinstance(grid, vtk.vtkUnstructuredGrid) and grid.GetCells() is not None:
        state["connectivity"] = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).copy()
        state["offsets"] = vtk_to_numpy(grid.GetCells().GetOffsetsArray()).copy()
    for where, attributes in (("point", grid.GetPointData()), ("cell", grid.GetCellData())):
        scalars = attributes.GetScalars()
        state[where + " scalars"] = scalars.GetName() if scalars is not None else None
        for index in range(attributes.GetNumberOfArrays()):
            array = attributes.GetArray(index)
            state[f"{where} {array.GetName()}"] = vtk_to_numpy(array).copy()
    return state


def assert_unchanged(grid: vtk.vtkDataSet, before: Dict[str, object]) -> None:
    """The grid is as `snapshot` saw it (NaN compares equal to NaN)."""
    after = snapshot(grid)
    assert after.keys() == before.keys(), "the input's arrays changed"
    for key, value in before.items():
        if isinstance(value, np.ndarray):
            assert np.array_equal(value, after[key], equal_nan=value.dtype.kind == "f"), (
                f"the input's {key} changed")
        else:
            assert value == after[key], f"the input's {key} changed: {value} -> {after[key]}"
