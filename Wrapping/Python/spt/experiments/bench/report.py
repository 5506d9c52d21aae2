"""The benchmark's Markdown report, ``bench.md``: the race first, then the sweeps, the
models, the crossovers, time to quality, host time and the large case."""

from __future__ import annotations

import os
import pathlib
from typing import Dict, Iterable, List, Optional, Sequence

from .. import tables
from .methods import METHODS
from .models import Fit

Entry = Dict[str, object]

#: The paper's figures that this report stands next to: only the memory per tetrahedron is
#: comparable (the paper's time coefficients were measured on a 2009 GPU).
PAPER = {"spt_bytes_per_cell": 20.6}


def table(header: Sequence[str], rows: Iterable[Sequence[object]]) -> str:
    """A Markdown table (its last line ends the paragraph in the report)."""
    return tables.markdown(header, rows)


def _reached(cell) -> str:
    if cell is None:
        return "not reached"
    return f"{tables.format_value(cell['ratio'])} (L={cell['repetitions']})"


def race_summary_table(race: Dict[str, object]) -> str:
    """Each stochastic method's time to each target as a multiple of VTK PT's frame."""
    summary = race["summary"]
    if not summary:
        return ""
    targets = list(summary[0]["reached"])
    rows = [[s["scene"], s["label"]] + [_reached(s["reached"].get(t)) for t in targets]
            + [1000.0 * s["host_seconds"], s["host_repetitions"]] for s in summary]
    return table(["scene", "method"] + [f"to {t}" for t in targets]
                 + ["host CPU [ms/frame]", "at L"], rows)


def _objects(objects: Dict[str, float]) -> str:
    """Shared objects and their milliseconds per frame, as in ``libvtkCommonCore 12``."""
    if not objects:
        return "-"
    return "; ".join(f"{name.split('.so')[0].split('-pv')[0]} {1000.0 * t:.3g}"
                     for name, t in objects.items())


def race_rows_table(race: Dict[str, object]) -> str:
    """Every measurement of the race."""
    pt = {r["scene"]: r["seconds"] for r in race["rows"] if r["method"] == "pt"}
    # the objects are recorded where perf measured the host time
    objects = any(r.get("host_objects") for r in race["rows"])
    rows = [[r["scene"], r["label"], r["repetitions"], r["rmse"], r["seconds"],
             r["seconds"] / pt[r["scene"]] if r["scene"] in pt else "-",
             1000.0 * r["host_seconds"]]
            + ([_objects(r.get("host_objects", {}))] if objects else [])
            + [r["cpu_seconds"]] for r in race["rows"]]
    return table(["scene", "method", "L", "RMSE", "frame [s]", "frame / VTK PT", "host CPU [ms]"]
                 + (["host CPU's largest objects [ms]"] if objects else [])
                 + ["CPU, all threads [s]"], rows)


def race_runs(race: Dict[str, object],
              note: str = ": each scene's methods in one process, so compare ratios within a "
                          "scene.") -> str:
    """Which scenes were raced together, where a race was run scene by scene, and ``note``."""
    runs = race.get("runs") or []
    if len(runs) < 2:
        return ""
    groups = "; ".join(", ".join(run["scenes"]) for run in runs)
    return f" The scenes were raced in {len(runs)} runs ({groups}){note}"


def _read_back_floors(race: Dict[str, object]) -> str:
    """Each scene's least error of an 8-bit image, where the race recorded it."""
    floors: Dict[str, float] = {}
    for row in race["rows"]:
        if row.get("read_back_floor") is not None:
            floors.setdefault(row["scene"], row["read_back_floor"])
    if not floors:
        return ""
    listed = ", ".join(f"{scene} {tables.format_value(value)}" for scene, value in floors.items())
    return (" Every image is read back through 8 bits per channel, so no error can be below "
            f"that of the exact image rounded to 8 bits: {listed}.")


def race_section(race: Dict[str, object]) -> List[str]:
    """The race, the report's headline."""
    if not race:
        return []
    source = ("`perf` samples of the application thread outside the OpenGL driver"
              if race["host_source"] == "perf" else
              "CPU time of the application thread during the frame (`perf` was not "
              "available; this includes the driver's work on that thread)")
    return ["## The race: time to quality", "",
            f"{race['size']} x {race['size']}, azimuth {race['azimuth']:g}, elevation "
            f"{race['elevation']:g}, every error against the exact reference (RMSE of "
            f"premultiplied RGBA), every time the best of {race['frames']} frames in one "
            f"process. Stochastic methods at L = 1, 2, 4, ... up to "
            f"{race['max_repetitions']}, until every target is reached. Time to an error: "
            "the frame of the smallest L at or below it, as a multiple of VTK PT's frame. "
            f"Host CPU time: {source}.{race_runs(race)}{_read_back_floors(race)}", "",
            "![race](race.png)", "", race_summary_table(race), race_rows_table(race)]


def cells_section(results: Dict[str, object]) -> List[str]:
    """The cell sweep, and SPT against the floor."""
    cells = [e for e in results["entries"] if e.get("sweep") == "cells"]
    if not cells:
        return []
    names = [n for n in METHODS if any(e["method"] == n for e in cells)]
    rows = []
    for count in sorted({e["cells"] for e in cells}):
        row: List[object] = [count]
        for name in names:
            match = [e for e in cells if e["cells"] == count and e["method"] == name]
            row.append(match[0]["seconds"] if match else "-")
        rows.append(row)
    settings = results["settings"]
    lines = ["## Cell count", "", "![cells](cells.png)", "",
             f"Seconds per frame (SPT and PBVR at {settings['sweep_repetitions']} "
             f"repetitions, SPT paper at {settings['paper_sweep_repetitions']}):", "",
             table(["cells"] + names, rows)]
    ratios = results.get("floor_ratios", [])
    if ratios:
        lines += ["SPT's time per repetition as a multiple of the floor (all faces drawn "
                  "opaque by vtkPolyDataMapper, same image; a method re-run on its own with "
                  "`--methods` is compared with the floor of the earlier run). SPT: the "
                  "survivor estimator; SPT default: the visibility estimator with exact "
                  "coverage:", "",
                  table(["cells", "floor [s]", "SPT", "SPT paper", "SPT default",
                         "SPT (CPU time)", "SPT paper (CPU time)", "SPT default (CPU time)"],
                        [[r["cells"], r["floor_seconds"]]
                         + [r.get(k, "-") for k in ("spt", "spt-paper", "spt-visibility",
                                                    "spt cpu", "spt-paper cpu",
                                                    "spt-visibility cpu")] for r in ratios])]
    return lines


def sweep_sections(entries: Sequence[Entry]) -> List[str]:
    """The repetition, subpixel and image-size sweeps."""
    lines = []
    for sweep, title, picture in (("repetitions", "Repetition level", "repetitions.png"),
                                  ("subpixels", "Subpixel level", "subpixels.png"),
                                  ("image", "Image size", "image.png")):
        chosen = [e for e in entries if e.get("sweep") == sweep]
        if not chosen:
            continue
        lines += [f"## {title}", "", f"![{sweep}]({picture})", "",
                  table(["method", "L_r", "L_s", "size", "cells", "seconds", "CPU seconds",
                         "GPU MiB"],
                        [[e["method"], e["repetitions"], e["subpixels"], e["width"],
                          e["cells"], e["seconds"], e.get("cpu_seconds", "-"),
                          e.get("gpu_memory", 0.0) / 2 ** 20] for e in chosen])]
    return lines


def _model_rows(models: Dict[str, Fit], label: str) -> List[List[object]]:
    return [[f"{label}{m.name}",
             ", ".join(f"{t} = {c:.4g}" for t, c in zip(m.terms, m.coefficients)),
             m.r2, m.n] for m in models.values()]


def models_section(results: Dict[str, object]) -> List[str]:
    """The fitted time and memory models."""
    time_fits, memory_fits = results["time_models"], results["memory_models"]
    lines = ["## Fitted models", "",
             "Time in milliseconds (wall time of the frame, and the CPU time of all the "
             "process's threads, which on a machine shared with other jobs measures the "
             "work without the waiting), memory in bytes. Weighted least squares (relative "
             "error), each with a fixed term that the paper's forms leave out. Residual "
             "plots: `time_residuals.png`, `cpu_time_residuals.png`, `memory_residuals.png`.",
             "", table(["model", "coefficients", "R^2", "points"],
                       _model_rows(time_fits, "wall, ")
                       + _model_rows(results.get("cpu_time_models", {}), "CPU, ")
                       + _model_rows(memory_fits, "memory, "))]
    if "spt" in memory_fits:
        c = memory_fits["spt"].coefficients[0]
        lines += [f"SPT: {c:.1f} bytes per tetrahedron on the GPU plus the framebuffers "
                  f"(the paper: {PAPER['spt_bytes_per_cell']} bytes per tetrahedron).", ""]
    lines += ["![time residuals](time_residuals.png)", "",
              "![CPU time residuals](cpu_time_residuals.png)", "",
              "![memory residuals](memory_residuals.png)", ""]
    return lines


def _equal_error_rows(cross: Dict[str, object]) -> List[List[object]]:
    rows = []
    for t in cross["time_at_equal_error"]:
        bound = "≤ " if t.get("at_most") else ""
        rows.append([t["scene"], t.get("spt", "spt"), t["havs"], t["havs_rmse"],
                     t["havs_seconds"], bound + tables.format_value(t["spt_repetitions"]),
                     t["spt_seconds"], bound + tables.format_value(t["spt_over_havs"])])
    return rows


def crossover_section(cross: Dict[str, object]) -> List[str]:
    """Memory against PBVR, time at equal error against HAVS-like, sampling gains."""
    lines = []
    if cross["memory"]:
        lines += ["## Crossovers", "", "Memory: PBVR needs more GPU memory than SPT above this "
                  "repetition level (particles per repetition from PBVR's own count):", "",
                  table(["scene", "cells", "particles per repetition", "L_r at equal memory"],
                        [[m["scene"], m["cells"], m["particles_per_repetition"],
                          m["repetitions_at_equal_memory"]] for m in cross["memory"]])]
    if cross["time_at_equal_error"]:
        lines += ["Time at equal error: the repetitions SPT needs to reach HAVS-like's error "
                  "on each data set, and its time there (SPT's error interpolated on its "
                  "log-log curve):", "",
                  table(["scene", "SPT", "HAVS-like", "its RMSE", "its time [s]", "SPT L_r",
                         "SPT time [s]", "SPT / HAVS"], _equal_error_rows(cross))]
    if cross.get("sampling"):
        lines += ["Beyond the paper: 16 repetitions per pass against the paper's one per pass "
                  "(the same image, so equal error), and the stratified repetitions that reach "
                  "the error of the most independent repetitions measured:", "",
                  table(["scene", "L_r", "1 per pass / 16 per pass (time)",
                         "RMSE (1 / 16 per pass)", "independent L_r", "its RMSE",
                         "stratified L_r for it", "stratified slope"],
                        [[g["scene"], g.get("per_pass_repetitions", "-"),
                          g.get("per_pass_speedup", "-"),
                          " / ".join(f"{v:.4f}" for v in g["per_pass_rmse"])
                          if "per_pass_rmse" in g else "-",
                          g["independent_repetitions"], g["independent_rmse"],
                          g["stratified_repetitions"], g["stratified_slope"]]
                         for g in cross["sampling"]])]
    return lines


def quality_section(entries: Sequence[Entry]) -> List[str]:
    """Error against time on the real data sets."""
    chosen = [e for e in entries if e.get("sweep") == "quality" and "rmse" in e]
    if not chosen:
        return []
    return ["## Time to quality at fixed levels", "", "![quality](quality.png)", "",
            table(["scene", "method", "L_r", "seconds", "CPU seconds", "RMSE"],
                  [[e["scene"], e["method"], e["repetitions"], e["seconds"],
                    e.get("cpu_seconds", "-"), e["rmse"]] for e in chosen])]


def host_section(host: Sequence[Entry]) -> List[str]:
    """Where SPT's host time goes as the cell count grows."""
    if not host:
        return []
    return ["## Host time per frame", "",
            "CPU seconds per SPT frame (16 repetitions), from `perf` samples of the timed "
            "frames, by thread and shared object. Host: this project's library, VTK and "
            "Python on the application thread, the part a real GPU leaves on the CPU. Kernel "
            "and C library: on that thread, mostly the memory that llvmpipe's vertex stage "
            "maps for every draw. The rest is the emulated GPU (llvmpipe's shaders and Mesa's "
            "driver on the application thread, the rasterizer threads).", "",
            table(["cells", "frame [s]", "host [s]", "SPT library [s]", "kernel + libc [s]",
                   "application thread [s]", "llvmpipe workers [s]"],
                  [[h["cells"], h["frame_seconds"], h["host_seconds_per_frame"],
                    h["project_seconds_per_frame"], h.get("system_seconds_per_frame", "-"),
                    h["application_thread_seconds_per_frame"],
                    h["worker_seconds_per_frame"]] for h in host])]


def camera_section(camera: Dict[str, object]) -> List[str]:
    """Frame time and error with the camera outside, cutting and inside the mesh."""
    if not camera:
        return []
    return ["## The camera anywhere", "",
            f"{camera['size']} x {camera['size']}, the stochastic methods at "
            f"{camera['repetitions']} repetitions; best of {camera['frames']} frames; the "
            "camera dollies from the framed view into the mesh. Ratio: the frame time over "
            "the same method's with the camera outside.", "",
            table(["scene", "method", "camera", "dolly", "frame [s]", "ratio", "RMSE"],
                  [[r["scene"], r["label"], r["camera"], r["dolly"], r["seconds"],
                    r["ratio_to_outside"], r["rmse"]] for r in camera["rows"]]), ""]


def large_section(large: Dict[str, object]) -> List[str]:
    """The paper's large case against the models' prediction."""
    if not large:
        return []
    nan = float("nan")
    return ["## The paper's large case", "",
            f"{large['cells']} tetrahedra, {large['width']} x {large['height']}, "
            f"{large['repetitions']} repetitions: {large['seconds']:.1f} s per frame "
            f"({large.get('cpu_seconds', nan):.1f} CPU seconds), "
            f"{large.get('gpu_memory', 0) / 2 ** 20:.0f} MiB on the GPU. The models fitted "
            "above predict: the paper's form (per pass) "
            f"{large.get('predicted_seconds', nan):.1f} s "
            f"({large.get('predicted_cpu_seconds', nan):.1f} CPU seconds); the fragment form "
            f"{large.get('predicted_seconds_fragments', nan):.1f} s "
            f"({large.get('predicted_cpu_seconds_fragments', nan):.1f} CPU seconds); memory "
            f"{large.get('predicted_memory', nan) / 2 ** 20:.0f} MiB.", ""]


def paraview_parallel_table(rows: Sequence[Entry]) -> List[str]:
    """pvbatch: SPT without redistribution against the methods ParaView redistributes."""
    if not rows:
        return []
    nan = float("nan")
    return ["pvbatch with the plugin on the same interleaved pieces: reading, the first render "
            "(ParaView's redistribution, where the representation asks for it, and the frame; "
            "SPT asks for none) and later renders (the camera turned), in process CPU time "
            "(the largest over the ranks, all threads) and wall time on rank 0. \"Volume\" is "
            "ParaView's own, VTK's projected tetrahedra.", "",
            table(["scene", "ranks", "representation", "SPT reps (estimate)",
                   "reading CPU [s]", "first CPU [s]", "later CPU [s]", "reading wall [s]",
                   "first wall [s]", "later wall [s]"],
                  [[r["scene"], r["ranks"], r["representation"], spt_counts(r),
                    r.get("read_cpu_seconds", nan), r.get("first_cpu_seconds", nan),
                    r.get("later_cpu_seconds", nan), r["read_wall_seconds"],
                    r["first_wall_seconds"], r["later_wall_seconds"]] for r in rows]), ""]


def spt_counts(row: Entry) -> str:
    """SPT's repetitions and estimated noise per render in a pvbatch row, if it has them."""
    counts = [c for c in row.get("spt_counts") or [] if c]
    return ", ".join(f"{n} ({e:.4f})" for n, e in counts)


def parallel_rows(rows: Sequence[Entry]) -> List[List[object]]:
    """The VTK table's rows."""
    mib = 2.0 ** 20
    return [[r["scene"], r["cells"], r["ranks"], r.get("first_repetitions", ""),
             " / ".join(str(n) for n in r.get("later_repetitions", [])),
             r.get("first_estimated_error", float("nan")), r["first_cpu_seconds"],
             r["later_cpu_seconds"], r["first_wall_seconds"], r["later_wall_seconds"],
             r["bytes_per_frame_per_rank"] / mib,
             " / ".join(f"{b / mib:.0f}" for b in r["peak_rss_bytes"]),
             " / ".join(f"{b / mib:.1f}" for b in r["piece_bytes"]),
             " / ".join(f"{b / mib:.1f}" for b in r["gpu_bytes"]),
             r["max_levels_from_one_rank"]] for r in rows]


def parallel_section(measured) -> List[str]:
    """SPT on several MPI ranks, each with an interleaved piece, no redistribution."""
    if not measured:
        return []
    # Results of the first version of the section are a list of the VTK rows.
    rows = measured.get("vtk", []) if isinstance(measured, dict) else measured
    paraview = measured.get("paraview", []) if isinstance(measured, dict) else []
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
            table(["scene", "cells", "ranks", "first reps", "later reps", "estimate",
                   "first CPU [s]", "later CPU [s]", "first wall [s]", "later wall [s]",
                   "MiB moved per rank", "peak RSS [MiB]", "piece [MiB]", "GPU [MiB]",
                   "max diff. to 1 rank [levels]"], parallel_rows(rows)), ""] + \
        paraview_parallel_table(paraview)


def paraview_view_section(measured: Optional[Dict[str, object]]) -> List[str]:
    """Every still and interactive render of the ``paraview`` section."""
    if not measured or not measured.get("scenes"):
        return []
    rows = [[r["scene"], r["representation"], r["cells"], r["seconds"],
             ", ".join(f"{v:.3g}" for v in r["still_seconds"]), r["rmse"], r["rmse_rgba"],
             (r.get("still") or {}).get("repetitions", "-"), r["interactive_seconds"],
             1.0 / r["desired_update_rate"], (r.get("interactive") or {}).get("repetitions", "-"),
             r["used_lod"]]
            for scene in measured["scenes"] for r in scene["rows"]]
    width, height = measured["size"]
    return [f"## ParaView: a {width} x {height} view", "",
            "pvpython with the plugin, each representation at its defaults. Still renders: "
            "the first three, the second is the one timed; RMSE of the second's image in the "
            "view (RGB over black) and of a screenshot over a transparent background (RGBA), "
            "against the exact reference; the second interactive render against one over the "
            "desired update rate.", "",
            table(["scene", "representation", "tetrahedra", "still [s]", "still renders [s]",
                   "RMSE (view)", "RMSE (RGBA shot)", "L", "interactive [s]",
                   "requested [s]", "L interactive", "LOD"], rows),
            table(["scene", "exact reference [s]", "read-back floor", "unit distance"],
                  [[m["scene"], m["reference_seconds"], m["read_back_floor"],
                    m["unit_distance"]] for m in measured["scenes"]])]


def write_report(results: Dict[str, object], output: pathlib.Path) -> str:
    """Write ``bench.md`` into ``output``; returns its text."""
    entries = results["entries"]
    lines = ["# SPT benchmark", "",
             f"Machine: {results['machine']}. Sweep times are medians of {results['frames']} "
             "frames after a warm-up frame, with the GPU finished; every ratio is taken within "
             "one run of its section (of its scene in the race). Generated meshes: "
             + results["shape"] + ".", ""]
    lines += race_section(results.get("race"))
    for other in results.get("race_sizes") or []:
        at = race_section(other)
        lines += [f"## The race at {other['size']} x {other['size']}"] + at[1:]
    lines += paraview_view_section(results.get("paraview"))
    lines += camera_section(results.get("camera"))
    lines += cells_section(results)
    lines += sweep_sections(entries)
    lines += models_section(results)
    lines += crossover_section(results["crossovers"])
    lines += quality_section(entries)
    lines += host_section(results.get("host", []))
    lines += large_section(results.get("large"))
    lines += parallel_section(results.get("parallel"))
    text = "\n".join(lines)
    (output / "bench.md").write_text(text, encoding="utf-8")
    return text
