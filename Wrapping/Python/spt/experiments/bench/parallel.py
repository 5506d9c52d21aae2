"""The ``parallel`` section: SPT on 1, 2 and 4 MPI ranks with no redistribution, each rank
with an interleaved piece of the scene (cells by id modulo the number of ranks: every piece
spans the whole mesh, so a sorted method could not composite the ranks' images without moving
cells first), run by :mod:`.parallel_rank`; then pvbatch with the plugin (:mod:`.pvbatch_frames`)
against the representations ParaView redistributes. The ranks share this machine's cores: on
fewer cores than ranks, the times show the cost of the reductions and of oversubscription, not
a speed-up.
"""

from __future__ import annotations

import json
import os
import pathlib
import shutil
import subprocess
import sys
from statistics import median
from typing import Dict, List

import numpy as np

from ...meshes import interleaved_piece, write_legacy
from ...progress import Progress
from .race import race_scene
from .settings import Settings

Row = Dict[str, object]
TIMEOUT = 3600  # seconds per run


def mpiexec(ranks: int) -> List[str]:
    """mpiexec arguments for ``ranks`` local ranks (root needs consent), passing the
    environment the package needs."""
    path = shutil.which("mpiexec")
    if not path:
        raise RuntimeError("the parallel section needs mpiexec (OpenMPI)")
    command = [path, "-n", str(ranks), "--oversubscribe"]
    if os.geteuid() == 0:
        command.append("--allow-run-as-root")
    for variable in ("PYTHONPATH", "DISPLAY", "SPT_DATA_DIR", "SPT_CACHE_DIR"):
        if variable in os.environ:
            command += ["-x", variable]
    return command


def _run(command: List[str], output: pathlib.Path, settings: Settings) -> None:
    """``command`` with the section's settings of a frame and ``output``, as both the ranks'
    scripts take them."""
    command = command + [
        "--output", str(output), "--size", str(settings.parallel_size),
        "--repetitions", str(settings.parallel_repetitions),
        "--target-error", str(settings.parallel_target_error), "--frames", str(settings.frames)]
    result = subprocess.run(command, capture_output=True, text=True, timeout=TIMEOUT,
                            check=False)
    if result.returncode != 0:
        raise RuntimeError(f"{' '.join(command)} failed:\n{result.stderr[-4000:]}")


def run_ranks(scene: str, ranks: int, settings: Settings, directory: pathlib.Path) -> Row:
    """One run of ``ranks`` ranks: its report and rank 0's image."""
    output = directory / f"{scene}-{ranks}"
    _run(mpiexec(ranks) + [sys.executable, "-m", "spt.experiments.bench.parallel_rank",
                           "--scene", scene], output, settings)
    report = json.loads(output.with_suffix(".json").read_text())
    report["image"] = np.load(output.with_suffix(".npy"))
    return report


def summarize(report: Row, one_rank_image: np.ndarray) -> Row:
    """The row of one run: the slowest rank's times, every rank's memory and bytes."""
    ranks = report["per_rank"]

    def slowest(key: str, later: bool) -> float:
        return max(median(f[key] for f in r["frames"][1:]) if later else r["frames"][0][key]
                   for r in ranks)

    difference = np.abs(np.rint(report["image"] * 255.0) - np.rint(one_rank_image * 255.0))
    root = ranks[0]["frames"]
    return {"scene": report["scene"], "ranks": report["ranks"],
            "target_error": report.get("target_error", 0.0),
            "first_repetitions": root[0].get("repetitions"),
            "later_repetitions": [f.get("repetitions") for f in root[1:]],
            "first_estimated_error": root[0].get("estimated_error"),
            "cells": report["whole_cells"],
            "first_cpu_seconds": slowest("cpu_seconds", False),
            "later_cpu_seconds": slowest("cpu_seconds", True),
            "first_wall_seconds": slowest("wall_seconds", False),
            "later_wall_seconds": slowest("wall_seconds", True),
            "bytes_per_frame_per_rank": max(r["bytes_per_frame"] for r in ranks),
            "peak_rss_bytes": [r["peak_rss_bytes"] for r in ranks],
            "piece_bytes": [r["piece_bytes"] for r in ranks],
            "gpu_bytes": [r["gpu_bytes"] for r in ranks],
            "max_levels_from_one_rank": float(difference.max()),
            "alpha_mean": float(report["image"][..., 3].mean())}


def write_pieces(scene: str, ranks: int, directory: pathlib.Path) -> pathlib.Path:
    """The scene's mesh as ``ranks`` interleaved legacy pieces and their .pvtk index."""
    grid = race_scene(scene).grid
    entries = []
    for rank in range(ranks):
        path = directory / f"{scene}-{ranks}.{rank}.vtk"
        write_legacy(interleaved_piece(grid, rank, ranks), path)
        entries.append(f'  <Piece fileName="{path.name}" />')
    index = directory / f"{scene}-{ranks}.pvtk"
    index.write_text('<File version="pvtk-1.0" dataType="vtkUnstructuredGrid" '
                     f'numberOfPieces="{ranks}" >\n' + "\n".join(entries) + "\n</File>\n")
    return index


def paraview_row(scene: str, ranks: int, representation: str, settings: Settings,
                 directory: pathlib.Path) -> Row:
    """One pvbatch run of ``representation`` on ``ranks`` ranks with interleaved pieces."""
    index = write_pieces(scene, ranks, directory)
    output = directory / f"{scene}-{ranks}-{representation.replace(' ', '_')}.json"
    command = mpiexec(ranks) + ["-x", "PV_PLUGIN_PATH"]
    preload = os.environ.get("SPT_EXPAT_COMPAT_LIBRARY")
    if preload:  # ParaView's redistribution loses data with Debian 12's expat without it
        command += ["-x", f"LD_PRELOAD={preload}"]
    command += [shutil.which("pvbatch") or "pvbatch", "--symmetric",
                str(pathlib.Path(__file__).with_name("pvbatch_frames.py")),
                "--data", str(index), "--representation", representation]
    _run(command, output, settings)
    return dict({"scene": scene, "ranks": ranks, "representation": representation},
                **json.loads(output.read_text()))


def paraview_rows(settings: Settings, progress: Progress, output: pathlib.Path) -> List[Row]:
    """pvbatch with the plugin (PV_PLUGIN_PATH), each representation at each rank count."""
    rows: List[Row] = []
    if not os.environ.get("PV_PLUGIN_PATH") or not shutil.which("pvbatch"):
        return rows
    for scene in settings.parallel_scenes:
        for ranks in settings.parallel_paraview_ranks:
            for representation in settings.parallel_paraview_representations:
                rows.append(paraview_row(scene, ranks, representation, settings, output))
                progress.step(f"pvbatch {scene} {ranks} ranks {representation} "
                              f"{rows[-1]['first_wall_seconds']:.2f} s")
    return rows


def steps(settings: Settings) -> int:
    paraview = len(settings.parallel_paraview_ranks) * len(
        settings.parallel_paraview_representations)
    return len(settings.parallel_scenes) * (len(settings.parallel_ranks) + paraview)


def parallel(settings: Settings, progress: Progress, output: pathlib.Path) -> Dict[str, object]:
    """Every scene at every rank count (the first count's image is the reference), then
    pvbatch's first and later frames of SPT without redistribution and of the methods that
    redistribute."""
    output.mkdir(parents=True, exist_ok=True)
    rows: List[Row] = []
    for scene in settings.parallel_scenes:
        reference = None
        for ranks in settings.parallel_ranks:
            report = run_ranks(scene, ranks, settings, output)
            if reference is None:
                reference = report["image"]
            rows.append(summarize(report, reference))
            progress.step(f"parallel {scene} {ranks} ranks "
                          f"{rows[-1]['later_wall_seconds']:.2f} s")
    return {"vtk": rows, "paraview": paraview_rows(settings, progress, output)}
