"""Benchmarks: time and GPU memory of SPT, HAVS-like, PBVR and VTK's projected tetrahedra.

``python3 -m spt bench`` measures, on this machine and in one process:

- sweeps of the cell count (generated meshes, 10 thousand up), the repetition level, the
  subpixel level and the image size, for every method;
- the *floor*: all tetrahedron faces drawn opaque by ``vtkPolyDataMapper`` at the same image
  size, measured next to each point of the cell sweep;
- the fitted time and memory models (the paper's ``T = L_r (a n_c + b w h L_s^2)`` ms and
  ``M = c n_c + d w h L_s^2`` bytes for SPT, the same with particles for PBVR, linear models
  for HAVS-like and VTK's projected tetrahedra), with R^2 and residual plots;
- the crossovers: the repetition level above which PBVR needs more memory than SPT, and SPT
  against HAVS-like in time at equal image error;
- time to quality: image error against the exact reference as a function of render time on
  SPX, Blunt Fin and Oxygen Post, for every method and SPT's sampling modes;
- where SPT's host (application thread) time goes per frame as the cell count grows, from
  ``perf`` samples, to show that no per-cell work is left on the CPU;
- the paper's large case, about 13 million tetrahedra at 1024 x 1024 with 144 repetitions,
  against the prediction of the fitted model.

Each time is the median of several frames after one untimed warm-up frame, taken with the
pipeline finished (``WaitForCompletion``). The results go to ``bench.json``, PNG plots and
one Markdown report, ``bench.md``. Nothing here is part of ``make test``: these are
measurements, not assertions.
"""

from __future__ import annotations

import dataclasses
import json
import math
import os
import pathlib
import shutil
import signal
import subprocess
import tempfile
import time
from typing import Callable, Dict, Iterable, List, Optional, Sequence, Tuple

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtkIdTypeArray, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData, vtkUnstructuredGrid
from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper, vtkVolumeProperty

from . import data, figures, metrics, render, tables
from .progress import Progress

#: The sections of a full run, in the order they run.
SECTIONS = ("cells", "repetitions", "subpixels", "image", "quality", "host", "large")

#: The paper's figures that this report stands next to. Only the memory per tetrahedron is
#: quoted in the project's issue (20.6 bytes); the paper's time coefficients were measured on
#: a 2009 GPU and are not reproduced here.
PAPER = {"spt_bytes_per_cell": 20.6}

VIEW = render.View(azimuth=30.0, elevation=25.0)

#: SPT's RepetitionsPerPass in the benchmark (the mapper's default).
PER_PASS = 16


# --------------------------------------------------------------------------------------------
# Methods
# --------------------------------------------------------------------------------------------

@dataclasses.dataclass(frozen=True)
class Method:
    """One renderer of the comparison. ``make(repetitions, subpixels)`` returns its mapper;
    the floor has none (it draws the faces with vtkPolyDataMapper)."""

    name: str
    label: str
    make: Optional[Callable[[int, int], object]]
    stochastic: bool


def _spt(stratified: bool, per_pass: int, survivor: bool = True
         ) -> Callable[[int, int], object]:
    sampling = ({"estimator": "survivor", "exact_coverage": False} if survivor else
                {"estimator": "visibility", "exact_coverage": True})
    return lambda repetitions, subpixels: render.spt_mapper(
        repetitions, subpixels, stratified=stratified, per_pass=per_pass, **sampling)


#: "spt" is the survivor estimator (the paper's estimator, drawn 16 repetitions per pass with
#: stratified thresholds), which the time and memory models describe; "spt-visibility" is the
#: mapper's default since session 4 (visibility estimator with exact coverage: one more
#: traversal per image, no hashing in the colour traversals).
METHODS: Dict[str, Method] = {m.name: m for m in (
    Method("spt", "SPT survivor (16 per pass, stratified)", _spt(True, PER_PASS), True),
    Method("spt-visibility", "SPT default (visibility, exact coverage)",
           _spt(True, PER_PASS, survivor=False), True),
    Method("spt-paper", "SPT, paper (1 per pass, independent)", _spt(False, 1), True),
    Method("spt-independent", "SPT survivor (16 per pass, independent)",
           _spt(False, PER_PASS), True),
    Method("havs2", "HAVS-like k=2", lambda r, s: render.havs_mapper(2), False),
    Method("havs6", "HAVS-like k=6", lambda r, s: render.havs_mapper(6), False),
    Method("pbvr", "PBVR", lambda r, s: render.pbvr_mapper(r, s), True),
    Method("pt", "VTK projected tetrahedra", lambda r, s: render.projected_tetrahedra_mapper(),
           False),
    Method("floor", "floor: all faces opaque (vtkPolyDataMapper)", None, False),
)}


# --------------------------------------------------------------------------------------------
# Scenes
# --------------------------------------------------------------------------------------------

def generated_mesh(shape: str, cells: int) -> vtkUnstructuredGrid:
    """A generated mesh of about ``cells`` tetrahedra: TetGen's drill or torus
    (:mod:`spt.meshes`, cached on disk), or ``helix``, the embedded default mesh at the
    nearest resolution (48,000 r^3 cells)."""
    if shape == "helix":
        return data.make_default_mesh(max(1, round((cells / 48000.0) ** (1.0 / 3.0))))
    from . import meshes
    return meshes.generate(shape, cells)


def generated_scene(shape: str, cells: int) -> figures.Scene:
    grid = generated_mesh(shape, cells)
    return figures.Scene(f"{shape}-{grid.GetNumberOfCells()}", grid,
                         data.transfer_function(grid), VIEW)


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


# --------------------------------------------------------------------------------------------
# Timing
# --------------------------------------------------------------------------------------------

@dataclasses.dataclass
class Timing:
    """The frames of one configuration: every frame's seconds, their median, what the mapper
    reported, and the image of the last frame."""

    seconds: List[float]
    report: Dict[str, float]
    image: Optional[np.ndarray] = None
    cpu_seconds: List[float] = dataclasses.field(default_factory=list)

    @property
    def median(self) -> float:
        return float(np.median(self.seconds))

    @property
    def cpu_median(self) -> float:
        return float(np.median(self.cpu_seconds)) if self.cpu_seconds else float("nan")


def time_method(s: figures.Scene, method: Method, size: int, repetitions: int = 16,
                subpixels: int = 1, frames: int = 3, keep_image: bool = False,
                on_frames: Optional[Callable[[], Callable[[], None]]] = None) -> Timing:
    """Render ``s`` with ``method`` ``frames`` times after one untimed frame; every frame
    does the whole work (SPT's progressive refinement is off). ``on_frames``, if given, is
    called right before the timed frames and returns what to call right after them (the
    host-time profiler uses it)."""
    window, renderer = render.make_window(size, size)
    if method.make is None:
        mapper = vtkPolyDataMapper()
        mapper.SetInputData(face_polydata(s.grid))
        mapper.ScalarVisibilityOff()
        actor = vtkActor()
        actor.SetMapper(mapper)
        renderer.AddActor(actor)
        volume_mapper = None
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
    seconds, cpu_seconds = [], []
    for _ in range(frames):
        start, cpu_start = time.perf_counter(), time.process_time()
        window.Render()
        window.WaitForCompletion()
        seconds.append(time.perf_counter() - start)
        cpu_seconds.append(time.process_time() - cpu_start)
    if finish is not None:
        finish()
    report = render.mapper_report(volume_mapper) if volume_mapper is not None else {}
    if method.name == "havs2" or method.name == "havs6":
        report["sort_seconds"] = volume_mapper.GetLastSortTime()
    image = render.read_rgba(window) if keep_image else None
    renderer.RemoveAllViewProps()
    window.Finalize()
    return Timing(seconds, report, image, cpu_seconds)


def _record(s: figures.Scene, method: Method, size: int, repetitions: int, subpixels: int,
            timing: Timing, **extra) -> Dict[str, object]:
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


# --------------------------------------------------------------------------------------------
# Sweeps
# --------------------------------------------------------------------------------------------

@dataclasses.dataclass
class Settings:
    """What a run measures. The defaults are the full benchmark; ``quick()`` is a smoke run
    of every section at small sizes."""

    shape: str = "drill"
    cells: Tuple[int, ...] = (10_000, 30_000, 100_000, 300_000, 1_000_000, 3_000_000,
                              10_000_000)
    sweep_cells: int = 300_000            # the mesh of the repetition, subpixel, image sweeps
    size: int = 512                       # image size of the cell and repetition sweeps
    sweep_repetitions: int = 16           # L_r of SPT and PBVR in the other sweeps
    paper_sweep_repetitions: int = 2      # the paper's mode costs a mesh traversal each
    repetitions: Tuple[int, ...] = (1, 2, 4, 8, 16, 32, 64, 128, 256)
    paper_repetitions: int = 32           # the largest L_r of the paper's mode
    subpixels: Tuple[int, ...] = (1, 2, 3, 4)
    sizes: Tuple[int, ...] = (256, 512, 768, 1024)
    frames: int = 3
    methods: Tuple[str, ...] = ("spt", "spt-visibility", "spt-paper", "havs2", "havs6", "pbvr",
                                "pt", "floor")
    # the slow methods stop growing the cell sweep here (seconds of one frame)
    frame_limit: float = 120.0
    quality_datasets: Tuple[str, ...] = ("spx", "bluntfin", "post")
    quality_size: int = 256
    quality_levels: Tuple[int, ...] = (4, 16, 64, 256)
    host_cells: Tuple[int, ...] = (100_000, 1_000_000, 3_000_000)
    large_cells: int = 13_000_000
    large_size: int = 1024
    large_repetitions: int = 144
    # run the sections for these methods only, keeping the other methods' earlier results
    only_methods: Optional[Tuple[str, ...]] = None

    def wants(self, name: str) -> bool:
        return self.only_methods is None or name in self.only_methods

    @staticmethod
    def quick() -> "Settings":
        return Settings(cells=(10_000, 30_000, 100_000), sweep_cells=30_000, size=256,
                        sweep_repetitions=4, paper_sweep_repetitions=1,
                        repetitions=(1, 4, 16), paper_repetitions=4, subpixels=(1, 2),
                        sizes=(128, 256), frames=2, quality_datasets=("spx",),
                        quality_size=128, quality_levels=(4, 16), host_cells=(10_000, 30_000),
                        large_cells=100_000, large_size=256, large_repetitions=16)


def sweep_cells(settings: Settings, progress: Progress) -> List[Dict[str, object]]:
    """Every method at every cell count, the floor next to each; a method whose frame took
    longer than ``frame_limit`` stops there."""
    results = []
    stopped = set()
    for cells in settings.cells:
        s = generated_scene(settings.shape, cells)
        for name in settings.methods:
            method = METHODS[name]
            if not settings.wants(name):
                continue
            if name in stopped:
                progress.step(f"{name} skipped")
                continue
            repetitions = _sweep_level(settings, name)
            timing = time_method(s, method, settings.size, repetitions, 1, settings.frames)
            results.append(_record(s, method, settings.size, repetitions, 1, timing,
                                   sweep="cells"))
            if timing.median > settings.frame_limit:
                stopped.add(name)
            progress.step(f"{name} {s.grid.GetNumberOfCells()} cells {timing.median:.2f} s")
    return results


#: The methods of the repetition and subpixel sweeps.
REPETITION_METHODS = ("spt", "spt-visibility", "spt-paper", "pbvr")


def _wanted(settings: Settings, names: Sequence[str]) -> List[str]:
    return [name for name in names if settings.wants(name)]


def _sweep_level(settings: Settings, name: str) -> int:
    return settings.paper_sweep_repetitions if name == "spt-paper" else settings.sweep_repetitions


def sweep_repetitions(settings: Settings, progress: Progress) -> List[Dict[str, object]]:
    s = generated_scene(settings.shape, settings.sweep_cells)
    results = []
    for name in _wanted(settings, REPETITION_METHODS):
        for level in settings.repetitions:
            if name == "spt-paper" and level > settings.paper_repetitions:
                progress.step(f"{name} L={level} skipped")
                continue
            timing = time_method(s, METHODS[name], settings.size, level, 1, settings.frames)
            results.append(_record(s, METHODS[name], settings.size, level, 1, timing,
                                   sweep="repetitions"))
            progress.step(f"{name} L={level} {timing.median:.2f} s")
    return results


def sweep_subpixels(settings: Settings, progress: Progress) -> List[Dict[str, object]]:
    s = generated_scene(settings.shape, settings.sweep_cells)
    size = min(settings.sizes)
    results = []
    for name in _wanted(settings, REPETITION_METHODS):
        level = _sweep_level(settings, name)
        for subpixels in settings.subpixels:
            timing = time_method(s, METHODS[name], size, level, subpixels, settings.frames)
            results.append(_record(s, METHODS[name], size, level, subpixels, timing,
                                   sweep="subpixels"))
            progress.step(f"{name} Ls={subpixels} {timing.median:.2f} s")
    return results


def sweep_image(settings: Settings, progress: Progress) -> List[Dict[str, object]]:
    s = generated_scene(settings.shape, settings.sweep_cells)
    results = []
    for size in settings.sizes:
        for name in _wanted(settings, settings.methods):
            level = _sweep_level(settings, name)
            timing = time_method(s, METHODS[name], size, level, 1, settings.frames)
            results.append(_record(s, METHODS[name], size, level, 1, timing, sweep="image"))
            progress.step(f"{name} {size}^2 {timing.median:.2f} s")
    return results


def _steps(settings: Settings, section: str) -> int:
    methods = len(_wanted(settings, settings.methods))
    swept = len(_wanted(settings, REPETITION_METHODS))
    stochastic = len(_wanted(settings, ("spt", "spt-visibility", "spt-independent", "pbvr",
                                        "spt-paper")))
    exact = len(_wanted(settings, ("havs2", "havs4", "havs6", "pt")))
    return {
        "cells": len(settings.cells) * methods,
        "repetitions": swept * len(settings.repetitions),
        "subpixels": swept * len(settings.subpixels),
        "image": len(settings.sizes) * methods,
        "quality": len(settings.quality_datasets) * (
            1 + stochastic * len(settings.quality_levels) + exact),
        "host": len(settings.host_cells),
        "large": 1,
    }[section]


# --------------------------------------------------------------------------------------------
# Time to quality
# --------------------------------------------------------------------------------------------

def quality(settings: Settings, progress: Progress, output: pathlib.Path
            ) -> List[Dict[str, object]]:
    """Image error against the exact reference and render time, for every method on the real
    data sets. The paper's mode draws the same image as 16 independent repetitions per pass
    (tested), so its error is that image's; only its time is measured separately, up to
    ``paper_repetitions``."""
    results = []
    size = settings.quality_size
    for name in settings.quality_datasets:
        s = figures.scene(name)
        reference = render.reference(s.grid, s.property, s.view, (size, size)).image
        metrics.write_png(output / f"quality_{name}_reference.png", reference)
        progress.step(f"{name} reference")

        def measure(method: Method, level: int, **extra) -> Dict[str, object]:
            timing = time_method(s, method, size, level, 1, settings.frames, keep_image=True)
            entry = _record(s, method, size, level, 1, timing, sweep="quality", **extra)
            if timing.image is not None:
                entry["rmse"] = metrics.rmse(timing.image, reference)
                metrics.write_png(output / f"quality_{name}_{method.name}_{level}.png",
                                  timing.image)
            progress.step(f"{name} {method.name} L={level} {timing.median:.2f} s")
            return entry

        for level in settings.quality_levels:
            for method_name in ("spt", "spt-visibility", "spt-independent", "pbvr"):
                if settings.wants(method_name):
                    results.append(measure(METHODS[method_name], level))
            if not settings.wants("spt-paper"):
                continue
            if level <= settings.paper_repetitions:
                paper = measure(METHODS["spt-paper"], level)
                results.append(paper)
            else:
                progress.step(f"{name} spt-paper L={level} skipped")
        for method_name in ("havs2", "havs6", "pt"):
            if settings.wants(method_name):
                results.append(measure(METHODS[method_name], 1))
        # HAVS-like k=4, the middle of its range
        if settings.wants("havs4"):
            havs4 = Method("havs4", "HAVS-like k=4", lambda r, sp: render.havs_mapper(4), False)
            results.append(measure(havs4, 1))
    return results


# --------------------------------------------------------------------------------------------
# Host time per frame, from perf samples
# --------------------------------------------------------------------------------------------

#: Where the emulated GPU runs: llvmpipe's JIT-compiled shaders and Mesa's driver.
_GPU_OBJECTS = ("[JIT]", "swrast_dri.so", "libgallium", "[unknown]")
#: The kernel and the C library: on the application thread, mostly the memory that llvmpipe's
#: vertex stage maps and fills for every draw.
_SYSTEM_OBJECTS = ("[kernel", "libc.so")


def _perf_available() -> bool:
    if shutil.which("perf") is None:
        return False
    probe = subprocess.run(["perf", "stat", "-e", "cpu-clock", "true"],
                           capture_output=True, text=True)
    return probe.returncode == 0


def _perf_attach(path: str, frequency: int) -> Callable[[], Callable[[], None]]:
    """An ``on_frames`` hook of :func:`time_method`: perf samples this process (all its
    threads) while the timed frames run."""
    def start() -> Callable[[], None]:
        process = subprocess.Popen(
            ["perf", "record", "-e", "cpu-clock", "-F", str(frequency), "-p", str(os.getpid()),
             "-o", path, "--quiet"],
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        time.sleep(1.0)   # let perf attach to every thread

        def stop() -> None:
            process.send_signal(signal.SIGINT)
            process.wait(timeout=120)
        return stop
    return start


def _perf_seconds_by_object(path: str, frequency: int) -> Dict[Tuple[str, str], float]:
    """Seconds of CPU per (thread name, shared object) in a perf recording."""
    report = subprocess.run(
        ["perf", "report", "-i", path, "--stdio", "--sort", "comm,dso", "-g", "none", "-n",
         "--percent-limit", "0"], capture_output=True, text=True, check=True).stdout
    seconds: Dict[Tuple[str, str], float] = {}
    for line in report.splitlines():
        fields = line.split()
        if len(fields) < 4 or line.startswith("#") or not fields[0].endswith("%"):
            continue
        samples, comm, dso = int(fields[1]), fields[2], " ".join(fields[3:])
        key = (comm, dso)
        seconds[key] = seconds.get(key, 0.0) + samples / frequency
    return seconds


def host_time(settings: Settings, progress: Progress) -> List[Dict[str, object]]:
    """Per frame, the CPU seconds of the application thread by where they are spent, as the
    cell count grows: this project's library, VTK and Python (the host part a real GPU would
    leave on the CPU; a per-cell loop per frame would grow it), the kernel and the C library
    (on this thread mostly llvmpipe's vertex-stage memory), and the emulated GPU itself."""
    if not _perf_available():
        progress.step("perf not available")
        return []
    results = []
    frequency = 499
    frames = max(settings.frames, 3)
    for cells in settings.host_cells:
        s = generated_scene(settings.shape, cells)
        with tempfile.TemporaryDirectory() as directory:
            path = os.path.join(directory, "perf.data")
            timing = time_method(s, METHODS["spt"], settings.size, 16, 1, frames,
                                 on_frames=_perf_attach(path, frequency))
            by_object = _perf_seconds_by_object(path, frequency)
        main = {dso: t for (comm, dso), t in by_object.items() if not comm.startswith("llvmpipe")}
        project = sum(t for dso, t in main.items() if "SPTRendering" in dso)
        system = sum(t for dso, t in main.items() if dso.startswith(_SYSTEM_OBJECTS))
        host = sum(t for dso, t in main.items()
                   if not dso.startswith(_GPU_OBJECTS + _SYSTEM_OBJECTS))
        results.append({
            "scene": s.name, "cells": s.grid.GetNumberOfCells(), "frames": frames,
            "frame_seconds": timing.median,
            "host_seconds_per_frame": host / frames,
            "project_seconds_per_frame": project / frames,
            "system_seconds_per_frame": system / frames,
            "application_thread_seconds_per_frame": sum(main.values()) / frames,
            "worker_seconds_per_frame": sum(
                t for (comm, _), t in by_object.items() if comm.startswith("llvmpipe")) / frames,
            "top_objects": sorted(((t / frames, dso) for dso, t in main.items()),
                                  reverse=True)[:8]})
        progress.step(f"host {cells} cells")
    return results


# --------------------------------------------------------------------------------------------
# Models
# --------------------------------------------------------------------------------------------

@dataclasses.dataclass
class Fit:
    """A linear least-squares model ``y = sum(coefficient_i * term_i)``."""

    name: str
    terms: List[str]
    coefficients: List[float]
    r2: float
    n: int
    observed: List[float]
    predicted: List[float]

    def predict(self, columns: Sequence[float]) -> float:
        columns = list(columns) + [1.0] * (len(self.coefficients) - len(columns))
        return float(np.dot(self.coefficients, columns))

    def as_dict(self) -> Dict[str, object]:
        return dataclasses.asdict(self)


def fit(name: str, terms: Sequence[str], rows: Sequence[Sequence[float]],
        observed: Sequence[float], constant: bool = True) -> Optional[Fit]:
    """Least squares weighted by 1 / observed, so that every point counts by its relative
    error (the sweeps span four decades). ``constant`` adds a fixed term (``fixed``): what a
    frame or a mapper costs whatever the mesh and the image (window, pre-integration table),
    which the paper's forms leave out."""
    terms = list(terms) + (["fixed"] if constant else [])
    rows = [list(row) + ([1.0] if constant else []) for row in rows]
    if len(observed) < len(terms) + 1:
        return None
    design = np.asarray(rows, dtype=float)
    y = np.asarray(observed, dtype=float)
    weights = 1.0 / np.maximum(y, 1e-12)
    coefficients, *_ = np.linalg.lstsq(design * weights[:, None], y * weights, rcond=None)
    predicted = design @ coefficients
    residual = np.sum((y - predicted) ** 2)
    total = np.sum((y - y.mean()) ** 2)
    r2 = 1.0 - residual / total if total > 0 else float("nan")
    return Fit(name + (" + fixed" if constant else ""), terms,
               [float(c) for c in coefficients], float(r2), len(y), y.tolist(),
               predicted.tolist())


def time_key(entries: Sequence[Dict[str, object]]) -> str:
    """``cpu_seconds`` when every entry has it: on a machine that runs other jobs it measures
    the work of the frame, where wall time also counts the waiting; else ``seconds``."""
    have = [e for e in entries if np.isfinite(e.get("cpu_seconds", float("nan")))]
    return "cpu_seconds" if entries and len(have) == len(entries) else "seconds"


def _pixels(entry: Dict[str, object]) -> float:
    return float(entry["width"]) * float(entry["height"]) * float(entry["subpixels"]) ** 2


def time_models(entries: Sequence[Dict[str, object]], key: str = "seconds"
                ) -> Dict[str, Fit]:
    """Time in milliseconds, per method, in the paper's form where it has one. ``key`` is
    ``seconds`` (wall time of the frame) or ``cpu_seconds`` (CPU time of all the process's
    threads, llvmpipe's included: the work done, whatever else the machine runs)."""
    models: Dict[str, Fit] = {}

    def select(name: str) -> List[Dict[str, object]]:
        return [e for e in entries if e["method"] == name and e.get("sweep") != "quality"
                and np.isfinite(e.get(key, float("nan")))]

    for name in ("spt-paper", "spt"):
        rows = [(e["repetitions"] * e["cells"], e["repetitions"] * _pixels(e))
                for e in select(name)]
        model = fit(f"{name}: T = L_r (a n_c + b w h L_s^2)", ["a", "b"], rows,
                    [1000.0 * e[key] for e in select(name)])
        if model:
            models[name] = model
    # SPT with N repetitions per pass: the mesh is traversed twice per pass (keys, colors)
    # and every fragment works for each of the pass's repetitions.
    spt = select("spt")
    rows = [(math.ceil(e["repetitions"] / PER_PASS) * e["cells"],
             math.ceil(e["repetitions"] / PER_PASS) * _pixels(e),
             e["repetitions"] * _pixels(e)) for e in spt]
    model = fit("spt: T = P a n_c + (P b + L_r c) w h L_s^2, P = ceil(L_r / 16)",
                ["a", "b", "c"], rows, [1000.0 * e[key] for e in spt])
    if model:
        models["spt-passes"] = model
    # On a software rasterizer the cost is the fragments': a traversal covers the footprint
    # about as many times as a ray crosses cells, which grows as n_c^(1/3), not as n_c.
    # The default (visibility estimator, exact coverage) adds one traversal per image: half a
    # pass of two traversals.
    for name, per_pass, extra in (("spt-paper", 1, 0.0), ("spt", PER_PASS, 0.0),
                                  ("spt-visibility", PER_PASS, 0.5)):
        chosen = select(name)
        passes = [math.ceil(e["repetitions"] / per_pass) + extra for e in chosen]
        rows = [(p * e["cells"], p * _pixels(e) * e["cells"] ** (1 / 3),
                 e["repetitions"] * _pixels(e)) for p, e in zip(passes, chosen)]
        label = f"ceil(L_r / {per_pass})" + (f" + {extra:g}" if extra else "")
        model = fit(f"{name}: T = P (a n_c + b w h L_s^2 n_c^(1/3)) + L_r c w h L_s^2, "
                    f"P = {label}", ["a", "b", "c"], rows,
                    [1000.0 * e[key] for e in chosen])
        if model:
            models[f"{name}-fragments"] = model
    pbvr = [e for e in select("pbvr") if e.get("particles")]
    rows = [(e["particles"], e["repetitions"] * _pixels(e)) for e in pbvr]  # particles: n_p L_r
    model = fit("pbvr: T = L_r (a n_p + b w h L_s^2), n_p particles per repetition",
                ["a", "b"], rows, [1000.0 * e[key] for e in pbvr])
    if model:
        models["pbvr"] = model
    for name in ("havs2", "havs6", "pt", "floor"):
        chosen = select(name)
        rows = [(e["cells"], _pixels(e)) for e in chosen]
        model = fit(f"{name}: T = a n_c + b w h", ["a", "b"], rows,
                    [1000.0 * e[key] for e in chosen])
        if model:
            models[name] = model
    return models


def memory_models(entries: Sequence[Dict[str, object]]) -> Dict[str, Fit]:
    """GPU bytes each mapper reports, in the paper's form ``M = c n + d w h L_s^2``."""
    models: Dict[str, Fit] = {}
    with_memory = [e for e in entries if e.get("gpu_memory")]
    for name in ("spt", "spt-visibility", "spt-paper", "havs2", "havs6"):
        chosen = [e for e in with_memory if e["method"] == name]
        rows = [(e["cells"], _pixels(e)) for e in chosen]
        model = fit(f"{name}: M = c n_c + d w h L_s^2", ["c", "d"], rows,
                    [e["gpu_memory"] for e in chosen])
        if model:
            models[name] = model
    chosen = [e for e in with_memory if e["method"] == "pbvr" and e.get("particles")]
    # PBVR reports the particles of all its sets: n_p L_r.
    rows = [(e["particles"], _pixels(e)) for e in chosen]
    model = fit("pbvr: M = c n_p L_r + d w h L_s^2", ["c", "d"], rows,
                [e["gpu_memory"] for e in chosen])
    if model:
        models["pbvr"] = model
    return models


def crossovers(entries: Sequence[Dict[str, object]], memory: Dict[str, Fit]
               ) -> Dict[str, object]:
    """Where one method overtakes another.

    - Memory, SPT against PBVR: PBVR keeps ``L_r`` particle sets of ``n_p`` particles, SPT
      one copy of the mesh; PBVR needs more once ``L_r > c_SPT n_c / (c_PBVR n_p)``.
    - Time at equal error, SPT against HAVS-like: on each data set, the repetition level at
      which SPT's error falls to HAVS-like's (interpolated on the log-log curve), and the
      times there.
    """
    result: Dict[str, object] = {"memory": [], "time_at_equal_error": []}
    if "spt" in memory and "pbvr" in memory:
        c_spt, c_pbvr = memory["spt"].coefficients[0], memory["pbvr"].coefficients[0]
        pbvr = [e for e in entries if e["method"] == "pbvr" and e.get("particles")]
        seen = set()
        for e in pbvr:
            if e["scene"] in seen:
                continue
            seen.add(e["scene"])
            per_repetition = e["particles"] / max(e.get("particle_sets", 1.0), 1.0)
            level = (c_spt * e["cells"] / (c_pbvr * per_repetition) if c_pbvr > 0
                     else math.inf)
            result["memory"].append({"scene": e["scene"], "cells": e["cells"],
                                     "particles_per_repetition": per_repetition,
                                     "repetitions_at_equal_memory": level})
    quality_entries = [e for e in entries if e.get("sweep") == "quality" and "rmse" in e]
    for scene, name in sorted({(e["scene"], e["method"]) for e in quality_entries
                               if e["method"] in ("spt", "spt-visibility")}):
        spt = sorted((e for e in quality_entries if e["scene"] == scene and e["method"] == name),
                     key=lambda e: e["repetitions"])
        if len(spt) < 2:
            continue
        key = time_key(spt)
        levels = np.log([e["repetitions"] for e in spt])
        errors = np.log([e["rmse"] for e in spt])
        seconds = np.log([e[key] for e in spt])
        slope, intercept = np.polyfit(levels, errors, 1)
        time_slope, time_intercept = np.polyfit(levels, seconds, 1)
        for havs in (e for e in quality_entries
                     if e["scene"] == scene and e["method"].startswith("havs")):
            level = math.exp((math.log(havs["rmse"]) - intercept) / slope) if slope < 0 else math.inf
            spt_seconds = math.exp(time_intercept + time_slope * math.log(max(level, 1.0)))
            # Already below HAVS-like's error at the lowest level measured: that level and its
            # measured time are an upper bound, not an extrapolation.
            below = spt[0]["rmse"] <= havs["rmse"]
            if below:
                level, spt_seconds = spt[0]["repetitions"], spt[0][key]
            result["time_at_equal_error"].append({
                "scene": scene, "spt": name, "havs": havs["method"], "havs_rmse": havs["rmse"],
                "havs_seconds": havs[key], "spt_repetitions": level, "time": key,
                "spt_seconds": spt_seconds, "spt_over_havs": spt_seconds / havs[key],
                "at_most": below})
    result["sampling"] = sampling_gains(quality_entries)
    return result


def _curve(entries: Sequence[Dict[str, object]], scene: str, method: str
           ) -> List[Dict[str, object]]:
    return sorted((e for e in entries if e["scene"] == scene and e["method"] == method),
                  key=lambda e: e["repetitions"])


def sampling_gains(entries: Sequence[Dict[str, object]]) -> List[Dict[str, object]]:
    """Beyond the paper, per data set: how much faster 16 repetitions per pass are than the
    paper's one per pass at equal error (they draw the same image, so at equal L_r), and how
    many stratified repetitions reach the error of the most independent ones measured."""
    rows = []
    for scene in sorted({e["scene"] for e in entries}):
        paper = _curve(entries, scene, "spt-paper")
        independent = _curve(entries, scene, "spt-independent")
        stratified = _curve(entries, scene, "spt")
        if not independent or not stratified:
            continue
        key = time_key(paper + independent + stratified)
        row: Dict[str, object] = {"scene": scene, "time": key}
        pairs = [(p, i) for p in paper for i in independent if p["repetitions"] == i["repetitions"]]
        if pairs:
            p, i = pairs[-1]
            row["per_pass_repetitions"] = p["repetitions"]
            row["per_pass_speedup"] = p[key] / i[key]
            row["per_pass_rmse"] = (p["rmse"], i["rmse"])
        target = independent[-1]
        levels = np.log([e["repetitions"] for e in stratified])
        errors = np.log([e["rmse"] for e in stratified])
        slope, intercept = np.polyfit(levels, errors, 1)
        needed = math.exp((math.log(target["rmse"]) - intercept) / slope) if slope < 0 else math.inf
        row.update({"independent_repetitions": target["repetitions"],
                    "independent_rmse": target["rmse"], "stratified_repetitions": needed,
                    "stratified_slope": slope})
        rows.append(row)
    return rows


# --------------------------------------------------------------------------------------------
# Plots and report
# --------------------------------------------------------------------------------------------

def _figure(width: float, height: float):
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    figure = Figure(figsize=(width, height))
    FigureCanvasAgg(figure)
    return figure


def _plot_sweep(entries: Sequence[Dict[str, object]], sweep: str, x_key: str, xlabel: str,
                path: pathlib.Path, per_repetition: bool = False) -> None:
    chosen = [e for e in entries if e.get("sweep") == sweep]
    if not chosen:
        return
    key = time_key(chosen)
    figure = _figure(10, 4.2)
    axes_time, axes_memory = figure.add_subplot(1, 2, 1), figure.add_subplot(1, 2, 2)
    for name in METHODS:
        points = sorted((e for e in chosen if e["method"] == name), key=lambda e: e[x_key])
        if not points:
            continue
        x = [e[x_key] if x_key != "width" else e["width"] * e["height"] for e in points]
        y = [e[key] / (e["repetitions"] if per_repetition else 1) for e in points]
        axes_time.loglog(x, y, "o-", label=METHODS[name].label)
        memory = [(xx, e["gpu_memory"]) for xx, e in zip(x, points) if e.get("gpu_memory")]
        if memory:
            axes_memory.loglog(*zip(*memory), "o-", label=METHODS[name].label)
    axes_time.set_xlabel(xlabel)
    unit = "CPU seconds (all threads)" if key == "cpu_seconds" else "seconds"
    axes_time.set_ylabel(f"{unit} per repetition" if per_repetition else f"{unit} per frame")
    axes_memory.set_xlabel(xlabel)
    axes_memory.set_ylabel("GPU bytes the mapper reports")
    for axes in (axes_time, axes_memory):
        axes.grid(True, which="both", alpha=0.3)
    axes_time.legend(fontsize=7)
    figure.tight_layout()
    figure.savefig(str(path), dpi=110)


def _plot_residuals(models: Dict[str, Fit], path: pathlib.Path, unit: str) -> None:
    if not models:
        return
    columns = min(4, len(models))
    rows = math.ceil(len(models) / columns)
    figure = _figure(3.2 * columns, 2.8 * rows)
    for index, (name, model) in enumerate(models.items()):
        axes = figure.add_subplot(rows, columns, index + 1)
        observed, predicted = np.array(model.observed), np.array(model.predicted)
        axes.semilogx(predicted, (observed - predicted) / observed, "o", markersize=3)
        axes.axhline(0.0, color="gray", linewidth=0.8)
        axes.set_title(f"{name} (R^2 {model.r2:.3f})", fontsize=8)
        axes.set_xlabel(f"predicted [{unit}]", fontsize=7)
        axes.set_ylabel("relative residual", fontsize=7)
        axes.tick_params(labelsize=6)
    figure.tight_layout()
    figure.savefig(str(path), dpi=110)


def _plot_quality(entries: Sequence[Dict[str, object]], path: pathlib.Path) -> None:
    chosen = [e for e in entries if e.get("sweep") == "quality" and "rmse" in e]
    scenes = sorted({e["scene"] for e in chosen})
    if not scenes:
        return
    key = time_key(chosen)
    figure = _figure(4.2 * len(scenes), 4.8)
    for index, scene in enumerate(scenes):
        axes = figure.add_subplot(1, len(scenes), index + 1)
        for name in ("spt-visibility", "spt", "spt-independent", "spt-paper", "pbvr"):
            points = sorted((e for e in chosen if e["scene"] == scene and e["method"] == name),
                            key=lambda e: e[key])
            if points:
                axes.loglog([e[key] for e in points], [e["rmse"] for e in points], "o-",
                            label=METHODS[name].label, markersize=4)
        for e in chosen:
            if e["scene"] == scene and e["method"] in ("havs2", "havs4", "havs6", "pt"):
                axes.loglog([e[key]], [e["rmse"]], "s", markersize=6,
                            label=METHODS[e["method"]].label if e["method"] in METHODS
                            else "HAVS-like k=4")
        axes.set_title(scene)
        axes.set_xlabel("CPU seconds per frame, all threads" if key == "cpu_seconds"
                        else "render time [s]")
        axes.set_ylabel("RMSE against the exact reference")
        axes.grid(True, which="both", alpha=0.3)
    # One legend under the panels: inside them it hid the lowest curves.
    handles, labels = figure.axes[0].get_legend_handles_labels()
    figure.legend(handles, labels, loc="lower center", ncol=4, fontsize=7)
    figure.tight_layout(rect=(0.0, 0.12, 1.0, 1.0))
    figure.savefig(str(path), dpi=110)


def _table(header: Sequence[str], rows: Iterable[Sequence[object]]) -> str:
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(tables.format_value(v) for v in row) + " |" for row in rows]
    return "\n".join(lines) + "\n"


def floor_ratios(entries: Sequence[Dict[str, object]]) -> List[Dict[str, object]]:
    """SPT's time per repetition as a multiple of the floor, at each cell count."""
    cells = [e for e in entries if e.get("sweep") == "cells"]
    rows = []
    for floor in (e for e in cells if e["method"] == "floor"):
        row: Dict[str, object] = {"cells": floor["cells"], "floor_seconds": floor["seconds"]}
        for name in ("spt", "spt-paper", "spt-visibility"):
            for e in cells:
                if e["method"] == name and e["cells"] == floor["cells"]:
                    row[name] = e["seconds"] / e["repetitions"] / floor["seconds"]
                    if np.isfinite(e.get("cpu_seconds", float("nan"))):
                        row[name + " cpu"] = (e["cpu_seconds"] / e["repetitions"] /
                                              floor["cpu_seconds"])
        rows.append(row)
    return rows


def write_report(results: Dict[str, object], output: pathlib.Path) -> str:
    entries = results["entries"]
    time_fits: Dict[str, Fit] = results["time_models"]
    memory_fits: Dict[str, Fit] = results["memory_models"]
    lines = ["# SPT benchmark", "",
             f"Machine: {results['machine']}. Times are medians of {results['frames']} frames "
             "after a warm-up frame, with the GPU finished; every ratio is taken within this "
             "run. Generated meshes: " + results["shape"] + ".", ""]

    cells = [e for e in entries if e.get("sweep") == "cells"]
    if cells:
        lines += ["## Cell count", "", "![cells](cells.png)", ""]
        counts = sorted({e["cells"] for e in cells})
        names = [n for n in METHODS if any(e["method"] == n for e in cells)]
        rows = []
        for count in counts:
            row: List[object] = [count]
            for name in names:
                match = [e for e in cells if e["cells"] == count and e["method"] == name]
                row.append(match[0]["seconds"] if match else "-")
            rows.append(row)
        lines += [f"Seconds per frame (SPT and PBVR at {results['settings']['sweep_repetitions']} "
                  "repetitions, SPT paper at "
                  f"{results['settings']['paper_sweep_repetitions']}):", "",
                  _table(["cells"] + names, rows)]
        ratios = floor_ratios(entries)
        if ratios:
            lines += ["SPT's time per repetition as a multiple of the floor (all faces drawn "
                      "opaque by vtkPolyDataMapper, same image; a method re-run on its own "
                      "with `--methods` is compared with the floor of the earlier run). "
                      "SPT: the survivor estimator; SPT default: the visibility estimator "
                      "with exact coverage:", "",
                      _table(["cells", "floor [s]", "SPT", "SPT paper", "SPT default",
                              "SPT (CPU time)", "SPT paper (CPU time)",
                              "SPT default (CPU time)"],
                             [[r["cells"], r["floor_seconds"], r.get("spt", "-"),
                               r.get("spt-paper", "-"), r.get("spt-visibility", "-"),
                               r.get("spt cpu", "-"), r.get("spt-paper cpu", "-"),
                               r.get("spt-visibility cpu", "-")] for r in ratios])]
    for sweep, title, picture in (("repetitions", "Repetition level", "repetitions.png"),
                                  ("subpixels", "Subpixel level", "subpixels.png"),
                                  ("image", "Image size", "image.png")):
        chosen = [e for e in entries if e.get("sweep") == sweep]
        if not chosen:
            continue
        lines += [f"## {title}", "", f"![{sweep}]({picture})", "",
                  _table(["method", "L_r", "L_s", "size", "cells", "seconds", "CPU seconds",
                          "GPU MiB"],
                         [[e["method"], e["repetitions"], e["subpixels"], e["width"],
                           e["cells"], e["seconds"], e.get("cpu_seconds", "-"),
                           e.get("gpu_memory", 0.0) / 2 ** 20] for e in chosen])]

    cpu_fits: Dict[str, Fit] = results.get("cpu_time_models", {})

    def model_rows(models: Dict[str, Fit], label: str) -> List[List[object]]:
        return [[f"{label}{m.name}",
                 ", ".join(f"{t} = {c:.4g}" for t, c in zip(m.terms, m.coefficients)),
                 m.r2, m.n] for m in models.values()]

    lines += ["## Fitted models", "",
              "Time in milliseconds (wall time of the frame, and the CPU time of all the "
              "process's threads, which on a machine shared with other jobs measures the "
              "work without the waiting), memory in bytes. Weighted least squares (relative "
              "error), each with a fixed term that the paper's forms leave out. Residual "
              "plots: `time_residuals.png`, `cpu_time_residuals.png`, `memory_residuals.png`.",
              ""]
    lines += [_table(["model", "coefficients", "R^2", "points"],
                     model_rows(time_fits, "wall, ") + model_rows(cpu_fits, "CPU, ") +
                     model_rows(memory_fits, "memory, "))]
    if "spt" in memory_fits:
        c = memory_fits["spt"].coefficients[0]
        lines += [f"SPT: {c:.1f} bytes per tetrahedron on the GPU plus the framebuffers "
                  f"(the paper: {PAPER['spt_bytes_per_cell']} bytes per tetrahedron).", ""]
    lines += ["![time residuals](time_residuals.png)", "",
              "![CPU time residuals](cpu_time_residuals.png)", "",
              "![memory residuals](memory_residuals.png)", ""]

    cross = results["crossovers"]
    if cross["memory"]:
        lines += ["## Crossovers", "", "Memory: PBVR needs more GPU memory than SPT above this "
                  "repetition level (particles per repetition from PBVR's own count):", "",
                  _table(["scene", "cells", "particles per repetition", "L_r at equal memory"],
                         [[m["scene"], m["cells"], m["particles_per_repetition"],
                           m["repetitions_at_equal_memory"]] for m in cross["memory"]])]
    if cross["time_at_equal_error"]:
        lines += ["Time at equal error: the repetitions SPT needs to reach HAVS-like's error "
                  "on each data set, and its time there (SPT's error interpolated on its "
                  "log-log curve):", "",
                  _table(["scene", "SPT", "HAVS-like", "its RMSE", "its time [s]", "SPT L_r",
                          "SPT time [s]", "SPT / HAVS"],
                         [[t["scene"], t.get("spt", "spt"), t["havs"], t["havs_rmse"],
                           t["havs_seconds"],
                           (f"≤ {t['spt_repetitions']}" if t.get("at_most")
                            else t["spt_repetitions"]),
                           t["spt_seconds"],
                           (f"≤ {tables.format_value(t['spt_over_havs'])}" if t.get("at_most")
                            else t["spt_over_havs"])]
                          for t in cross["time_at_equal_error"]])]

    if cross.get("sampling"):
        lines += ["Beyond the paper (issue 7): 16 repetitions per pass against the paper's one "
                  "per pass (the same image, so equal error), and the stratified repetitions "
                  "that reach the error of the most independent repetitions measured:", "",
                  _table(["scene", "L_r", "1 per pass / 16 per pass (time)",
                          "RMSE (1 / 16 per pass)", "independent L_r", "its RMSE",
                          "stratified L_r for it", "stratified slope"],
                         [[g["scene"], g.get("per_pass_repetitions", "-"),
                           g.get("per_pass_speedup", "-"),
                           " / ".join(f"{v:.4f}" for v in g["per_pass_rmse"])
                           if "per_pass_rmse" in g else "-",
                           g["independent_repetitions"], g["independent_rmse"],
                           g["stratified_repetitions"], g["stratified_slope"]]
                          for g in cross["sampling"]])]

    quality_entries = [e for e in entries if e.get("sweep") == "quality" and "rmse" in e]
    if quality_entries:
        lines += ["## Time to quality", "", "![quality](quality.png)", "",
                  _table(["scene", "method", "L_r", "seconds", "CPU seconds", "RMSE"],
                         [[e["scene"], e["method"], e["repetitions"], e["seconds"],
                           e.get("cpu_seconds", "-"), e["rmse"]] for e in quality_entries])]
    host = results.get("host", [])
    if host:
        lines += ["## Host time per frame", "",
                  "CPU seconds per SPT frame (16 repetitions), from `perf` samples of the "
                  "timed frames, by thread and shared object. Host: this project's library, "
                  "VTK and Python on the application thread, the part a real GPU leaves on "
                  "the CPU. Kernel and C library: on that thread, mostly the memory that "
                  "llvmpipe's vertex stage maps for every draw. The rest is the emulated GPU "
                  "(llvmpipe's shaders and Mesa's driver on the application thread, the "
                  "rasterizer threads).", "",
                  _table(["cells", "frame [s]", "host [s]", "SPT library [s]",
                          "kernel + libc [s]", "application thread [s]",
                          "llvmpipe workers [s]"],
                         [[h["cells"], h["frame_seconds"], h["host_seconds_per_frame"],
                           h["project_seconds_per_frame"],
                           h.get("system_seconds_per_frame", "-"),
                           h["application_thread_seconds_per_frame"],
                           h["worker_seconds_per_frame"]] for h in host])]
    large = results.get("large")
    if large:
        lines += ["## The paper's large case", "",
                  f"{large['cells']} tetrahedra, {large['width']} x {large['height']}, "
                  f"{large['repetitions']} repetitions: {large['seconds']:.1f} s per frame "
                  f"({large.get('cpu_seconds', float('nan')):.1f} CPU seconds), "
                  f"{large.get('gpu_memory', 0) / 2 ** 20:.0f} MiB on the GPU. The models "
                  "fitted above predict: the paper's form (per pass) "
                  f"{large.get('predicted_seconds', float('nan')):.1f} s "
                  f"({large.get('predicted_cpu_seconds', float('nan')):.1f} CPU seconds); the "
                  "fragment form "
                  f"{large.get('predicted_seconds_fragments', float('nan')):.1f} s "
                  f"({large.get('predicted_cpu_seconds_fragments', float('nan')):.1f} CPU "
                  f"seconds); memory {large.get('predicted_memory', float('nan')) / 2 ** 20:.0f}"
                  " MiB.", ""]
    text = "\n".join(lines)
    (output / "bench.md").write_text(text)
    return text


# --------------------------------------------------------------------------------------------
# The run
# --------------------------------------------------------------------------------------------

def _machine() -> str:
    cores = os.cpu_count()
    renderer = "Mesa llvmpipe" if os.environ.get("GALLIUM_DRIVER", "llvmpipe") else "?"
    return f"{cores} cores, {renderer}"


def predict_large(entry: Dict[str, object], time_fits: Dict[str, Fit],
                  cpu_fits: Dict[str, Fit], memory_fits: Dict[str, Fit]) -> None:
    """The fitted models' prediction for the large case, next to its measurement."""
    pixels = float(entry["width"]) * float(entry["height"]) * float(entry["subpixels"]) ** 2
    passes = math.ceil(entry["repetitions"] / PER_PASS)
    columns = [passes * entry["cells"], passes * pixels, entry["repetitions"] * pixels]
    fragments = [passes * entry["cells"], passes * pixels * entry["cells"] ** (1 / 3),
                 entry["repetitions"] * pixels]
    for models, suffix in ((time_fits, "seconds"), (cpu_fits, "cpu_seconds")):
        if "spt-passes" in models:
            entry[f"predicted_{suffix}"] = models["spt-passes"].predict(columns) / 1000.0
        if "spt-fragments" in models:
            entry[f"predicted_{suffix}_fragments"] = (
                models["spt-fragments"].predict(fragments) / 1000.0)
    if "spt" in memory_fits:
        entry["predicted_memory"] = memory_fits["spt"].predict([entry["cells"], pixels])


def large_case(settings: Settings, progress: Progress) -> Dict[str, object]:
    """The paper's large case: one frame (after a one-repetition warm-up)."""
    s = generated_scene(settings.shape, settings.large_cells)
    timing = time_method(s, METHODS["spt"], settings.large_size, settings.large_repetitions,
                         1, frames=1)
    entry = _record(s, METHODS["spt"], settings.large_size, settings.large_repetitions, 1,
                    timing, sweep="large")
    progress.step(f"large {entry['cells']} cells {timing.median:.1f} s")
    return entry


def run(output: pathlib.Path, sections: Sequence[str] = SECTIONS,
        settings: Optional[Settings] = None) -> Dict[str, object]:
    """Run the chosen sections and write ``bench.json``, the plots and ``bench.md`` into
    ``output``; returns the results. Earlier results in ``output/bench.json`` of sections
    not run now are kept, so a long run can be done section by section."""
    settings = settings or Settings()
    unknown = [s for s in sections if s not in SECTIONS]
    if unknown:
        raise ValueError(f"unknown section(s) {', '.join(unknown)}; choose from "
                         f"{', '.join(SECTIONS)}")
    output.mkdir(parents=True, exist_ok=True)
    previous: Dict[str, object] = {}
    if (output / "bench.json").exists():
        previous = json.loads((output / "bench.json").read_text())
    entries = [e for e in previous.get("entries", [])
               if e.get("sweep") not in sections or not settings.wants(e.get("method", ""))]
    progress = Progress(sum(_steps(settings, s) for s in sections), "bench")
    for section in sections:
        if section == "cells":
            entries += sweep_cells(settings, progress)
        elif section == "repetitions":
            entries += sweep_repetitions(settings, progress)
        elif section == "subpixels":
            entries += sweep_subpixels(settings, progress)
        elif section == "image":
            entries += sweep_image(settings, progress)
        elif section == "quality":
            entries += quality(settings, progress, output)
    time_fits = time_models(entries)
    cpu_fits = time_models(entries, "cpu_seconds")
    memory_fits = memory_models(entries)
    results: Dict[str, object] = {
        "machine": _machine(), "shape": settings.shape, "frames": settings.frames,
        "settings": dataclasses.asdict(settings), "entries": entries,
        "host": previous.get("host", []), "large": previous.get("large")}
    if "host" in sections:
        results["host"] = host_time(settings, progress)
    if "large" in sections:
        results["large"] = large_case(settings, progress)
    if results["large"]:
        predict_large(results["large"], time_fits, cpu_fits, memory_fits)
    results["time_models"] = time_fits
    results["cpu_time_models"] = cpu_fits
    results["memory_models"] = memory_fits
    results["crossovers"] = crossovers(entries, memory_fits)
    results["floor_ratios"] = floor_ratios(entries)

    _plot_sweep(entries, "cells", "cells", "tetrahedra", output / "cells.png")
    _plot_sweep(entries, "repetitions", "repetitions", "RepetitionLevel",
                output / "repetitions.png")
    _plot_sweep(entries, "subpixels", "subpixels", "SubpixelLevel", output / "subpixels.png")
    _plot_sweep(entries, "image", "width", "pixels", output / "image.png")
    _plot_residuals(time_fits, output / "time_residuals.png", "ms")
    _plot_residuals(cpu_fits, output / "cpu_time_residuals.png", "ms")
    _plot_residuals(memory_fits, output / "memory_residuals.png", "bytes")
    _plot_quality(entries, output / "quality.png")

    serializable = dict(results)
    serializable["time_models"] = {k: v.as_dict() for k, v in time_fits.items()}
    serializable["cpu_time_models"] = {k: v.as_dict() for k, v in cpu_fits.items()}
    serializable["memory_models"] = {k: v.as_dict() for k, v in memory_fits.items()}
    (output / "bench.json").write_text(json.dumps(serializable, indent=1))
    write_report(results, output)
    return results
