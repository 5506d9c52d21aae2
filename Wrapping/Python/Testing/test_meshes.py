"""spt.meshes and vtkTetGenMesher from Python: the generated shapes are closed, their meshes
have the size asked for and fill the surface, the field is usable, the cache round-trips, and
bad arguments are refused with a clear ValueError.

The meshes are small (10,000 to 20,000 tetrahedra, under a second each), and every cache is a
temporary folder (SPT_CACHE_DIR)."""

import collections

import numpy as np
import pytest
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkCommand
from vtkmodules.vtkCommonDataModel import VTK_TETRA
from vtkmodules.vtkIOLegacy import vtkUnstructuredGridReader

import spt
from spt import cli, meshes

SMALL = 20_000


@pytest.fixture(autouse=True)
def cache_folder(tmp_path, monkeypatch):
    folder = tmp_path / "cache"
    monkeypatch.setenv("SPT_CACHE_DIR", str(folder))
    return folder


def edge_uses(triangles: np.ndarray) -> collections.Counter:
    """Directed edge -> number of triangles running along it."""
    return collections.Counter((int(triangle[k]), int(triangle[(k + 1) % 3]))
                               for triangle in triangles for k in range(3))


def tet_volumes(points: np.ndarray, tets: np.ndarray) -> np.ndarray:
    a, b, c, d = (points[tets[:, k]] for k in range(4))
    return np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a)) / 6.0


def grid_arrays(grid):
    points = vtk_to_numpy(grid.GetPoints().GetData())
    tets = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).reshape(-1, 4)
    return points, tets


@pytest.mark.parametrize("shape", meshes.SHAPES)
@pytest.mark.parametrize("resolution", [8, 24])
def test_surface_is_closed_and_faces_outwards(shape, resolution):
    points, triangles = meshes.surface_arrays(shape, resolution)
    uses = edge_uses(triangles)
    # Closed, manifold and consistently oriented: each edge once in each direction.
    assert all(count == 1 for count in uses.values())
    assert all((b, a) in uses for a, b in uses)
    assert meshes.signed_volume(points, triangles) > 0.0
    assert np.isfinite(points).all()
    polydata = meshes.surface(shape, resolution)
    assert polydata.GetNumberOfPolys() == len(triangles)


@pytest.mark.parametrize("shape", meshes.SHAPES)
def test_surface_converges_to_the_shape_volume(shape):
    coarse, fine = (meshes.signed_volume(*meshes.surface_arrays(shape, r)) for r in (32, 128))
    assert abs(fine - meshes._VOLUMES[shape]) < 0.002 * meshes._VOLUMES[shape]
    assert abs(coarse - meshes._VOLUMES[shape]) > abs(fine - meshes._VOLUMES[shape])


def test_drill_is_not_convex():
    # A closed surface is convex when every point lies behind every triangle's plane; the
    # drill's flutes put points in front of a large part of them.
    points, triangles = meshes.surface_arrays("drill", 32)
    a, b, c = (points[triangles[:, k]] for k in range(3))
    normals = np.cross(b - a, c - a)
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    ahead = np.einsum("tj,pj->tp", normals, points) - np.einsum("tj,tj->t", normals, a)[:, None]
    assert np.mean(ahead.max(axis=1) > 0.01) > 0.2


@pytest.mark.parametrize("shape", meshes.SHAPES)
def test_generated_mesh_has_the_size_and_fills_the_surface(shape):
    grid = meshes.generate(shape, SMALL, cache=False)
    count = grid.GetNumberOfCells()
    assert abs(count / SMALL - 1.0) < 0.25, count
    assert set(vtk_to_numpy(grid.GetDistinctCellTypesArray())) == {VTK_TETRA}
    points, tets = grid_arrays(grid)
    volumes = tet_volumes(points, tets)
    assert volumes.min() > 0.0
    resolution, _ = meshes.mesh_parameters(shape, SMALL)
    enclosed = meshes.signed_volume(*meshes.surface_arrays(shape, resolution))
    # TetGen treats triangles within 0.1 degrees of coplanar as one facet and may put points
    # slightly off them (3e-6 here); one missing tetrahedron would be 5e-5.
    assert abs(volumes.sum() - enclosed) < 2e-5 * enclosed
    scalars = grid.GetPointData().GetScalars()
    assert scalars is not None and scalars.GetName() == "field"
    values = vtk_to_numpy(scalars)
    assert values.shape == (grid.GetNumberOfPoints(),)
    assert np.isfinite(values).all() and values.min() >= 0.0 and values.max() <= 1.0
    # Worth volume rendering: spread over its range, not one value.
    assert np.percentile(values, 90) - np.percentile(values, 10) > 0.2


def test_an_interrupted_cache_write_leaves_no_file(tmp_path):
    """A run stopped while it writes a cache file (the mesh, an exact reference) leaves neither
    a partial file, which every later run would fail to read, nor a temporary one."""
    path = tmp_path / "cache" / "reference.npy"

    def interrupted(stream):
        stream.write(b"\x93NUMPY partial")
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        meshes.save_atomically(path, interrupted)
    assert not list(path.parent.iterdir())
    meshes.save_atomically(path, lambda stream: np.save(stream, np.arange(3.0)))
    assert np.array_equal(np.load(path), np.arange(3.0)) and len(list(path.parent.iterdir())) == 1


def test_cache_round_trip_gives_the_same_mesh(cache_folder, monkeypatch):
    first = meshes.generate_arrays("torus", 10_000, seed=3)
    path = meshes.cache_path("torus", 10_000, seed=3)
    assert path.parent == cache_folder and path.is_file()
    assert not list(cache_folder.glob("*.tmp"))

    def no_meshing(*arguments):
        raise AssertionError("the cached mesh should have been read")
    monkeypatch.setattr(meshes, "tetrahedralize", no_meshing)
    second = meshes.generate_arrays("torus", 10_000, seed=3)
    for name in ("points", "tetrahedra", "field"):
        assert np.array_equal(getattr(first, name), getattr(second, name)), name
    grid = meshes.generate("torus", 10_000, seed=3)
    points, tets = grid_arrays(grid)
    assert np.array_equal(points, first.points) and np.array_equal(tets, first.tetrahedra)


def test_unreadable_cache_file_is_replaced(cache_folder):
    path = meshes.cache_path("drill", 10_000)
    path.parent.mkdir(parents=True)
    path.write_bytes(b"not a mesh")
    mesh = meshes.generate_arrays("drill", 10_000)
    assert len(mesh.tetrahedra) > 0
    assert meshes.load_cached(path) is not None


def test_a_cache_that_cannot_be_written_keeps_the_mesh(monkeypatch):
    """/proc takes no new folders, even for root: the mesh is returned, with a warning."""
    monkeypatch.setenv("SPT_CACHE_DIR", "/proc/spt-cache")
    with pytest.warns(UserWarning, match="could not be cached at /proc/spt-cache"):
        mesh = meshes.generate_arrays("drill", 10_000)
    assert len(mesh.tetrahedra) > 0


def test_seed_moves_the_field_not_the_mesh():
    points, _ = meshes.surface_arrays("drill", 16)
    a, b = meshes.field("drill", points, 0), meshes.field("drill", points, 1)
    assert np.array_equal(a, meshes.field("drill", points, 0))
    assert np.abs(a - b).max() > 0.05
    names = {meshes.cache_path("drill", 10_000, seed).name for seed in (0, 1)}
    assert len(names) == 2


@pytest.mark.parametrize("call, message", [
    (lambda: meshes.generate("cube", SMALL), "unknown shape 'cube'"),
    (lambda: meshes.generate("drill", 5), "cells 5 is outside"),
    (lambda: meshes.generate("drill", 10 ** 9), "is outside"),
    (lambda: meshes.generate("drill", 20000.5), "cells must be a whole number"),
    (lambda: meshes.generate("drill", True), "cells must be a whole number"),
    (lambda: meshes.generate("drill", SMALL, seed=-1), "seed must be >= 0"),
    (lambda: meshes.surface("torus", 3), "resolution 3 is outside"),
    (lambda: meshes.surface("ring", 16), "unknown shape"),
])
def test_bad_arguments_raise_value_error(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_mesher_reports_an_open_surface_without_crashing():
    points, triangles = meshes.surface_arrays("torus", 8)
    polydata = meshes.surface("torus", 8)
    polydata.SetPolys(meshes.cell_array(triangles[1:]))
    messages = []
    mesher = spt.vtkTetGenMesher()
    mesher.AddObserver(vtkCommand.ErrorEvent, lambda caller, event: messages.append(event))
    mesher.GetExecutive().AddObserver(vtkCommand.ErrorEvent, lambda caller, event: None)
    mesher.SetInputData(polydata)
    mesher.Update()
    assert messages and mesher.GetOutput().GetNumberOfCells() == 0
    assert len(points) == polydata.GetNumberOfPoints()


def test_cli_writes_a_legacy_file(tmp_path, capsys):
    output = tmp_path / "drill.vtk"
    assert cli.main(["mesh", "--shape", "drill", "--cells", "10000", "--output",
                     str(output)]) == 0
    reader = vtkUnstructuredGridReader()
    reader.SetFileName(str(output))
    reader.Update()
    grid = reader.GetOutput()
    assert abs(grid.GetNumberOfCells() / 10_000 - 1.0) < 0.25
    assert grid.GetPointData().GetArray("field") is not None
    assert cli.main(["mesh", "--cells", "10000", "--output", str(tmp_path / "x.vtu")]) == 1
    assert "must end in .vtk" in capsys.readouterr().err
