"""The sweeps: the cell count (with SPT against the floor), the repetition level, the subpixel
level and the image size, and time to quality at fixed repetition levels on the real data."""

from __future__ import annotations

from typing import List, Sequence, Tuple

from ...tables import markdown
from ..methods import METHODS, label
from .markdown import Entry, Results, Section, figure, short, short_table, swept

#: The sweeps after the cell count: the entries' key, its unit in the summary, the title in
#: ``bench.md``.
OTHER_SWEEPS = (("repetitions", "repetitions", ("L = ", ""), "Repetition level"),
                ("subpixels", "subpixels", ("SubpixelLevel ", ""), "Subpixel level"),
                ("image", "width", ("", " px wide"), "Image size"))
CELL_FIGURES = {"cells": ("cells.png", "time and GPU memory against the cell count", "cells")}
LEVEL_FIGURES = {
    "repetitions": ("repetitions.png", "time and GPU memory against RepetitionLevel",
                    "repetitions"),
    "subpixels": ("subpixels.png", "time and GPU memory against SubpixelLevel", "subpixels"),
    "image": ("image.png", "time and GPU memory against the image size", "image")}
QUALITY_FIGURES = {
    "quality": ("quality.png", "error against time at fixed repetition levels", "quality")}


def sweep_table(entries: Sequence[Entry], key: str, unit: Tuple[str, str]) -> str:
    """Each method's frame at the sweep's smallest and largest value, and their ratio."""
    rows = []
    for name in METHODS:
        points = sorted((e for e in entries if e["method"] == name), key=lambda e: e[key])
        if len(points) < 2:
            continue
        first, last = points[0], points[-1]
        memory = last.get("gpu_memory") or 0.0
        rows.append([label(name),
                     f"{unit[0]}{first[key]:,}{unit[1]}: {short(first['seconds'])} s",
                     f"{unit[0]}{last[key]:,}{unit[1]}: {short(last['seconds'])} s",
                     short(last["seconds"] / first["seconds"]),
                     short(memory / 2 ** 20) if memory else "-"])
    return short_table(["method", "smallest", "largest", "time ratio",
                        "GPU MiB at the largest"], rows)


def cells_summary(results: Results, folder: str) -> List[str]:
    entries = swept(results, "cells")
    if not entries:
        return []
    settings = results["settings"]
    lines = [f"Generated {results['shape']} meshes at {settings['size']} x "
             f"{settings['size']}, SPT and PBVR at {settings['sweep_repetitions']} "
             f"repetitions (the paper's mode at {settings['paper_sweep_repetitions']}), "
             f"medians of {results['frames']} frames. The floor draws every face opaque with "
             "`vtkPolyDataMapper`: no method that rasterizes the cells can be faster.", "",
             sweep_table(entries, "cells", ("", " cells"))]
    ratios = [r for r in results.get("floor_ratios") or []
              if all(k in r for k in ("spt", "spt-paper", "spt-visibility"))]
    if ratios:
        last = ratios[-1]
        lines += [f"At {last['cells']:,} cells one repetition of SPT's default costs "
                  f"{short(last['spt-visibility'])} floors (the survivor estimator "
                  f"{short(last['spt'])}, the paper's mode {short(last['spt-paper'])}).", ""]
    return lines + figure(CELL_FIGURES["cells"], folder)


def cells_full(results: Results) -> List[str]:
    """The cell sweep, and SPT against the floor."""
    cells = swept(results, "cells")
    if not cells:
        return []
    names = [n for n in METHODS if any(e["method"] == n for e in cells)]
    rows = [[count] + [next((e["seconds"] for e in cells
                             if e["cells"] == count and e["method"] == name), "-")
                       for name in names]
            for count in sorted({e["cells"] for e in cells})]
    settings = results["settings"]
    lines = ["## Cell count", "", "![cells](cells.png)", "",
             f"Seconds per frame (SPT and PBVR at {settings['sweep_repetitions']} "
             f"repetitions, SPT paper at {settings['paper_sweep_repetitions']}):", "",
             markdown(["cells"] + names, rows)]
    ratios = results.get("floor_ratios", [])
    if ratios:
        lines += ["SPT's time per repetition as a multiple of the floor (all faces drawn "
                  "opaque by vtkPolyDataMapper, same image; a method re-run on its own with "
                  "`--methods` is compared with the floor of the earlier run). SPT: the "
                  "survivor estimator; SPT default: the visibility estimator with exact "
                  "coverage:", "",
                  markdown(["cells", "floor [s]", "SPT", "SPT paper", "SPT default",
                            "SPT (CPU time)", "SPT paper (CPU time)", "SPT default (CPU time)"],
                           [[r["cells"], r["floor_seconds"]]
                            + [r.get(k, "-") for k in ("spt", "spt-paper", "spt-visibility",
                                                       "spt cpu", "spt-paper cpu",
                                                       "spt-visibility cpu")] for r in ratios])]
    return lines


def levels_summary(results: Results, folder: str) -> List[str]:
    measured = [(s, key, unit) for s, key, unit, _ in OTHER_SWEEPS if swept(results, s)]
    if not measured:
        return []
    lines = [f"On the {results['settings']['sweep_cells']:,}-cell {results['shape']} mesh. "
             "SPT's survivor and default frames grow far more slowly than the repetitions: "
             "a traversal pair holds a group of up to 256 repetitions, and a fragment's work "
             "follows its opacity, not the group's size.", ""]
    for sweep, key, unit in measured:
        lines += [f"**{sweep.capitalize()}.**", "", sweep_table(swept(results, sweep), key, unit)]
        lines += figure(LEVEL_FIGURES[sweep], folder)
    return lines


def levels_full(results: Results) -> List[str]:
    """The repetition, subpixel and image-size sweeps."""
    lines = []
    for sweep, _, _, title in OTHER_SWEEPS:
        chosen = swept(results, sweep)
        if chosen:
            lines += [f"## {title}", "", f"![{sweep}]({sweep}.png)", "",
                      markdown(["method", "L_r", "L_s", "size", "cells", "seconds",
                                "CPU seconds", "GPU MiB"],
                               [[e["method"], e["repetitions"], e["subpixels"], e["width"],
                                 e["cells"], e["seconds"], e.get("cpu_seconds", "-"),
                                 e.get("gpu_memory", 0.0) / 2 ** 20] for e in chosen])]
    return lines


CELLS = Section("Cell count", "cells", cells_summary, cells_full, CELL_FIGURES)
LEVELS = Section("Repetitions, subpixels and image size", "repetitions,subpixels,image",
                 levels_summary, levels_full, LEVEL_FIGURES)


def _quality(results: Results) -> List[Entry]:
    return [e for e in swept(results, "quality") if "rmse" in e]


def quality_summary(results: Results, folder: str) -> List[str]:
    chosen = _quality(results)
    if not chosen:
        return []
    scenes = sorted({e["scene"] for e in chosen})
    rows = []
    for name in (n for n in METHODS if any(e["method"] == n for e in chosen)):
        row: List[object] = [label(name)]
        for scene in scenes:
            points = [e for e in chosen if e["scene"] == scene and e["method"] == name]
            best = max(points, key=lambda e: e["repetitions"], default=None)
            row.append(f"{short(best['rmse'])} ({short(best['seconds'])} s, "
                       f"L={best['repetitions']})" if best else "-")
        rows.append(row)
    return ["The real data sets at each method's largest repetition level: RMSE against "
            "the exact reference (frame, L).", "",
            short_table(["method"] + scenes, rows)] + figure(QUALITY_FIGURES["quality"], folder)


def quality_full(results: Results) -> List[str]:
    chosen = _quality(results)
    if not chosen:
        return []
    return ["## Time to quality at fixed levels", "", "![quality](quality.png)", "",
            markdown(["scene", "method", "L_r", "seconds", "CPU seconds", "RMSE"],
                     [[e["scene"], e["method"], e["repetitions"], e["seconds"],
                       e.get("cpu_seconds", "-"), e["rmse"]] for e in chosen])]


QUALITY = Section("Time to quality at fixed levels", "quality", quality_summary, quality_full,
                  QUALITY_FIGURES)
