"""Long runs of the three mappers: 1000 renders with transfer-function edits, camera moves and
resizes, without growth of the process's memory or of the GPU memory the mapper reports, and
without an error (the mappers check GL errors in debug builds; VTK reports them as errors).
Random input: test_fuzz.py."""

import ctypes
import ctypes.util
import resource

import pytest
import vtk

from spt import data, render

from robustness_support import watch


def _gl_error(window) -> int:
    """glGetError() in the window's context (VTK 9.2 does not wrap CheckGraphicError)."""
    window.MakeCurrent()
    return int(_GL.glGetError())


_GL = ctypes.CDLL(ctypes.util.find_library("GL") or "libGL.so.1")


def _rss_bytes() -> int:
    with open("/proc/self/statm") as statm:
        return int(statm.read().split()[1]) * resource.getpagesize()


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


MAPPERS = {
    "spt": lambda: _small_table(render.spt_mapper(1, seed=1)),
    "havs": lambda: _small_table(render.havs_mapper(2)),
    "pbvr": lambda: render.pbvr_mapper(1, seed=1),
}


def _particle_bytes(mapper) -> int:
    """The GPU memory that depends on the view and the opacity, not on the window size: PBVR's
    particles (8 bytes each)."""
    return 8 * mapper.GetNumberOfParticles() if hasattr(mapper, "GetNumberOfParticles") else 0


@pytest.mark.parametrize("kind", list(MAPPERS))
def test_a_thousand_renders_do_not_grow(kind):
    """1000 renders with transfer-function edits, camera moves and resizes: the process's RSS
    and the GPU memory the mapper reports stop growing after the first renders."""
    grid = _small_mesh()
    prop = data.transfer_function(grid)
    window, renderer = render.make_window(64, 64)
    mapper = MAPPERS[kind]()
    render.add_volume(renderer, grid, prop, mapper)
    renderer.ResetCamera()
    messages = [watch(obj) for obj in (mapper, window, renderer)]
    opacity = prop.GetScalarOpacity()
    sizes = [(64, 64), (80, 48), (48, 72)]
    gpu_bytes, rss, particles, graphic_errors = [], [], [], []
    for frame in range(1000):
        if frame % 7 == 0:
            opacity.AddPoint(0.5, 0.2 + 0.6 * ((frame // 7) % 5) / 4.0)  # moves a point
        renderer.GetActiveCamera().Azimuth(3.0)
        if frame % 50 == 0:
            window.SetSize(*sizes[(frame // 50) % len(sizes)])
        window.Render()
        if frame % 50 == 49:
            held = mapper.GetGPUMemorySize() - _particle_bytes(mapper)
            gpu_bytes.append((window.GetSize(), held))
            particles.append(_particle_bytes(mapper))
            rss.append(_rss_bytes())
            error = _gl_error(window)
            if error:
                graphic_errors.append((frame, hex(error)))
    reported = [text for m in messages for text in m.errors + m.warnings]
    assert not reported and not graphic_errors, (reported, graphic_errors)
    # GPU memory (apart from PBVR's particles, which follow the view) depends only on the
    # window size.
    by_size = {}
    for size, used in gpu_bytes:
        by_size.setdefault(tuple(size), set()).add(used)
    assert all(len(values) == 1 for values in by_size.values()), by_size
    # The particles follow the view and the opacity, which repeat: no more in the second half.
    half = len(particles) // 2
    assert max(particles[half:]) <= max(particles[:half]), particles
    # RSS: what the second half adds is noise, far less than a leak per frame would add.
    growth = rss[-1] - rss[len(rss) // 2]
    assert growth < 8 * 1024 * 1024, f"RSS grew by {growth / 2**20:.1f} MiB over 500 renders"
