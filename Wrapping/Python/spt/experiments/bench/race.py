"""The race: every method's error against the exact reference and its frame time, side by
side in one process, and each stochastic method's time to reach a given error.

For each scene, at 256 x 256 from azimuth 35 and elevation 25 by default: VTK's projected
tetrahedra, HAVS-like with k = 2 to 6, PBVR, SPT at its defaults, SPT with 8 depth slabs and
SPT with the paper's sampling, the stochastic ones at L = 1, 2, 4, ... up to a cap, each time
the best of two frames. A stochastic method's time to reach an error is the time of the
smallest L measured whose RMSE (premultiplied RGBA against the reference) is at most that
error, as a multiple of VTK PT's frame; "not reached" if none is. Each method's host CPU time
per frame (the application thread outside the OpenGL driver) comes with it: the part a GPU
would not take over. SPT also runs with VTK PT's error as its error target: a new mapper,
whose first image estimates its noise from 16 repetitions per half, a mapper that has drawn the
scene from another view (azimuth 10 degrees further), whose first step aims with the noise per
repetition measured there, and a new mapper with 8 depth slabs.
Every image is read back through 8 bits per channel, so each row also records the least error
an 8-bit image can have against the reference (``read_back_floor``): a method whose error is
near it is exact to the read-back.
"""

from __future__ import annotations

import dataclasses
import hashlib
import pathlib
from typing import Dict, List, Optional, Sequence, Tuple

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy

from ... import meshes, metrics, render, scenes
from ...progress import Progress
from . import host
from .methods import METHODS, Method, havs_method, time_method
from .settings import RACE_SCENES, Settings

Entry = Dict[str, object]

#: The race's camera (the zoom is the scene's own).
AZIMUTH, ELEVATION = 35.0, 25.0
#: Frames per measurement; the best is kept.
FRAMES = 2
#: The errors every stochastic method races to, besides VTK PT's and HAVS-like k=6's.
TARGETS = (0.005, 0.002)
#: The generated drill at the race's sizes.
DRILLS = {"drill-0.2M": 200_000, "drill-1M": 1_000_000, "drill-3M": 3_000_000}

#: The depth slabs of the race's "SPT, depth slabs" (vtkSPTVolumeMapper::SetDepthSlabs()).
RACE_DEPTH_SLABS = 8

EXACT_METHODS: Tuple[Method, ...] = (METHODS["pt"],) + tuple(havs_method(k) for k in range(2, 7))
STOCHASTIC_METHODS: Tuple[Method, ...] = (
    Method("spt", "SPT", lambda r, s: render.spt_mapper(r, s), True),
    Method("spt-paper-sampling", "SPT, paper's sampling",
           lambda r, s: render.spt_mapper(r, s, **render.PAPER_SAMPLING), True),
    Method("spt-slabs", f"SPT, {RACE_DEPTH_SLABS} depth slabs",
           lambda r, s: render.spt_mapper(r, s, depth_slabs=RACE_DEPTH_SLABS), True),
    METHODS["pbvr"],
)


def scene_names() -> List[str]:
    """The scenes the race can run."""
    return list(scenes.SCENES) + list(DRILLS)


def race_scene(name: str) -> scenes.Scene:
    """The named scene with the race's camera."""
    if name in DRILLS:
        made = scenes.generated_scene(name, "drill", DRILLS[name], render.View())()
        zoom = scenes.VIEWS["drill"].zoom
    else:
        made = scenes.scene(name)
        zoom = made.view.zoom
    made.view = render.View(azimuth=AZIMUTH, elevation=ELEVATION, zoom=zoom)
    return made


def levels(cap: int, factor: int = 2) -> List[int]:
    """1, ``factor``, ``factor``^2, ... up to ``cap``."""
    result = [1]
    while result[-1] * factor <= cap:
        result.append(result[-1] * factor)
    return result


# --------------------------------------------------------------------------------------------
# Bookkeeping
# --------------------------------------------------------------------------------------------

def time_to_error(points: Sequence[Tuple[int, float, float]], target: float
                  ) -> Optional[Tuple[int, float]]:
    """From (L, error, seconds) rows, the smallest L whose error is at most ``target`` and its
    seconds; None if no row reaches it."""
    for level, error, seconds in sorted(points):
        if error <= target:
            return level, seconds
    return None


def race_targets(rows: Sequence[Entry]) -> Dict[str, float]:
    """The errors the stochastic methods race to, by label."""
    errors = {row["method"]: row["rmse"] for row in rows}
    targets = {label: errors[method] for method, label in (
        ("pt", "VTK PT's error"), ("havs6", "HAVS-like k=6's error")) if method in errors}
    targets.update((f"RMSE {target:g}", target) for target in TARGETS)
    return targets


def summarize(rows: Sequence[Entry]) -> List[Entry]:
    """Per scene and stochastic method: its time to reach each target as a multiple of VTK
    PT's frame (None where not reached), with the L it took, and its host CPU time per frame
    at the L that reaches VTK PT's error (or at its largest L)."""
    summary = []
    for scene in dict.fromkeys(row["scene"] for row in rows):
        chosen = [row for row in rows if row["scene"] == scene]
        pt = next((row for row in chosen if row["method"] == "pt"), None)
        if pt is None:
            continue
        targets = race_targets(chosen)
        for method in dict.fromkeys(row["method"] for row in chosen if row["stochastic"]):
            points = [(row["repetitions"], row["rmse"], row["seconds"])
                      for row in chosen if row["method"] == method]
            entry: Entry = {"scene": scene, "method": method, "reached": {}}
            for label, target in targets.items():
                found = time_to_error(points, target)
                entry["reached"][label] = (None if found is None else
                                           {"repetitions": found[0],
                                            "ratio": found[1] / pt["seconds"]})
            first = entry["reached"].get("VTK PT's error")
            level = first["repetitions"] if first else max(p[0] for p in points)
            at = next(row for row in chosen if row["method"] == method
                      and row["repetitions"] == level)
            entry.update(host_seconds=at["host_seconds"], host_repetitions=level,
                         label=at["label"])
            summary.append(entry)
    return summary


# --------------------------------------------------------------------------------------------
# Reference cache
# --------------------------------------------------------------------------------------------

def scene_digest(s: scenes.Scene) -> str:
    """A digest of a scene's mesh, scalars and transfer functions."""
    digest = hashlib.sha1()
    grid = s.grid
    digest.update(vtk_to_numpy(grid.GetPoints().GetData()).tobytes())
    digest.update(vtk_to_numpy(grid.GetCells().GetConnectivityArray()).tobytes())
    scalars = grid.GetPointData().GetScalars() or grid.GetCellData().GetScalars()
    if scalars is not None:
        digest.update(vtk_to_numpy(scalars).tobytes())
    # the transfer functions' nodes: opacity (x, y, midpoint, sharpness), color (x, r, g, b, ...)
    values = [s.property.GetScalarOpacityUnitDistance()]
    for function, width in ((s.property.GetScalarOpacity(), 4),
                            (s.property.GetRGBTransferFunction(), 6)):
        for index in range(function.GetSize()):
            node = [0.0] * width
            function.GetNodeValue(index, node)
            values += node
    digest.update(np.asarray(values).tobytes())
    return digest.hexdigest()[:16]


def cached_reference(s: scenes.Scene, size: int, directory: pathlib.Path) -> np.ndarray:
    """The exact reference of ``s`` at ``size`` x ``size``, read from ``directory`` if an
    earlier run rendered it (keyed by scene, view, size and the scene's digest), else
    rendered and written there."""
    view = s.view
    key = (f"{s.name}-{size}-az{view.azimuth:g}-el{view.elevation:g}-zoom{view.zoom:g}"
           f"{'-parallel' if view.parallel else ''}-{scene_digest(s)}")
    path = directory / f"{key}.npy"
    if path.exists():
        return np.load(path)
    image = render.reference(s.grid, s.property, view, (size, size)).image
    meshes.save_atomically(path, lambda stream: np.save(stream, image))
    return image


# --------------------------------------------------------------------------------------------
# Measurement
# --------------------------------------------------------------------------------------------

@dataclasses.dataclass
class Lap:
    """What one scene's race needs: the scene, its reference and how to measure."""

    scene: scenes.Scene
    reference: np.ndarray
    read_back_floor: float  # the least error an 8-bit image can have against the reference
    size: int
    use_perf: bool
    output: pathlib.Path


def measure(lap: Lap, method: Method, level: int, **extra) -> Entry:
    """One method at one repetition level: error, best frame time and host time."""
    def run(hook):
        return time_method(lap.scene, method, lap.size, level, 1, FRAMES, keep_image=True,
                           on_frames=hook)

    timing, host_seconds, source, objects = host.timed_with_host(run, FRAMES, lap.use_perf)
    best = int(np.argmin(timing.seconds))
    metrics.write_png(lap.output / f"{lap.scene.name}_{method.name}_{level}.png", timing.image)
    entry: Entry = {
        "scene": lap.scene.name, "cells": lap.scene.grid.GetNumberOfCells(),
        "method": method.name, "label": method.label, "stochastic": method.stochastic,
        "repetitions": level if method.stochastic else 1,
        "rmse": metrics.rmse(timing.image, lap.reference),
        "read_back_floor": lap.read_back_floor, "seconds": timing.seconds[best],
        "cpu_seconds": timing.cpu_seconds[best], "host_seconds": host_seconds,
        "host_source": source, "host_objects": objects}
    entry.update(timing.report)
    entry.update(extra)
    return entry


def _run_stochastic(lap: Lap, method: Method, cap: int, goal: float,
                    progress: Progress) -> List[Entry]:
    """``method`` at L = 1, 2, 4, ... up to ``cap``, stopping once its error is at most
    ``goal`` (every target reached: larger L add nothing to the race)."""
    rows = []
    steps = levels(cap)
    for index, level in enumerate(steps):
        row = measure(lap, method, level)
        rows.append(row)
        progress.step(f"{lap.scene.name} {method.name} L={level} RMSE {row['rmse']:.4f}")
        if row["rmse"] <= goal:
            for skipped in steps[index + 1:]:
                progress.step(f"{lap.scene.name} {method.name} L={skipped}: every target "
                              "reached")
            break
    return rows


def race_scene_rows(name: str, settings: Settings, progress: Progress, output: pathlib.Path,
                    use_perf: bool, references: Optional[pathlib.Path] = None) -> List[Entry]:
    """Every method of the race on one scene; its images go to ``output``, the cached
    reference to ``references`` (default: ``output/references``)."""
    s = race_scene(name)
    reference = cached_reference(s, settings.race_size, references or output / "references")
    metrics.write_png(output / f"{s.name}_reference.png", reference)
    progress.step(f"{name} reference")
    lap = Lap(s, reference, metrics.read_back_floor(reference), settings.race_size, use_perf,
              output)
    rows = []
    for method in EXACT_METHODS:
        rows.append(measure(lap, method, 1))
        progress.step(f"{name} {method.label} RMSE {rows[-1]['rmse']:.4f}")
    goal = min(race_targets(rows).values())
    for method in STOCHASTIC_METHODS:
        rows += _run_stochastic(lap, method, settings.race_max_repetitions, goal, progress)
    pt_error = rows[0]["rmse"]
    size = (settings.race_size, settings.race_size)
    # SPT with VTK PT's error as its target: a new mapper; one that has drawn an image from
    # another view, whose first step aims with the noise per repetition measured there (as
    # while a user turns the camera); and a new mapper with depth slabs.
    for method in (
            Method("spt-target", "SPT at VTK PT's error (error target)",
                   lambda r, sp: render.spt_mapper(r, sp, target_error=pt_error), True),
            Method("spt-target-turned",
                   "SPT at VTK PT's error, after another view (error target)",
                   lambda r, sp: render.after_another_view(
                       render.spt_mapper(r, sp, target_error=pt_error), s.grid,
                       s.property, s.view, size), True),
            Method("spt-slabs-target",
                   f"SPT at VTK PT's error, {RACE_DEPTH_SLABS} depth slabs (error target)",
                   lambda r, sp: render.spt_mapper(r, sp, target_error=pt_error,
                                                   depth_slabs=RACE_DEPTH_SLABS), True)):
        row = measure(lap, method, settings.race_max_repetitions, target_error=pt_error)
        # the repetitions it drew before its noise estimate reached the target
        row["repetitions"] = int(row.get("repetitions_drawn", row["repetitions"]))
        rows.append(row)
        progress.step(f"{name} {method.label}")
    return rows


def steps(settings: Settings) -> int:
    """The progress steps of the race."""
    per_scene = (1 + len(EXACT_METHODS) + len(STOCHASTIC_METHODS)
                 * len(levels(settings.race_max_repetitions)) + 3)
    return len(settings.race_scenes) * per_scene * len(settings.race_image_sizes())


#: What makes two runs' rows comparable: the same image, camera, frames and host-time source.
SAME_RACE = ("size", "azimuth", "elevation", "frames", "max_repetitions", "host_source")


def merge_runs(measured: Dict[str, object], previous: Optional[Dict[str, object]]
               ) -> Dict[str, object]:
    """``measured`` with the scenes of an earlier race that it did not run, so that a long
    race can be run scene by scene (``--scenes``). Each scene keeps the rows of the one run
    that raced it, in one process; an earlier race measured otherwise (another size, camera,
    number of frames, repetition cap or host-time source) is dropped. The scenes are listed in
    the race's order, and ``runs`` says which scenes were raced together."""
    names = list(RACE_SCENES) + [name for name in scene_names() if name not in RACE_SCENES]
    order = {name: index for index, name in enumerate(names)}

    def position(name: str) -> int:
        return order.get(name, len(order))

    run = {"scenes": sorted(dict.fromkeys(row["scene"] for row in measured["rows"]),
                            key=position)}
    runs = [run] if run["scenes"] else []
    rows = list(measured["rows"])
    if previous and all(previous.get(key) == measured[key] for key in SAME_RACE):
        rows += [row for row in previous.get("rows", []) if row["scene"] not in run["scenes"]]
        earlier = previous.get("runs") or [
            {"scenes": list(dict.fromkeys(row["scene"] for row in previous.get("rows", [])))}]
        for other in earlier:
            scenes_left = [name for name in other["scenes"] if name not in run["scenes"]]
            if scenes_left:
                runs.append({"scenes": scenes_left})
    rows.sort(key=lambda row: position(row["scene"]))  # stable: a scene's rows keep their order
    runs.sort(key=lambda r: min(position(name) for name in r["scenes"]))
    return dict(measured, rows=rows, summary=summarize(rows), runs=runs)


def race(settings: Settings, progress: Progress, output: pathlib.Path,
         previous: Optional[Dict[str, object]] = None,
         references: Optional[pathlib.Path] = None) -> Dict[str, object]:
    """The race on every scene of ``settings.race_scenes`` at ``settings.race_size``; images
    go to ``output``, the cached references to ``references`` (default:
    ``output/references``). Returns the rows, the summary and how host time was measured,
    with the scenes of ``previous`` (an earlier race) that this one did not run
    (merge_runs())."""
    output.mkdir(parents=True, exist_ok=True)
    use_perf = host.perf_available()
    rows: List[Entry] = []
    for name in settings.race_scenes:
        rows += race_scene_rows(name, settings, progress, output, use_perf, references)
    measured = {"size": settings.race_size, "azimuth": AZIMUTH, "elevation": ELEVATION,
                "frames": FRAMES, "max_repetitions": settings.race_max_repetitions,
                "host_source": "perf" if use_perf else "thread_time",
                "rows": rows, "summary": summarize(rows)}
    return merge_runs(measured, previous)


def races(settings: Settings, progress: Progress, output: pathlib.Path,
          previous: Sequence[Dict[str, object]] = ()) -> List[Dict[str, object]]:
    """The race at each of ``settings.race_image_sizes()``, size after size, each merged with
    the earlier race of its size in ``previous`` (merge_runs()); the earlier races at other
    sizes are kept. Returns every race, smallest size first. The images of the smallest size
    measured go to ``output``, the others' to ``output/<size>x<size>``; the references are
    cached in ``output/references`` (keyed by size)."""
    sizes = settings.race_image_sizes()
    by_size = {int(r["size"]): r for r in previous if r}
    for size in sizes:
        folder = output if size == sizes[0] else output / f"{size}x{size}"
        at_size = dataclasses.replace(settings, race_size=size, race_sizes=None)
        by_size[size] = race(at_size, progress, folder, by_size.get(size), output / "references")
    return [by_size[size] for size in sorted(by_size)]
