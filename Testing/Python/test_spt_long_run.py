"""Long runs and random input for vtkSPTVolumeMapper: no growth in memory, no errors, no crash."""

import resource

import numpy as np
import vtk
from vtkmodules.util.numpy_support import numpy_to_vtk

from spt import data, render


def _rss_bytes() -> int:
    with open("/proc/self/statm") as statm:
        return int(statm.read().split()[1]) * resource.getpagesize()


class Errors:
    """Counts error and warning events of the objects it watches."""

    def __init__(self, *objects):
        self.count = 0
        for obj in objects:
            obj.AddObserver("ErrorEvent", self._seen)
            obj.AddObserver("WarningEvent", self._seen)

    def _seen(self, *args):
        self.count += 1


def _small_mesh() -> vtk.vtkUnstructuredGrid:
    """About 1700 tetrahedra with a smooth field: these tests are about leaks, not pictures."""
    source = vtk.vtkRTAnalyticSource()
    source.SetWholeExtent(0, 7, 0, 7, 0, 7)
    tetrahedra = vtk.vtkDataSetTriangleFilter()
    tetrahedra.SetInputConnection(source.GetOutputPort())
    tetrahedra.Update()
    return tetrahedra.GetOutput()


def _small_table(mapper):
    mapper.SetPreIntegrationScalarResolution(32)
    mapper.SetPreIntegrationThicknessResolution(16)
    return mapper


def test_a_thousand_renders_do_not_grow(have_display):
    """1000 renders with transfer-function edits, camera moves and resizes: the process's RSS
    and the GPU memory the mapper reports stop growing after the first renders."""
    grid = _small_mesh()
    prop = data.transfer_function(grid)
    window, renderer = render.make_window(64, 64)
    mapper = _small_table(render.spt_mapper(1, seed=1))
    volume = render.add_volume(renderer, grid, prop, mapper)
    renderer.ResetCamera()
    errors = Errors(mapper, window, renderer)
    opacity = prop.GetScalarOpacity()
    sizes = [(64, 64), (80, 48), (48, 72)]
    gpu_bytes, rss = [], []
    for frame in range(1000):
        if frame % 7 == 0:
            opacity.AddPoint(0.5, 0.2 + 0.6 * ((frame // 7) % 5) / 4.0)  # moves a point
        renderer.GetActiveCamera().Azimuth(3.0)
        if frame % 50 == 0:
            window.SetSize(*sizes[(frame // 50) % len(sizes)])
        window.Render()
        if frame % 50 == 49:
            gpu_bytes.append((window.GetSize(), mapper.GetGPUMemorySize()))
            rss.append(_rss_bytes())
    assert errors.count == 0
    # GPU memory depends only on the window size.
    by_size = {}
    for size, used in gpu_bytes:
        by_size.setdefault(tuple(size), set()).add(used)
    assert all(len(values) == 1 for values in by_size.values()), by_size
    # RSS: what the second half adds is noise, far less than a leak per frame would add.
    growth = rss[-1] - rss[len(rss) // 2]
    assert growth < 8 * 1024 * 1024, f"RSS grew by {growth / 2**20:.1f} MiB over 500 renders"


def _random_grid(rng: np.random.Generator) -> vtk.vtkUnstructuredGrid:
    n_points = int(rng.integers(0, 40))
    points = vtk.vtkPoints()
    coordinates = rng.normal(size=(n_points, 3)) * 10.0 ** rng.uniform(-3, 3)
    if n_points and rng.random() < 0.2:
        coordinates[rng.integers(0, n_points)] = np.nan
    points.SetData(numpy_to_vtk(coordinates.reshape(-1, 3), deep=True))
    grid = vtk.vtkUnstructuredGrid()
    grid.SetPoints(points)
    cell_types = [vtk.VTK_TETRA, vtk.VTK_HEXAHEDRON, vtk.VTK_WEDGE, vtk.VTK_PYRAMID,
                  vtk.VTK_TRIANGLE, vtk.VTK_QUADRATIC_TETRA]
    sizes = {vtk.VTK_TETRA: 4, vtk.VTK_HEXAHEDRON: 8, vtk.VTK_WEDGE: 6, vtk.VTK_PYRAMID: 5,
             vtk.VTK_TRIANGLE: 3, vtk.VTK_QUADRATIC_TETRA: 10}
    for _ in range(int(rng.integers(0, 30))):
        cell_type = cell_types[int(rng.integers(0, len(cell_types)))]
        high = max(n_points, 1) + (3 if rng.random() < 0.1 else 0)  # sometimes out of range
        ids = rng.integers(-1 if rng.random() < 0.05 else 0, high, size=sizes[cell_type])
        grid.InsertNextCell(cell_type, len(ids), [int(i) for i in ids])
    if rng.random() < 0.9:
        components = int(rng.choice([1, 1, 3]))
        where = grid.GetPointData() if rng.random() < 0.7 else grid.GetCellData()
        count = n_points if where is grid.GetPointData() else grid.GetNumberOfCells()
        values = rng.normal(size=(count, components)) * 10.0 ** rng.uniform(-5, 5)
        if count and rng.random() < 0.3:
            values[rng.integers(0, count)] = rng.choice([np.nan, np.inf, -np.inf])
        array = numpy_to_vtk(values if components > 1 else values.ravel(), deep=True)
        array.SetName("random")
        where.SetScalars(array)
    return grid


def test_random_meshes_never_crash(have_display):
    """Random points, random and invalid connectivity, random arrays: every render returns,
    either with an image or with an error, and the image is finite."""
    rng = np.random.default_rng(20091116)
    window, renderer = render.make_window(48, 48)
    prop = vtk.vtkVolumeProperty()
    color = vtk.vtkColorTransferFunction()
    color.AddRGBPoint(-1.0, 0.0, 0.0, 1.0)
    color.AddRGBPoint(1.0, 1.0, 0.0, 0.0)
    opacity = vtk.vtkPiecewiseFunction()
    opacity.AddPoint(-1.0, 0.2)
    opacity.AddPoint(1.0, 0.9)
    prop.SetColor(color)
    prop.SetScalarOpacity(opacity)
    errors = Errors()
    for _ in range(150):
        grid = _random_grid(rng)
        mapper = _small_table(render.spt_mapper(2, seed=int(rng.integers(0, 1000))))
        mapper.SetScalarModeToUsePointFieldData() if rng.random() < 0.5 else None
        mapper.SelectScalarArray("random")
        quiet = Errors(mapper)
        volume = render.add_volume(renderer, grid, prop, mapper)
        renderer.ResetCamera()
        window.Render()
        image = render.read_rgba(window)
        assert np.isfinite(image).all()
        renderer.RemoveVolume(volume)
        mapper.ReleaseGraphicsResources(window)
        errors.count += quiet.count
    # Many of these inputs are invalid: the errors were reported, not swallowed.
    assert errors.count > 10
