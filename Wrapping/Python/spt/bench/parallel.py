"""The ``parallel`` section: SPT on 1, 2 and 4 MPI ranks with no redistribution.

Each rank renders an interleaved piece of the scene (cells by id modulo the number of ranks:
every piece spans the whole mesh, so a sorted method could not composite the ranks' images
without moving cells first) through vtkSPTVolumeMapper with a vtkMPIController; the ranks
combine their depth keys by a global minimum and their sums by a global sum (see
:mod:`.parallel_rank`). Per scene and rank count: the first frame and the later frames in
process CPU time (all threads, the rasterizer's too) and wall time, the largest over the
ranks; the bytes each rank puts into the reductions per frame; memory per rank (the peak
resident size, which includes making the whole scene before keeping the piece, the piece's
own size, and the mapper's GPU bytes); and the largest difference from the 1-rank image, in
8-bit levels.

The ranks share this machine's cores: on fewer cores than ranks, the times show the cost of
the reductions and of oversubscription, not a speed-up.
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

from ..progress import Progress
from .settings import Settings

Row = Dict[str, object]
TIMEOUT = 3600  # seconds per run


def interleaved_piece(grid, rank: int, ranks: int):
    """The cells of ``grid`` whose id is ``rank`` modulo ``ranks``, with their ids in the
    whole as global ids."""
    from vtkmodules.util.numpy_support import numpy_to_vtk
    from vtkmodules.vtkCommonCore import VTK_ID_TYPE, vtkIdList
    from vtkmodules.vtkFiltersCore import vtkExtractCells

    ids = numpy_to_vtk(np.arange(grid.GetNumberOfCells()), deep=True, array_type=VTK_ID_TYPE)
    ids.SetName("GlobalIds")
    grid.GetCellData().SetGlobalIds(ids)
    keep = vtkIdList()
    for cell in range(rank, grid.GetNumberOfCells(), ranks):
        keep.InsertNextId(cell)
    extract = vtkExtractCells()
    extract.SetInputData(grid)
    extract.SetCellList(keep)
    extract.Update()
    return extract.GetOutput()


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


def run_ranks(scene: str, ranks: int, settings: Settings, directory: pathlib.Path) -> Row:
    """One run of ``ranks`` ranks: its report and rank 0's image."""
    output = directory / f"{scene}-{ranks}"
    command = mpiexec(ranks) + [
        sys.executable, "-m", "spt.bench.parallel_rank", "--scene", scene,
        "--output", str(output), "--size", str(settings.parallel_size),
        "--repetitions", str(settings.parallel_repetitions), "--frames", str(settings.frames)]
    result = subprocess.run(command, capture_output=True, text=True, timeout=TIMEOUT,
                            check=False)
    if result.returncode != 0:
        raise RuntimeError(f"{' '.join(command)} failed:\n{result.stderr[-4000:]}")
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
    return {"scene": report["scene"], "ranks": report["ranks"],
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


def steps(settings: Settings) -> int:
    return len(settings.parallel_scenes) * len(settings.parallel_ranks)


def parallel(settings: Settings, progress: Progress, output: pathlib.Path) -> List[Row]:
    """Every scene at every rank count; the first count is the reference image."""
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
    return rows
