"""``python3 -m spt demo``: what only a sorting-free renderer does, measured against the exact
reference.

Two scenes at 256 x 256 by default:

* **interpenetrating**: the generated drill and a ring through it, two volumes with their own
  data and transfer functions (:func:`spt.volumes.interpenetrating`, 200,000 tetrahedra in
  all). VTK draws the volumes of a renderer one after the other, so VTK's projected tetrahedra
  and the HAVS-like k-buffer composite them in the wrong order where they interpenetrate; the
  SPT volumes of a renderer share one set of buffers and composite exactly.
* **a large mesh** (``--dataset``): the iron protein in full (1.5M tetrahedra) where the data
  sets are, else the race's generated drill at 10^6 tetrahedra, where VTK PT sorts and
  projects every cell on the CPU each frame.

A build without the meshing module (the pip wheel; ``spt.HAVE_MESHING``) races the large scene
alone, by default the embedded helix mesh where the data sets are not.

On each: VTK PT and HAVS-like k=6, each the best of two frames after an untimed one, and SPT
at L = 1, 4, 16, ... until its error is at most VTK PT's and the demo's target error, the best
of two frames each. SPT's time to an error is the frame of the smallest L at or below it, as
in the benchmark's race (:func:`spt.experiments.bench.race.time_to_error`), whose ladder of
L = 1, 2, 4, ... reaches an error at the same L or sooner. The exact references are cached next to
the generated meshes (:func:`spt.meshes.cache_dir`).
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import pathlib
from typing import Dict, List, Optional, Sequence

import numpy as np

from .. import HAVE_MESHING, data, meshes, metrics, render, scenes, volumes
from ..progress import Progress
from . import tables
from .bench import race, runner

PathLike = pathlib.Path
Entry = Dict[str, object]

#: The interpenetrating pair's cells, and the large scenes of :func:`default_large_scene`.
PAIR_CELLS = 200_000
LARGE_SCENE = "drill-1M"
LARGE_DATA_SCENE, LARGE_DATA_FILE = "ironprot_full", "ironProt.vtk"
#: The best of this many frames, after an untimed one (the race's).
FRAMES = race.FRAMES
#: SPT's levels grow by this factor (the race's by 2): a coarser ladder, whose time to an
#: error is the same or later, for half the frames.
LADDER_FACTOR = 4
#: The race table's columns.
RACE_HEADER = ["scene", "tetrahedra", "VTK PT: RMSE, frame", "HAVS-like k=6: RMSE, frame",
               "SPT to VTK PT's error", "SPT to RMSE {target:g}"]
#: Where SPT loses, from the benchmark's race on 2 cores with llvmpipe (Documentation/results.md).
WHERE_SPT_LOSES = (
    "SPT loses where a VTK PT frame is cheap, on small meshes on a software rasterizer: "
    "SPT's two traversals rasterized by llvmpipe cost more than sorting a few thousand cells "
    "(in the benchmark's race on 2 cores, SPX, the torus, Blunt Fin and the drill at 0.2M "
    "reach VTK PT's error in 1.3 to 5.0 VTK PT frames, and the drill at 1M, where VTK PT is "
    "near exact, in 1.04).")


def default_large_scene() -> str:
    """The iron protein in full where its file is in the data sets, else the drill at 1M, or,
    in a build without the meshing module (the pip wheel), the embedded helix mesh."""
    try:
        if (data.data_dir() / LARGE_DATA_FILE).is_file():
            return LARGE_DATA_SCENE
    except FileNotFoundError:
        pass
    return LARGE_SCENE if HAVE_MESHING else "default"


def _digest(s: volumes.VolumesScene, size: int) -> str:
    parts = [race.scene_digest(scenes.Scene(s.name, grid, prop, s.view))
             for grid, prop in s.volumes]
    view = s.view
    text = f"{s.name}-{size}-{view.azimuth}-{view.elevation}-{view.zoom}-{view.parallel}"
    return hashlib.sha1("-".join([text] + parts).encode()).hexdigest()[:16]


def cached_reference(s: volumes.VolumesScene, size: int) -> render.Rendering:
    """The exact reference of ``s`` at ``size`` x ``size``, read from ``references`` in the
    mesh cache if a run rendered it before, else rendered and kept there (keyed by the scene's
    meshes, scalars, transfer functions, view and size)."""
    path = meshes.cache_dir() / "references" / f"{s.name}-{size}-{_digest(s, size)}.npy"
    if path.exists():
        return render.Rendering(image=np.load(path), seconds=0.0, mapper=None)
    rendering = volumes.reference(s, (size, size))
    try:
        meshes.save_atomically(path, lambda stream: np.save(stream, rendering.image))
    except OSError:
        pass  # the cache only spares the next run the ray casting
    return rendering


def levels(cap: int) -> List[int]:
    """1, 4, 16, ... up to ``cap``, and ``cap`` itself."""
    result = race.levels(cap, LADDER_FACTOR)
    return result + ([cap] if result[-1] < cap else [])


def _entry(method: str, label: str, rendering: render.Rendering, reference: np.ndarray,
           repetitions: int) -> Entry:
    return {"method": method, "label": label, "repetitions": repetitions,
            "rmse": metrics.rmse(rendering.image, reference), "seconds": rendering.seconds}


def race_scene(s: volumes.VolumesScene, size: int, cap: int, target: float,
               progress: Progress, output: PathLike) -> Entry:
    """VTK PT, HAVS-like k=6 and SPT's ladder on ``s`` against its exact reference; writes
    each method's image (SPT's at its last level) to ``output``."""
    shape = (size, size)
    reference = cached_reference(s, size)
    progress.step(f"{s.name}: exact reference")
    images = {"reference": reference.image}
    rows = []
    for method, label, make in (("vtk_pt", "VTK PT", render.projected_tetrahedra_mapper),
                                ("havs6", "HAVS-like k=6", lambda: render.havs_mapper(6))):
        rendering = volumes.draw(s, make, shape, FRAMES)
        rows.append(_entry(method, label, rendering, reference.image, 1))
        images[method] = rendering.image
        progress.step(f"{s.name}: {label} RMSE {rows[-1]['rmse']:.4f}")
    goal = min(rows[0]["rmse"], target)
    ladder_levels = levels(cap)
    with contextlib.closing(volumes.draw_levels(s, ladder_levels, shape, FRAMES)) as ladder:
        for level, rendering in zip(ladder_levels, ladder):
            rows.append(_entry("spt", f"SPT L={level}", rendering, reference.image, level))
            images["spt"] = rendering.image
            progress.step(f"{s.name}: SPT L={level} RMSE {rows[-1]['rmse']:.4f}")
            if rows[-1]["rmse"] <= goal:
                break
    for name, image in images.items():
        metrics.write_png(output / f"{s.name}_{name}.png", image)
    return {"scene": s.name, "cells": s.cells(), "volumes": len(s.volumes), "size": size,
            "reference_seconds": reference.seconds, "target": target, "rows": rows,
            "summary": summarize(rows, target), "images": images}


def summarize(rows: Sequence[Entry], target: float) -> Entry:
    """VTK PT's error and frame, HAVS-like's as a multiple of it, and SPT's time to VTK PT's
    error and to ``target`` ({repetitions, seconds, ratio}, None where not reached)."""
    pt = next(row for row in rows if row["method"] == "vtk_pt")
    havs = next(row for row in rows if row["method"] == "havs6")
    points = [(row["repetitions"], row["rmse"], row["seconds"])
              for row in rows if row["method"] == "spt"]

    def reached(error: float) -> Optional[Entry]:
        found = race.time_to_error(points, error)
        return None if found is None else {"repetitions": found[0], "seconds": found[1],
                                           "ratio": found[1] / pt["seconds"]}

    return {"vtk_pt_rmse": pt["rmse"], "vtk_pt_seconds": pt["seconds"],
            "havs6_rmse": havs["rmse"], "havs6_ratio": havs["seconds"] / pt["seconds"],
            "spt_to_vtk_pt_error": reached(pt["rmse"]), "spt_to_target": reached(target)}


def _reached_text(found: Optional[Entry]) -> str:
    if found is None:
        return "not reached"
    return f"{found['ratio']:.2f}x (L={found['repetitions']})"


def race_rows(results: Sequence[Entry]) -> List[List[object]]:
    """The race table's rows, one per scene."""
    rows = []
    for result in results:
        summary = result["summary"]
        rows.append([result["scene"], f"{result['cells']:,}",
                     f"{summary['vtk_pt_rmse']:.4f}, {summary['vtk_pt_seconds']:.2f} s",
                     f"{summary['havs6_rmse']:.4f}, {summary['havs6_ratio']:.2f}x",
                     _reached_text(summary["spt_to_vtk_pt_error"]),
                     _reached_text(summary["spt_to_target"])])
    return rows


def comparison(results: Sequence[Entry]) -> np.ndarray:
    """One row per scene: the reference, VTK PT, HAVS-like k=6 and SPT, then each method's
    difference from the reference (x4)."""
    strips = []
    for result in results:
        images, reference = result["images"], result["images"]["reference"]
        spt = next(row for row in reversed(result["rows"]) if row["method"] == "spt")
        methods = (("vtk_pt", "VTK PT"), ("havs6", "HAVS-like k=6"),
                   ("spt", f"SPT, L={spt['repetitions']}"))
        pictures = [reference] + [images[m] for m, _ in methods] + [
            metrics.difference_image(images[m], reference) for m, _ in methods]
        labels = [f"{result['scene']}: exact"] + [label for _, label in methods] + [
            f"|{label.split(',')[0]} - exact| x4" for _, label in methods]
        strips.append(metrics.side_by_side(pictures, labels))
    width = max(strip.shape[1] for strip in strips)
    padded = [np.pad(strip, ((0, 0), (0, width - strip.shape[1]), (0, 0)),
                     constant_values=int(0.12 * 255)) for strip in strips]
    return np.concatenate(padded, axis=0)


def demo(output: PathLike, size: int = 256, repetitions: int = 256,
         large: Optional[str] = None, pair_cells: int = PAIR_CELLS,
         target_error: float = render.DEFAULT_TARGET_ERROR) -> List[Entry]:
    """The main job: the race on the interpenetrating pair (``pair_cells`` tetrahedra) and on
    ``large`` (default: :func:`default_large_scene`), each method against the exact
    reference. Writes every image, ``comparison.png``, ``race.md`` and ``results.json`` (with
    the machine and its load average) to ``output``; returns the results (per scene: rows of
    method, repetitions, RMSE and seconds, and the race's summary)."""
    output.mkdir(parents=True, exist_ok=True)
    load_at_start = os.getloadavg()[0]
    # The interpenetrating drill and ring are TetGen meshes: a build without the meshing module
    # (the pip wheel) races the large scene alone.
    count = 2 if HAVE_MESHING else 1
    progress = Progress(count + count * (3 + len(levels(repetitions))), "demo")
    large = large or default_large_scene()
    # The race's scene as one volume, first: a missing data set fails before anything is drawn.
    s = race.race_scene(large)
    big = volumes.single(s.grid, s.property, s.name, s.view)
    progress.step(f"{large}: {big.cells():,} tetrahedra")
    chosen = [big]
    if HAVE_MESHING:
        pair = volumes.interpenetrating(pair_cells)
        progress.step(f"interpenetrating: {pair.cells():,} tetrahedra")
        chosen.insert(0, pair)
    results = [race_scene(s, size, repetitions, target_error, progress, output)
               for s in chosen]
    metrics.write_png(output / "comparison.png", comparison(results))
    header = [column.format(target=target_error) for column in RACE_HEADER]
    tables.write_table(output / "race.md", header, race_rows(results))
    # Other processes on the machine slow the frames down, and not all methods alike.
    document = {"machine": runner.machine(),
                "load_average": {"start": load_at_start, "end": os.getloadavg()[0]},
                "size": size, "frames": FRAMES, "max_repetitions": repetitions,
                "target_error": target_error, "where_spt_loses": WHERE_SPT_LOSES,
                "scenes": [{key: value for key, value in result.items() if key != "images"}
                           for result in results]}
    (output / "results.json").write_text(json.dumps(document, indent=1), encoding="utf-8")
    return results
