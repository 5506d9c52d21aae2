"""Parallel rendering: SPT on several MPI ranks, each with an interleaved piece and no
redistribution, and pvbatch with the plugin against the methods ParaView redistributes."""

from __future__ import annotations

import os
from typing import List, Sequence

from ...tables import markdown
from .markdown import Entry, Results, Section, short, short_table

MIB = 2.0 ** 20
NAN = float("nan")


def summary(results: Results, folder: str) -> List[str]:
    vtk, paraview = results["parallel"]["vtk"], results["parallel"]["paraview"]
    if not vtk and not paraview:
        return []
    lines = [f"Ranks on this machine's {os.cpu_count()} cores, each with an interleaved "
             "piece and no redistribution: more ranks than cores measure the reductions' "
             "cost and oversubscription, not a speed-up.", ""]
    if vtk:
        lines += [short_table(
            ["scene", "ranks", "repetitions", "later frame [s]", "MiB moved per rank",
             "largest difference to 1 rank [levels]"],
            [[r["scene"], r["ranks"], r.get("first_repetitions", "-"),
              r["later_wall_seconds"], r["bytes_per_frame_per_rank"] / MIB,
              r["max_levels_from_one_rank"]] for r in vtk])]
    if paraview:
        kinds = sorted({r["representation"] for r in paraview})
        rows = [[scene, ranks] + [next((short(r["later_wall_seconds"]) for r in paraview
                                        if (r["scene"], r["ranks"], r["representation"])
                                        == (scene, ranks, kind)), "-") for kind in kinds]
                for scene, ranks in sorted({(r["scene"], r["ranks"]) for r in paraview})]
        lines += ["pvbatch with the plugin, wall time of a later render [s] (ParaView "
                  "redistributes the data for \"Volume\" and the baselines, not for SPT):", "",
                  short_table(["scene", "ranks"] + kinds, rows)]
    return lines


def _spt_counts(row: Entry) -> str:
    """SPT's repetitions and estimated noise per render in a pvbatch row, if it has them."""
    counts = [c for c in row.get("spt_counts") or [] if c]
    return ", ".join(f"{n} ({e:.4f})" for n, e in counts)


def _paraview_table(rows: Sequence[Entry]) -> List[str]:
    """pvbatch: SPT without redistribution against the methods ParaView redistributes."""
    if not rows:
        return []
    return ["pvbatch with the plugin on the same interleaved pieces: reading, the first render "
            "(ParaView's redistribution, where the representation asks for it, and the frame; "
            "SPT asks for none) and later renders (the camera turned), in process CPU time "
            "(the largest over the ranks, all threads) and wall time on rank 0. \"Volume\" is "
            "ParaView's own, VTK's projected tetrahedra.", "",
            markdown(["scene", "ranks", "representation", "SPT reps (estimate)",
                      "reading CPU [s]", "first CPU [s]", "later CPU [s]", "reading wall [s]",
                      "first wall [s]", "later wall [s]"],
                     [[r["scene"], r["ranks"], r["representation"], _spt_counts(r),
                       r.get("read_cpu_seconds", NAN), r.get("first_cpu_seconds", NAN),
                       r.get("later_cpu_seconds", NAN), r["read_wall_seconds"],
                       r["first_wall_seconds"], r["later_wall_seconds"]] for r in rows]), ""]


def _vtk_rows(rows: Sequence[Entry]) -> List[List[object]]:
    return [[r["scene"], r["cells"], r["ranks"], r.get("first_repetitions", ""),
             " / ".join(str(n) for n in r.get("later_repetitions", [])),
             r.get("first_estimated_error", NAN), r["first_cpu_seconds"],
             r["later_cpu_seconds"], r["first_wall_seconds"], r["later_wall_seconds"],
             r["bytes_per_frame_per_rank"] / MIB,
             " / ".join(f"{b / MIB:.0f}" for b in r["peak_rss_bytes"]),
             " / ".join(f"{b / MIB:.1f}" for b in r["piece_bytes"]),
             " / ".join(f"{b / MIB:.1f}" for b in r["gpu_bytes"]),
             r["max_levels_from_one_rank"]] for r in rows]


def full(results: Results) -> List[str]:
    rows, paraview = results["parallel"]["vtk"], results["parallel"]["paraview"]
    target = rows[0].get("target_error", 0.0) if rows else 0.0
    return ["## Parallel: ranks with interleaved pieces, no redistribution", "",
            f"The ranks share this machine's {os.cpu_count()} cores, so more ranks than cores "
            "shows the cost of the reductions and of oversubscription, not a speed-up. SPT "
            f"with TargetError {target} (0: off) and RepetitionLevel as its cap: the "
            "repetitions of the first frame and of the later frames (the same camera: a "
            "frame that meets the target starts anew and draws the same), and the first "
            "frame's estimated noise. Times are the slowest rank's: process CPU time (all "
            "threads, the software rasterizer's too) and wall time of the first frame (the "
            "mesh prepared, the ranks' settings agreed) and of later frames (median). Bytes: "
            "what each rank puts into the reductions in the last frame. Memory per rank: peak "
            "resident size (it includes making the whole scene before keeping the piece), "
            "the piece, the GPU buffers.", "",
            markdown(["scene", "cells", "ranks", "first reps", "later reps", "estimate",
                      "first CPU [s]", "later CPU [s]", "first wall [s]", "later wall [s]",
                      "MiB moved per rank", "peak RSS [MiB]", "piece [MiB]", "GPU [MiB]",
                      "max diff. to 1 rank [levels]"], _vtk_rows(rows)), ""] \
        + _paraview_table(paraview)


PARALLEL = Section("Parallel rendering", "parallel", summary, full, key="parallel")
