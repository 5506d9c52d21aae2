"""One rank of the ``parallel`` benchmark section, run under ``mpiexec`` by :mod:`.parallel`.

Every rank makes the scene, keeps its interleaved piece (the cells whose id modulo the number
of ranks is its rank, numbered by their ids in the whole), and renders it with
vtkSPTVolumeMapper and the MPI controller: no redistribution. It times each frame (process
CPU time, all threads, and wall time, between barriers) and rank 0 writes the image, every
rank's measures and, per frame, the repetitions drawn and the noise estimated.

    mpiexec -n 2 python3 -m spt.experiments.bench.parallel_rank --scene post --output out/post-2
"""

from __future__ import annotations

import argparse
import json
import pathlib
import resource
import time
from typing import Dict, List, Optional, Sequence

import numpy as np


def parse(argv: Optional[Sequence[str]]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--scene", required=True)
    parser.add_argument("--output", type=pathlib.Path, required=True,
                        help="writes OUTPUT.npy (rank 0's image) and OUTPUT.json")
    parser.add_argument("--size", type=int, default=256)
    parser.add_argument("--repetitions", type=int, default=16,
                        help="RepetitionLevel: the cap, with --target-error")
    parser.add_argument("--target-error", type=float, default=0.0,
                        help="TargetError (0: off, every frame draws --repetitions)")
    parser.add_argument("--frames", type=int, default=3)
    return parser.parse_args(argv)


def controller():
    """VTK's MPI controller over MPI as mpi4py initialized it."""
    from mpi4py import MPI  # noqa: F401  (initializes MPI)
    from vtkmodules.vtkParallelCore import vtkMultiProcessController
    from vtkmodules.vtkParallelMPI import vtkMPIController

    made = vtkMPIController()
    made.Initialize()
    vtkMultiProcessController.SetGlobalController(made)
    return made


def render_frames(window, mapper, frames: int, barrier) -> List[Dict[str, float]]:
    """Each frame's process CPU time and wall time, the ranks starting together, and what the
    frame drew."""
    measures = []
    for _ in range(frames):
        barrier()
        cpu, wall = time.process_time(), time.perf_counter()
        window.Render()
        window.WaitForCompletion()
        measures.append({"cpu_seconds": time.process_time() - cpu,
                         "wall_seconds": time.perf_counter() - wall,
                         "repetitions": mapper.GetLastRepetitionCount(),
                         "estimated_error": mapper.GetEstimatedError()})
    return measures


def main(argv: Optional[Sequence[str]] = None) -> None:
    arguments = parse(argv)
    from mpi4py import MPI

    from ... import render
    from ...meshes import interleaved_piece
    from .race import race_scene

    # The whole scene first: VTK's parallel-aware readers (PLOT3D) read only a part of the
    # data on each rank once a global controller is set.
    scene = race_scene(arguments.scene)
    mpi = controller()
    rank, ranks = mpi.GetLocalProcessId(), mpi.GetNumberOfProcesses()
    piece = interleaved_piece(scene.grid, rank, ranks)
    mapper = render.spt_mapper(arguments.repetitions,
                               target_error=arguments.target_error or None)
    mapper.SetController(mpi)
    window, renderer = render.make_window(arguments.size, arguments.size)
    render.add_volume(renderer, piece, scene.property, mapper)
    render.place_camera(renderer, scene.grid.GetBounds(), scene.view)
    frames = render_frames(window, mapper, arguments.frames, MPI.COMM_WORLD.Barrier)
    measures = {"rank": rank, "cells": piece.GetNumberOfCells(), "frames": frames,
                "bytes_per_frame": mapper.GetFrameStatistics().GetParallelBytes(),
                "piece_bytes": piece.GetActualMemorySize() * 1024,
                "gpu_bytes": mapper.GetGPUMemorySize(),
                "peak_rss_bytes": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024}
    gathered = MPI.COMM_WORLD.gather(measures, root=0)
    if rank == 0:
        np.save(arguments.output.with_suffix(".npy"), render.read_rgba(window))
        arguments.output.with_suffix(".json").write_text(json.dumps(
            {"scene": arguments.scene, "ranks": ranks, "whole_cells": scene.grid.GetNumberOfCells(),
             "target_error": arguments.target_error, "per_rank": gathered}, indent=1))
    window.Finalize()


if __name__ == "__main__":
    main()
