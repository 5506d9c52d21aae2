"""Tests of spt.data: the embedded default mesh, data-directory lookup,
blanked-cell removal, transfer functions and (when the data directory is
available) the real data sets' tet counts."""

import math

import numpy as np
import pytest
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import (
    VTK_TETRA,
    vtkStaticCellLocator,
    vtkStructuredGrid,
)

import spt.data as data

# Tets after vtkDataSetTriangleFilter, and some scalar ranges, from shared/data/README.md.
README_TETS = {
    "tetramesh": 160, "postvtk": 8750, "torus": 9216, "spx": 12936,
    "office": 36100, "disk": 44832, "fire": 62772, "hexa": 63888,
    "ironprot": 66960, "ironprot_full": 1503815, "bluntfin": 187395,
    "post": 513375,
}
README_RANGES = {"spx": (0.0, 2.254), "bluntfin": (0.193, 4.978), "post": (0.0, 1.391)}


@pytest.fixture(scope="module")
def mesh():
    return data.make_default_mesh()


def _points(grid):
    return vtk_to_numpy(grid.GetPoints().GetData()).astype(float)


def test_default_mesh_is_a_deterministic_tube_of_positive_tetrahedra(mesh):
    assert set(vtk_to_numpy(mesh.GetDistinctCellTypesArray())) == {VTK_TETRA}
    assert 40000 <= mesh.GetNumberOfCells() <= 60000
    corners = _points(mesh)[vtk_to_numpy(mesh.GetCells().GetConnectivityArray()).reshape(-1, 4)]
    volumes = np.linalg.det(corners[:, 1:] - corners[:, :1]) / 6.0
    assert np.all(volumes > 0.0)
    # Tube of radius 0.3 around a helix of length 2 turns * sqrt(...)
    length = 2 * math.hypot(2 * math.pi, 1.0)
    assert volumes.sum() == pytest.approx(math.pi * 0.09 * length, rel=0.02)
    again = data.make_default_mesh()
    np.testing.assert_array_equal(_points(mesh), _points(again))
    np.testing.assert_array_equal(
        vtk_to_numpy(mesh.GetPointData().GetScalars()),
        vtk_to_numpy(again.GetPointData().GetScalars()))
    assert data.make_default_mesh(2).GetNumberOfCells() == 8 * mesh.GetNumberOfCells()
    with pytest.raises(ValueError):
        data.make_default_mesh(0)


def test_default_mesh_is_not_convex(mesh):
    locator = vtkStaticCellLocator()
    locator.SetDataSet(mesh)
    locator.BuildLocator()
    theta = 0.3
    centers = data.helix_center(np.array([theta, theta + 2 * math.pi]))
    # Both centre-line points are inside the mesh...
    for point in centers:
        assert locator.FindCell(tuple(point)) >= 0
    # ...but the midpoint between two turns (inside the convex hull) and
    # the helix axis are not.
    assert locator.FindCell(tuple(centers.mean(axis=0))) == -1
    assert locator.FindCell((0.0, 0.0, 0.0)) == -1


def test_default_mesh_scalar(mesh):
    scalars = mesh.GetPointData().GetScalars()
    assert scalars.GetName() == data.DEFAULT_FIELD_NAME
    assert mesh.GetPointData().GetNumberOfArrays() == 1
    values = vtk_to_numpy(scalars)
    assert np.all(np.isfinite(values))
    assert values.min() >= 0.0 and values.max() <= 1.05
    assert values.max() - values.min() > 0.8


# (transfer function, keyword arguments, unit distance as a fraction of the diagonal,
# [(fraction of the scalar range, opacity there)]).
TRANSFER_FUNCTIONS = [
    (data.default_transfer_function, {}, 1.0 / 20.0, [(0.0, (0.0, 0.05)), (1.0, (0.6, 0.8))]),
    (data.transfer_function, {"opacity_scale": 0.5}, 1.0 / 40.0, [(1.0, 0.4)]),
    (data.transfer_function, {"preset": "steep", "opacity_scale": 0.5}, 1.0 / 40.0,
     [(0.5, 0.0), (0.65, 0.45)]),
    (data.transfer_function, {"preset": "steep", "steep_center": 0.3}, 1.0 / 40.0,
     [(0.3, 0.9), (0.2, 0.0), (0.4, 0.0), (0.65, 0.0)]),
]


@pytest.mark.parametrize("make, keywords, unit, opacities", TRANSFER_FUNCTIONS)
def test_transfer_functions(mesh, make, keywords, unit, opacities):
    prop = make(mesh, **keywords)
    assert prop.GetScalarOpacityUnitDistance() == pytest.approx(unit * mesh.GetLength())
    assert not prop.GetShade()
    low, high = mesh.GetPointData().GetScalars().GetRange()
    for t, expected in opacities:
        value = prop.GetScalarOpacity().GetValue(low + t * (high - low))
        if isinstance(expected, tuple):
            assert expected[0] <= value <= expected[1]
        else:
            assert value == (pytest.approx(expected) if expected else 0.0)


@pytest.mark.parametrize("keywords", [{"preset": "no-such-preset"},
                                      {"preset": "steep", "steep_center": 0.99}])
def test_bad_transfer_function_arguments(mesh, keywords):
    with pytest.raises(ValueError):
        data.transfer_function(mesh, **keywords)


def _blanked_grid():
    """3x3x3-point structured grid (8 hexes) with one blanked corner."""
    z, y, x = np.meshgrid(*(np.arange(3.0),) * 3, indexing="ij")
    coords = np.stack([x, y, z], axis=-1).reshape(-1, 3)
    grid = vtkStructuredGrid()
    grid.SetDimensions(3, 3, 3)
    points = vtkPoints()
    points.SetData(numpy_to_vtk(coords, deep=True))
    grid.SetPoints(points)
    iblank = np.ones(27, dtype=np.int32)
    iblank[0] = 0            # blanked: removes the one hex using point 0
    iblank[26] = -1          # overset interface point: kept
    for name, values in (("IBlank", iblank), ("s", coords[:, 0].copy())):
        array = numpy_to_vtk(values, deep=True)
        array.SetName(name)
        grid.GetPointData().AddArray(array)
    return grid


def test_blanked_cells_are_removed():
    grid = _blanked_grid()
    data.flag_hidden_cells(grid)
    tets = data.to_unstructured(grid, "s", tetrahedralize=True)
    assert tets.GetNumberOfCells() == 7 * 5
    assert tets.GetCellData().GetNumberOfArrays() == 0
    hexes = data.to_unstructured(grid, "s", tetrahedralize=False)
    assert hexes.GetNumberOfCells() == 7


def test_data_dir_env(tmp_path, monkeypatch):
    monkeypatch.setenv(data.DATA_DIR_ENV, str(tmp_path))
    assert data.data_dir() == tmp_path.resolve()
    monkeypatch.setenv(data.DATA_DIR_ENV, str(tmp_path / "missing"))
    with pytest.raises(FileNotFoundError, match=data.DATA_DIR_ENV):
        data.data_dir()


@pytest.mark.parametrize("unset", ["unset", "empty"])
def test_data_dir_is_only_where_the_user_says(tmp_path, monkeypatch, unset):
    """Without SPT_DATA_DIR, no folder is guessed: not the working directory's, nor a
    shared/data folder above it (the same command must find the same data anywhere)."""
    if unset == "unset":
        monkeypatch.delenv(data.DATA_DIR_ENV, raising=False)
    else:
        monkeypatch.setenv(data.DATA_DIR_ENV, "")
    (tmp_path / "shared" / "data").mkdir(parents=True)
    (tmp_path / "shared" / "data" / "spx.vtk").write_text("")
    work = tmp_path / "repo" / "sub"
    work.mkdir(parents=True)
    monkeypatch.chdir(work)
    with pytest.raises(FileNotFoundError, match=data.DATA_DIR_ENV):
        data.data_dir()
    with pytest.raises(FileNotFoundError, match=data.DATA_DIR_ENV):
        data.load("spx")


def test_unknown_dataset():
    with pytest.raises(KeyError):
        data.load("no-such-data-set")


def _require_data_dir():
    try:
        return data.data_dir()
    except FileNotFoundError as error:
        pytest.skip(str(error))


@pytest.mark.parametrize("name", sorted(README_TETS))
def test_real_dataset_tet_counts(name):
    _require_data_dir()
    try:
        grid = data.load(name)
    except data.UnreadableDataError as error:
        # A fault of VTK 9.2 with the system's expat, reported clearly; not the loader's.
        assert "expat" in str(error) and name in data.DATASETS
        pytest.skip(str(error))
    assert grid.GetNumberOfCells() == README_TETS[name]
    assert set(vtk_to_numpy(grid.GetDistinctCellTypesArray())) == {VTK_TETRA}
    scalars = grid.GetPointData().GetScalars()
    assert scalars is not None
    assert scalars.GetName() == data.DATASETS[name][1]
    assert grid.GetPointData().GetNumberOfArrays() == 1
    assert grid.GetCellData().GetNumberOfArrays() == 0
    if name in README_RANGES:
        assert scalars.GetRange() == pytest.approx(README_RANGES[name], abs=1e-3)


def test_structured_load_without_tetrahedralize():
    _require_data_dir()
    hexes = data.load("bluntfin", tetrahedralize=False)
    assert hexes.GetNumberOfCells() == 39 * 31 * 31
