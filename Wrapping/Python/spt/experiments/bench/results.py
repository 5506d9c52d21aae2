"""The results for readers, ``results.md``: a summary of each section of a benchmark run,
dated and naming the machine, each figure with the command that measures it again.

``python3 -m spt report --input out/bench/bench.json --output out/results.md`` writes it from
a ``bench.json`` without measuring anything, and rewrites the full tables (``bench.md``, the
appendix) next to the input; ``--figures`` draws the figures there again too. A benchmark run
writes all of them.
"""

from __future__ import annotations

import datetime
import json
import math
import os
import pathlib
import subprocess
from typing import Callable, Dict, List, Optional, Sequence, Tuple

from .. import tables
from .methods import METHODS
from .models import Fit
from .plots import plot_results
from .report import race_runs, write_report
from .results_views import attach, views_section

Entry = Dict[str, object]

#: The benchmark's figures: file, caption, and the sections whose run draws it again.
FIGURES = {
    "race": ("race.png", "error against time in the race", "race"),
    "cells": ("cells.png", "time and GPU memory against the cell count", "cells"),
    "repetitions": ("repetitions.png", "time and GPU memory against RepetitionLevel",
                    "repetitions"),
    "subpixels": ("subpixels.png", "time and GPU memory against SubpixelLevel", "subpixels"),
    "image": ("image.png", "time and GPU memory against the image size", "image"),
    "time_residuals": ("time_residuals.png", "relative residuals of the time models",
                       "cells,repetitions,subpixels,image"),
    "cpu_time_residuals": ("cpu_time_residuals.png",
                           "relative residuals of the CPU time models",
                           "cells,repetitions,subpixels,image"),
    "memory_residuals": ("memory_residuals.png", "relative residuals of the memory models",
                         "cells,repetitions,subpixels,image"),
    "quality": ("quality.png", "error against time at fixed repetition levels", "quality"),
}

#: The report's sections, in order: each heading is written whether or not the run measured
#: it (a section that was not measured says how to measure it).
SECTIONS = ("The race: time to quality", "Larger views and ParaView", "The camera anywhere",
            "Cell count", "Repetitions, subpixels and image size", "Fitted models", "Crossovers",
            "Time to quality at fixed levels", "Host time per frame", "The paper's large case",
            "Parallel rendering", "Figures made outside the benchmark", "Appendix")

REPORT_COMMAND = "python3 -m spt report --input {input} --output {output}"
BENCH_COMMAND = "python3 -m spt bench --sections {sections} --output out/bench"


def _f(value: object) -> str:
    """A number as the summaries print it: three significant digits."""
    if isinstance(value, float) and math.isfinite(value):
        return f"{value:.3g}"
    return tables.format_value(value)


def _table(header: Sequence[str], rows: Sequence[Sequence[object]]) -> str:
    """A Markdown table followed by a blank line."""
    return tables.markdown(header, [[_f(v) for v in row] for row in rows])


def figure(name: str, folder: str) -> List[str]:
    """A figure, its caption and the command that measures and draws it again."""
    path, caption, sections = FIGURES[name]
    return [f"![{caption}]({folder}{path})", "",
            f"*Figure: {caption}.* Drawn from `bench.json` by `python3 -m spt report "
            f"--figures`; measured and drawn again by "
            f"`{BENCH_COMMAND.format(sections=sections)}`.", ""]


def not_measured(section: str) -> List[str]:
    return ["This run did not measure it. Measure it with "
            f"`{BENCH_COMMAND.format(sections=section)}`.", ""]


# --- the race -----------------------------------------------------------------------------

def _row(rows: Sequence[Entry], scene: str, method: str) -> Optional[Entry]:
    return next((r for r in rows if r["scene"] == scene and r["method"] == method), None)


NOT_RACED = {"ratio": math.nan, "repetitions": 0}


def _reached(summary: Sequence[Entry], scene: str, method: str,
             target: str = "VTK PT's error") -> Optional[Dict[str, float]]:
    """The method's time to the target on the scene, None where it did not reach it, and
    NOT_RACED where it did not run."""
    entry = next((s for s in summary if s["scene"] == scene and s["method"] == method), None)
    return entry["reached"].get(target) if entry else NOT_RACED


def _at(reached: Optional[Dict[str, float]]) -> str:
    if reached is None:
        return "not reached"
    if reached is NOT_RACED:
        return "not raced"
    return f"{_f(reached['ratio'])} (L={reached['repetitions']})"


def race_scenes(race: Dict[str, object]) -> List[str]:
    """The race's scenes in the order they were raced."""
    scenes: List[str] = []
    for row in race["rows"]:
        if row["scene"] not in scenes:
            scenes.append(row["scene"])
    return scenes


def race_table(race: Dict[str, object]) -> str:
    """One row per scene: VTK PT, HAVS-like k=6 and SPT's time to VTK PT's error."""
    rows, summary = race["rows"], race["summary"]
    out = []
    for scene in race_scenes(race):
        pt, havs = _row(rows, scene, "pt"), _row(rows, scene, "havs6")
        single = _row(rows, scene, "spt")
        out.append([
            scene, f"{pt['cells']:,}", f"{_f(pt['rmse'])}, {_f(pt['seconds'])} s",
            f"{_f(havs['rmse'])}, {_f(havs['seconds'] / pt['seconds'])}" if havs else "-",
            _at(_reached(summary, scene, "spt")),
            _at(_reached(summary, scene, "spt-target")),
            _at(_reached(summary, scene, "spt-slabs")),
            f"{_f(single['rmse'])}, {_f(single['seconds'] / pt['seconds'])}"
            if single else "-",
            _at(_reached(summary, scene, "pbvr"))])
    return _table(
        ["scene", "tetrahedra", "VTK PT: RMSE, frame", "HAVS-like k=6: RMSE, time",
         "SPT: time to VTK PT's error", "SPT, error target: time", "SPT, 8 depth slabs: time",
         "SPT at L=1: RMSE, time", "PBVR: time to VTK PT's error"], out)


def _listing(items: Sequence[Tuple[str, Dict[str, float]]]) -> str:
    return ", ".join(f"{scene} ({_f(r['ratio'])} at L={r['repetitions']})"
                     for scene, r in items) or "none"


def _havs_findings(race: Dict[str, object]) -> str:
    better, worse = [], []
    for scene in race_scenes(race):
        pt, havs = _row(race["rows"], scene, "pt"), _row(race["rows"], scene, "havs6")
        if pt and havs:
            (better if havs["rmse"] < pt["rmse"] else worse).append(scene)
    return ("- Sorted HAVS-like k=6 has a smaller error than VTK PT on "
            f"{', '.join(better) or 'no scene'} and a larger one on "
            f"{', '.join(worse) or 'no scene'}: its centroid sort and k-buffer recover the "
            "order along a ray only where the faces' order is nearly right.")


def race_findings(race: Dict[str, object]) -> List[str]:
    """What the race shows, read from its rows: where SPT wins, where it loses."""
    summary = race["summary"]
    wins, losses, missed = [], [], []
    for scene in race_scenes(race):
        reached = _reached(summary, scene, "spt")
        if reached is None:
            missed.append(scene)
        elif reached is NOT_RACED:
            continue
        elif reached["ratio"] <= 1.0:
            wins.append((scene, reached))
        else:
            losses.append((scene, reached))
    paper = [s for s in race_scenes(race)
             if _reached(summary, s, "spt-paper-sampling") not in (None, NOT_RACED)]
    lines = [f"- SPT reaches VTK PT's error in at most one VTK PT frame on: {_listing(wins)}.",
             f"- **Where SPT loses:** it takes longer than VTK PT's frame on "
             f"{_listing(losses)}"
             + (f", and does not reach VTK PT's error by L = {race['max_repetitions']} on "
                f"{', '.join(missed)}" if missed else "")
             + ". Where one repetition is enough, SPT's time is that of its two traversals of "
             "the mesh, each paid per primitive and per pixel; where the noise "
             "needs many repetitions, it is their traversal pair. SPT's frame grows more "
             "slowly with the cells than VTK PT's, whose sort and projection run on the host, "
             "so the ratio falls as the mesh grows (compare the drills).",
             f"- The paper's sampling (the survivor estimator, one traversal per repetition, "
             f"independent thresholds) reaches VTK PT's error by L = "
             f"{race['max_repetitions']} on {len(paper)} of {len(race_scenes(race))} scenes"
             + (f" ({', '.join(paper)})" if paper else "") + ".",
             _havs_findings(race)]
    return lines + [""]


def race_section(results: Dict[str, object], folder: str) -> List[str]:
    race = results.get("race")
    lines = [f"## {SECTIONS[0]}", ""]
    if not race:
        return lines + not_measured("race")
    floors = [r["read_back_floor"] for r in race["rows"] if r.get("read_back_floor")]
    lines += [
        f"Each scene in one process at {race['size']} x {race['size']} (azimuth "
        f"{race['azimuth']:g}, elevation {race['elevation']:g}): every method's error "
        "against the exact reference (RMSE of premultiplied RGBA over the footprint) and its "
        f"frame, the best of {race['frames']}. The stochastic methods draw L = 1, 2, 4, ... "
        f"up to {race['max_repetitions']}; a method's time to an error is the frame of the "
        "smallest L at or below it, as a multiple of VTK PT's frame in the same process "
        "(below 1: faster than VTK PT). \"Error target\": SPT with `TargetError` set to VTK "
        "PT's error, from a new mapper. Images are read back in 8 bits per channel, which "
        f"alone leaves an error of about {_f(min(floors)) if floors else '0.0011'}."
        + race_runs(race, ", with the methods that each run had: compare within a scene."), "",
        race_table(race)]
    lines += race_findings(race)
    return lines + figure("race", folder)


# --- the sweeps ---------------------------------------------------------------------------

def _label(name: str) -> str:
    return METHODS[name].label if name in METHODS else name


def sweep_table(entries: Sequence[Entry], sweep: str, key: str,
                unit: Tuple[str, str]) -> str:
    """Each method's frame at the sweep's smallest and largest value, and their ratio."""
    chosen = [e for e in entries if e.get("sweep") == sweep]
    rows = []
    for name in METHODS:
        points = sorted((e for e in chosen if e["method"] == name), key=lambda e: e[key])
        if len(points) < 2:
            continue
        first, last = points[0], points[-1]
        memory = last.get("gpu_memory") or 0.0
        rows.append([_label(name), f"{unit[0]}{first[key]:,}{unit[1]}: {_f(first['seconds'])} s",
                     f"{unit[0]}{last[key]:,}{unit[1]}: {_f(last['seconds'])} s",
                     _f(last["seconds"] / first["seconds"]),
                     _f(memory / 2 ** 20) if memory else "-"])
    return _table(["method", "smallest", "largest", "time ratio",
                   "GPU MiB at the largest"], rows)


def cells_section(results: Dict[str, object], folder: str) -> List[str]:
    entries = [e for e in results["entries"] if e.get("sweep") == "cells"]
    lines = [f"## {SECTIONS[3]}", ""]
    if not entries:
        return lines + not_measured("cells")
    settings = results["settings"]
    lines += [f"Generated {results['shape']} meshes at {settings['size']} x "
              f"{settings['size']}, SPT and PBVR at {settings['sweep_repetitions']} "
              f"repetitions (the paper's mode at {settings['paper_sweep_repetitions']}), "
              f"medians of {results['frames']} frames. The floor draws every face opaque with "
              "`vtkPolyDataMapper`: no method that rasterizes the cells can be faster.", "",
              sweep_table(entries, "cells", "cells", ("", " cells"))]
    ratios = results.get("floor_ratios") or []
    ratios = [r for r in ratios if all(k in r for k in ("spt", "spt-paper", "spt-visibility"))]
    if ratios:
        last = ratios[-1]
        lines += [f"At {last['cells']:,} cells one repetition of SPT's default costs "
                  f"{_f(last.get('spt-visibility', float('nan')))} floors (the survivor "
                  f"estimator {_f(last.get('spt', float('nan')))}, the paper's mode "
                  f"{_f(last.get('spt-paper', float('nan')))}).", ""]
    return lines + figure("cells", folder)


def levels_section(results: Dict[str, object], folder: str) -> List[str]:
    entries = results["entries"]
    lines = [f"## {SECTIONS[4]}", ""]
    swept = [(s, k, u) for s, k, u in (("repetitions", "repetitions", ("L = ", "")),
                                       ("subpixels", "subpixels", ("SubpixelLevel ", "")),
                                       ("image", "width", ("", " px wide")))
             if any(e.get("sweep") == s for e in entries)]
    if not swept:
        return lines + not_measured("repetitions,subpixels,image")
    lines += [f"On the {results['settings']['sweep_cells']:,}-cell {results['shape']} mesh. "
              "SPT's survivor and default frames grow far more slowly than the repetitions: "
              "a traversal pair holds a group of up to 256 repetitions, and a fragment's work "
              "follows its opacity, not the group's size.", ""]
    for sweep, key, unit in swept:
        lines += [f"**{sweep.capitalize()}.**", "", sweep_table(entries, sweep, key, unit)]
        lines += figure(sweep, folder)
    return lines


# --- models and crossovers ----------------------------------------------------------------

def models_section(results: Dict[str, object], folder: str) -> List[str]:
    wall, cpu = results.get("time_models") or {}, results.get("cpu_time_models") or {}
    memory = results.get("memory_models") or {}
    lines = [f"## {SECTIONS[5]}", ""]
    if not wall:
        return lines + not_measured("cells,repetitions,subpixels,image")
    rows = [[wall[k]["name"], _f(wall[k]["r2"]),
             _f(cpu[k]["r2"]) if k in cpu else "-", wall[k]["n"]] for k in wall]
    lines += ["Least-squares fits of every sweep's frames (time in ms; coefficients in the "
              "appendix). CPU time, all threads, measures the work on a machine shared with "
              "other jobs better than wall time.", "",
              _table(["time model", "R^2 (wall)", "R^2 (CPU)", "points"], rows)]
    rows = [[_label(k), _f(m["coefficients"][0]), _f(m["coefficients"][1]), _f(m["r2"])]
            for k, m in memory.items()]
    lines += ["GPU memory, `M = c n + d w h L_s^2 + fixed` (n: tetrahedra, or particles "
              "times repetitions for PBVR):", "",
              _table(["method", "c [bytes per cell or particle]",
                      "d [bytes per sample]", "R^2"], rows)]
    for name in ("time_residuals", "cpu_time_residuals", "memory_residuals"):
        lines += figure(name, folder)
    return lines


def _range(values: Sequence[float]) -> str:
    return f"{_f(min(values))} to {_f(max(values))}"


def crossovers_section(results: Dict[str, object]) -> List[str]:
    cross = results.get("crossovers") or {}
    lines = [f"## {SECTIONS[6]}", ""]
    if not any(cross.values()):
        return lines + not_measured("cells,repetitions,subpixels,image,quality")
    if cross.get("memory"):
        rows = sorted(cross["memory"], key=lambda m: m["cells"])
        lines += ["**Memory.** PBVR holds its particles for every repetition, SPT only the "
                  "mesh: above this repetition level PBVR needs more GPU memory than SPT.", "",
                  _table(["scene", "cells", "particles per repetition",
                                   "L at equal memory"],
                         [[m["scene"], f"{m['cells']:,}", m["particles_per_repetition"],
                           m["repetitions_at_equal_memory"]] for m in rows])]
    if cross.get("time_at_equal_error"):
        rows = []
        chosen = [t for t in cross["time_at_equal_error"]
                  if t.get("spt") == "spt-visibility"] or cross["time_at_equal_error"]
        for scene in sorted({t["scene"] for t in chosen}):
            for t in sorted((t for t in chosen if t["scene"] == scene),
                            key=lambda t: t["havs"]):
                bound = "≤ " if t.get("at_most") else ""
                rows.append([scene, _label(t.get("spt", "spt")), _label(t["havs"]),
                             _f(t["havs_rmse"]), bound + _f(t["spt_over_havs"])])
        lines += ["**Time at equal error.** SPT's time to HAVS-like's error (interpolated on "
                  "its log-log curve) over HAVS-like's time; \"≤\": SPT's fewest repetitions "
                  "measured are already below that error.", "",
                  _table(["scene", "SPT", "against", "its RMSE", "SPT / HAVS-like"],
                         rows)]
    if cross.get("sampling"):
        lines += ["**Sampling.** 16 repetitions per traversal against the paper's one (the "
                  "same image), and the stratified repetitions that reach the error of the "
                  "most independent ones measured:", "",
                  _table(["scene", "speed-up of 16 per pass", "independent L, RMSE",
                                   "stratified L for it", "stratified slope"],
                         [[g["scene"], _f(g.get("per_pass_speedup", "-")),
                           f"{g['independent_repetitions']}, "
                           f"{_f(g['independent_rmse'])}",
                           _f(g["stratified_repetitions"]),
                           _f(g["stratified_slope"])] for g in cross["sampling"]])]
    return lines


# --- quality, host, large, camera, parallel -----------------------------------------------

def quality_section(results: Dict[str, object], folder: str) -> List[str]:
    chosen = [e for e in results["entries"] if e.get("sweep") == "quality" and "rmse" in e]
    lines = [f"## {SECTIONS[7]}", ""]
    if not chosen:
        return lines + not_measured("quality")
    scenes = sorted({e["scene"] for e in chosen})
    rows = []
    for name in (n for n in METHODS if any(e["method"] == n for e in chosen)):
        row: List[object] = [_label(name)]
        for scene in scenes:
            points = [e for e in chosen if e["scene"] == scene and e["method"] == name]
            best = max(points, key=lambda e: e["repetitions"], default=None)
            row.append(f"{_f(best['rmse'])} ({_f(best['seconds'])} s, L={best['repetitions']})"
                       if best else "-")
        rows.append(row)
    lines += ["The real data sets at each method's largest repetition level: RMSE against "
              "the exact reference (frame, L).", "",
              _table(["method"] + scenes, rows)]
    return lines + figure("quality", folder)


def host_section(results: Dict[str, object]) -> List[str]:
    host = results.get("host") or []
    lines = [f"## {SECTIONS[8]}", ""]
    if not host:
        return lines + not_measured("host")
    lines += ["Where an SPT frame's CPU time goes (`perf`): *host* is this project's library, "
              "VTK and Python on the application thread, the part a GPU would leave on the "
              "CPU; the rest is the software rasterizer.", "",
              _table(["cells", "frame [s]", "host [ms]", "application thread [s]",
                               "llvmpipe workers [s]"],
                     [[f"{h['cells']:,}", h["frame_seconds"],
                       f"{1000.0 * h['host_seconds_per_frame']:.1f}",
                       h["application_thread_seconds_per_frame"],
                       h["worker_seconds_per_frame"]] for h in host])]
    return lines


def large_section(results: Dict[str, object]) -> List[str]:
    large = results.get("large")
    lines = [f"## {SECTIONS[9]}", ""]
    if not large:
        return lines + not_measured("large")
    nan = float("nan")
    return lines + [
        f"{large['cells']:,} tetrahedra at {large['width']} x {large['height']} with "
        f"{large['repetitions']} repetitions, as in the paper: {large['seconds']:.0f} s per "
        f"frame, {large.get('gpu_memory', 0) / 2 ** 20:.0f} MiB on the GPU. The fitted "
        f"models predict {large.get('predicted_seconds', nan):.0f} s and "
        f"{large.get('predicted_memory', nan) / 2 ** 20:.0f} MiB.", ""]


def camera_section(results: Dict[str, object]) -> List[str]:
    camera = results.get("camera")
    lines = [f"## {SECTIONS[2]}", ""]
    if not camera:
        return lines + not_measured("camera")
    return lines + ["The camera dollies from the framed view into the mesh; ratio: the frame "
                    "over the same method's from outside.", "",
                    _table(["scene", "method", "camera", "frame [s]", "ratio",
                                     "RMSE"],
                           [[r["scene"], r["label"], r["camera"], r["seconds"],
                             r["ratio_to_outside"], r["rmse"]]
                            for r in camera["rows"]])]


def parallel_section(results: Dict[str, object]) -> List[str]:
    measured = results.get("parallel") or {}
    vtk = measured.get("vtk", []) if isinstance(measured, dict) else measured
    paraview = measured.get("paraview", []) if isinstance(measured, dict) else []
    lines = [f"## {SECTIONS[10]}", ""]
    if not vtk and not paraview:
        return lines + not_measured("parallel")
    lines += [f"Ranks on this machine's {os.cpu_count()} cores, each with an interleaved "
              "piece and no redistribution: more ranks than cores measure the reductions' "
              "cost and oversubscription, not a speed-up.", ""]
    if vtk:
        lines += [_table(
            ["scene", "ranks", "repetitions", "later frame [s]", "MiB moved per rank",
             "largest difference to 1 rank [levels]"],
            [[r["scene"], r["ranks"], r.get("first_repetitions", "-"),
              r["later_wall_seconds"], r["bytes_per_frame_per_rank"] / 2 ** 20,
              r["max_levels_from_one_rank"]] for r in vtk])]
    if paraview:
        kinds = sorted({r["representation"] for r in paraview})
        keys = sorted({(r["scene"], r["ranks"]) for r in paraview})
        rows = [[scene, ranks] + [next((_f(r["later_wall_seconds"]) for r in paraview
                                        if (r["scene"], r["ranks"], r["representation"])
                                        == (scene, ranks, kind)), "-") for kind in kinds]
                for scene, ranks in keys]
        lines += ["pvbatch with the plugin, wall time of a later render [s] (ParaView "
                  "redistributes the data for \"Volume\" and the baselines, not for SPT):", "",
                  _table(["scene", "ranks"] + kinds, rows)]
    return lines


# --- the document -------------------------------------------------------------------------

OTHER_FIGURES = (
    ("convergence against the exact reference per repetition level",
     "python3 -m spt figures convergence --output out/convergence"),
    ("the influence of visibility sorting, with difference images",
     "python3 -m spt figures sorting --output out/sorting"),
    ("PBVR against SPT", "python3 -m spt figures pbvr --output out/pbvr"),
    ("the sampling modes' error against time", "python3 -m spt figures sampling --output "
     "out/sampling"),
    ("the accuracy of the Monte Carlo estimate", "python3 -m spt figures accuracy --output "
     "out/accuracy"),
    ("the demo: sorted rendering where it fails, and a large mesh", "python3 -m spt demo"),
)


def other_section() -> List[str]:
    return [f"## {SECTIONS[11]}", "",
            "Not part of `bench.json`; each command writes its images, a table and a plot:",
            ""] + [f"- {what}: `{command}`" for what, command in OTHER_FIGURES] + [""]


def measured_date(path: pathlib.Path, results: Dict[str, object]) -> str:
    """The day the results were measured: recorded in the run, else the day the file was
    last committed, else the day it was written."""
    if results.get("date"):
        return str(results["date"])[:10]
    try:
        done = subprocess.run(["git", "log", "-1", "--format=%cs", "--", path.name],
                              cwd=path.parent, capture_output=True, text=True, check=False,
                              timeout=30)
        if done.returncode == 0 and done.stdout.strip():
            return done.stdout.strip()
    except (OSError, subprocess.SubprocessError):
        pass
    stamp = path.stat().st_mtime
    return datetime.datetime.fromtimestamp(stamp, datetime.timezone.utc).date().isoformat()


def _relative(path: pathlib.Path, start: pathlib.Path) -> str:
    return pathlib.Path(os.path.relpath(path.resolve(), start.resolve())).as_posix()


def software(machine: str) -> bool:
    """Whether the machine's OpenGL renderer is a software rasterizer."""
    return any(name in machine.lower() for name in ("llvmpipe", "softpipe", "swiftshader"))


def header(results: Dict[str, object], date: str, command: str) -> List[str]:
    return ["# Results", "",
            f"Measured in runs up to {date} on {results['machine']}"
            + (": a software rasterizer, no GPU. " if software(results["machine"]) else ". ")
            + "Times vary with the machine's load, so every comparison is a ratio taken within "
            "one process. Errors are RMSE of premultiplied RGBA against the exact reference "
            "(`spt.raycast`) over the volume's footprint.", "",
            f"This page is generated from the benchmark's `bench.json` by `{command}`. A full "
            "benchmark run (`python3 -m spt bench --output out/bench`) measures everything "
            "again and writes `bench.json`, the figures, the full tables and this page; "
            "`--sections` measures part of it (each figure names its sections), keeping the "
            "rest of an earlier `bench.json` in the same folder.", ""]


def compose(results: Dict[str, object], date: str, command: str, folder: str,
            appendix: str) -> str:
    """The Markdown text of ``results.md``."""
    parts: List[Callable[[], List[str]]] = [
        lambda: race_section(results, folder),
        lambda: views_section(results, SECTIONS[1]), lambda: camera_section(results),
        lambda: cells_section(results, folder), lambda: levels_section(results, folder),
        lambda: models_section(results, folder), lambda: crossovers_section(results),
        lambda: quality_section(results, folder), lambda: host_section(results),
        lambda: large_section(results), lambda: parallel_section(results), other_section]
    lines = header(results, date, command)
    for part in parts:
        lines += part()
    lines += [f"## {SECTIONS[12]}", "",
              f"Every measurement of the run, table by table: [{appendix}]({appendix}).", ""]
    text = "\n".join(line.rstrip(" ") for line in lines)
    while "\n\n\n" in text:
        text = text.replace("\n\n\n", "\n\n")
    return text


def load(path: pathlib.Path) -> Dict[str, object]:
    """A ``bench.json``, with the ``large-views.json`` next to it if there is one
    (:func:`.results_views.attach`)."""
    try:
        results = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError) as error:
        raise ValueError(f"cannot read the benchmark results {path}: {error}") from None
    missing = [k for k in ("machine", "entries", "settings") if k not in results]
    if missing:
        raise ValueError(f"{path} is not a benchmark's bench.json: no {', '.join(missing)}")
    return attach(results, path)


def _with_fits(results: Dict[str, object]) -> Dict[str, object]:
    fitted = dict(results)
    for key in ("time_models", "cpu_time_models", "memory_models"):
        fitted[key] = {k: v if isinstance(v, Fit) else Fit(**v)
                       for k, v in (results.get(key) or {}).items()}
    fitted.setdefault("crossovers", {"memory": [], "time_at_equal_error": []})
    return fitted


def write_results(source: pathlib.Path, output: pathlib.Path,
                  results: Optional[Dict[str, object]] = None, figures: bool = False) -> str:
    """Write ``output`` (results.md) and the appendix ``bench.md`` next to ``source``, from
    the run in ``source`` (bench.json), and with ``figures`` the figures there too; returns
    the text of ``output``."""
    results = load(source) if results is None else attach(results, source)
    plain = json.loads(json.dumps(results, default=lambda v: v.as_dict()))
    write_report(_with_fits(plain), source.parent)
    if figures:
        plot_results(_with_fits(plain), source.parent)
    folder = _relative(source.parent, output.parent)
    folder = "" if folder == "." else folder + "/"
    command = REPORT_COMMAND.format(input=_relative(source, pathlib.Path.cwd()),
                                    output=_relative(output, pathlib.Path.cwd()))
    text = compose(plain, measured_date(source, plain), command, folder, folder + "bench.md")
    output.write_text(text, encoding="utf-8")
    return text


__all__ = ["FIGURES", "SECTIONS", "compose", "load", "measured_date", "write_results"]
