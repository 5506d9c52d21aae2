"""The renderers of the benchmark, the generated scenes its sweeps draw, and the timing of one
configuration: frames after a warm-up, the pipeline finished after each."""

from __future__ import annotations

import dataclasses
import time
from typing import Callable, Dict, List, Optional

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtkIdTypeArray, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData, vtkUnstructuredGrid
from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper

from ... import data, meshes, render
from ...scenes import Scene

#: The camera of the generated scenes.
VIEW = render.View(azimuth=30.0, elevation=25.0)

#: SPT's RepetitionsPerPass in the benchmark (the mapper's default).
PER_PASS = 16


@dataclasses.dataclass(frozen=True)
class Method:
    """One renderer of the comparison. ``make(repetitions, subpixels)`` returns its mapper;
    the floor has none (it draws the faces with vtkPolyDataMapper)."""

    name: str
    label: str
    make: Optional[Callable[[int, int], object]]
    stochastic: bool


def spt_method(stratified: bool, per_pass: int, survivor: bool = True
               ) -> Callable[[int, int], object]:
    """The mapper maker of SPT with the survivor or the visibility estimator."""
    sampling = ({"estimator": "survivor", "exact_coverage": False} if survivor else
                {"estimator": "visibility", "exact_coverage": True})
    return lambda repetitions, subpixels: render.spt_mapper(
        repetitions, subpixels, stratified=stratified, per_pass=per_pass, **sampling)


def havs_method(k: int) -> Method:
    """HAVS-like with a k-buffer of ``k`` fragments."""
    return Method(f"havs{k}", f"HAVS-like k={k}", lambda r, s: render.havs_mapper(k), False)


#: "spt" is the survivor estimator (the paper's estimator, drawn 16 repetitions per pass with
#: stratified thresholds), which the time and memory models describe; "spt-visibility" is the
#: mapper's default (the visibility estimator with exact coverage: one more traversal per
#: image, no hashing in the colour traversals).
METHODS: Dict[str, Method] = {m.name: m for m in (
    Method("spt", "SPT survivor (16 per pass, stratified)", spt_method(True, PER_PASS), True),
    Method("spt-visibility", "SPT default (visibility, exact coverage)",
           spt_method(True, PER_PASS, survivor=False), True),
    Method("spt-paper", "SPT, paper (1 per pass, independent)", spt_method(False, 1), True),
    Method("spt-independent", "SPT survivor (16 per pass, independent)",
           spt_method(False, PER_PASS), True),
    havs_method(2),
    havs_method(4),
    havs_method(6),
    Method("pbvr", "PBVR", lambda r, s: render.pbvr_mapper(r, s), True),
    Method("pt", "VTK projected tetrahedra", lambda r, s: render.projected_tetrahedra_mapper(),
           False),
    Method("floor", "floor: all faces opaque (vtkPolyDataMapper)", None, False),
)}


def label(name: str) -> str:
    """The label of the method ``name``, or the name where it is none of METHODS."""
    return METHODS[name].label if name in METHODS else name


def generated_mesh(shape: str, cells: int) -> vtkUnstructuredGrid:
    """A generated mesh of about ``cells`` tetrahedra: TetGen's drill or torus
    (:mod:`spt.meshes`, cached on disk), or ``helix``, the embedded default mesh at the
    nearest resolution (48,000 r^3 cells)."""
    if shape == "helix":
        return data.make_default_mesh(max(1, round((cells / 48000.0) ** (1.0 / 3.0))))
    return meshes.generate(shape, cells)


def generated_scene(shape: str, cells: int) -> Scene:
    """The scene of :func:`generated_mesh`, named by shape and cell count."""
    grid = generated_mesh(shape, cells)
    return Scene(f"{shape}-{grid.GetNumberOfCells()}", grid, data.transfer_function(grid), VIEW)


def face_polydata(grid: vtkUnstructuredGrid) -> vtkPolyData:
    """All four faces of every tetrahedron (shared faces twice), as the floor draws them."""
    connectivity = vtk_to_numpy(grid.GetCells().GetConnectivityArray())
    tets = connectivity.reshape(-1, 4).astype(np.int64)
    faces = tets[:, [[0, 1, 2], [0, 3, 1], [1, 3, 2], [0, 2, 3]]].reshape(-1)
    offsets = np.arange(0, faces.size + 1, 3, dtype=np.int64)
    polys = vtkCellArray()
    polys.SetData(numpy_to_vtkIdTypeArray(offsets, deep=True),
                  numpy_to_vtkIdTypeArray(faces, deep=True))
    polydata = vtkPolyData()
    polydata.SetPoints(grid.GetPoints())
    polydata.SetPolys(polys)
    return polydata


#: Called right before the timed frames; returns what to call right after them.
FramesHook = Callable[[], Callable[[], None]]


@dataclasses.dataclass
class Timing:
    """The frames of one configuration: every frame's wall seconds, the CPU seconds of the
    whole process and of the application thread alone, what the mapper reported, and the
    image of the last frame."""

    seconds: List[float]
    report: Dict[str, float]
    image: Optional[np.ndarray] = None
    cpu_seconds: List[float] = dataclasses.field(default_factory=list)
    thread_seconds: List[float] = dataclasses.field(default_factory=list)

    @property
    def median(self) -> float:
        return float(np.median(self.seconds))

    @property
    def cpu_median(self) -> float:
        return float(np.median(self.cpu_seconds)) if self.cpu_seconds else float("nan")

    @property
    def thread_median(self) -> float:
        return float(np.median(self.thread_seconds)) if self.thread_seconds else float("nan")


def _add_floor(renderer, s: Scene) -> None:
    mapper = vtkPolyDataMapper()
    mapper.SetInputData(face_polydata(s.grid))
    mapper.ScalarVisibilityOff()
    actor = vtkActor()
    actor.SetMapper(mapper)
    renderer.AddActor(actor)


def timed_frames(window, frames: int) -> Timing:
    """``frames`` frames, each finished, timed in wall, process and thread time."""
    seconds, cpu_seconds, thread_seconds = [], [], []
    for _ in range(frames):
        start, cpu_start = time.perf_counter(), time.process_time()
        thread_start = time.thread_time()
        window.Render()
        window.WaitForCompletion()
        seconds.append(time.perf_counter() - start)
        cpu_seconds.append(time.process_time() - cpu_start)
        thread_seconds.append(time.thread_time() - thread_start)
    return Timing(seconds, {}, None, cpu_seconds, thread_seconds)


def time_method(s: Scene, method: Method, size: int, repetitions: int = 16,
                subpixels: int = 1, frames: int = 3, keep_image: bool = False,
                on_frames: Optional[FramesHook] = None) -> Timing:
    """Render ``s`` with ``method`` ``frames`` times after one untimed frame; every frame
    does the whole work (SPT's progressive refinement is off). ``on_frames``: the host-time
    profiler's hook around the timed frames."""
    window, renderer = render.make_window(size, size)
    volume_mapper = None
    if method.make is None:
        _add_floor(renderer, s)
    else:
        volume_mapper = method.make(repetitions, subpixels)
        render.add_volume(renderer, s.grid, s.property, volume_mapper)
    render.place_camera(renderer, s.grid.GetBounds(), s.view)
    if volume_mapper is not None:
        render.warm_up(window, volume_mapper)
    else:
        window.Render()
        window.WaitForCompletion()
    finish = on_frames() if on_frames is not None else None
    timing = timed_frames(window, frames)
    if finish is not None:
        finish()
    if volume_mapper is not None:
        timing.report = render.mapper_report(volume_mapper)
        if hasattr(volume_mapper, "GetLastSortTime"):
            timing.report["sort_seconds"] = volume_mapper.GetLastSortTime()
        if hasattr(volume_mapper, "GetLastRepetitionCount"):
            timing.report["repetitions_drawn"] = float(volume_mapper.GetLastRepetitionCount())
    timing.image = render.read_rgba(window) if keep_image else None
    renderer.RemoveAllViewProps()
    window.Finalize()
    return timing


def record(s: Scene, method: Method, size: int, repetitions: int, subpixels: int,
           timing: Timing, **extra) -> Dict[str, object]:
    """One entry of the results: the configuration, the median times, what the mapper
    reported, and ``extra``."""
    entry: Dict[str, object] = {
        "scene": s.name, "method": method.name, "cells": s.grid.GetNumberOfCells(),
        "points": s.grid.GetNumberOfPoints(), "width": size, "height": size,
        "repetitions": repetitions if method.stochastic else 1,
        "subpixels": subpixels if method.name.startswith(("spt", "pbvr")) else 1,
        "seconds": timing.median, "frames": timing.seconds,
        "cpu_seconds": timing.cpu_median}
    entry.update(timing.report)
    entry.update(extra)
    return entry
