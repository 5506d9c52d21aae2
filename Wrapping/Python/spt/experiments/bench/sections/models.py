"""What is fitted to the sweeps and found from them: the time and memory models, the
crossovers against PBVR and HAVS-like, and the paper's large case against the prediction."""

from __future__ import annotations

from typing import Dict, List

from ...tables import format_value, markdown
from ..methods import label
from .markdown import Entry, Results, Section, figure, short, short_table

#: The paper's figures that this report stands next to: only the memory per tetrahedron is
#: comparable (the paper's time coefficients were measured on a 2009 GPU).
PAPER = {"spt_bytes_per_cell": 20.6}
NAN = float("nan")
SWEPT = "cells,repetitions,subpixels,image"
FIGURES = {
    "time_residuals": ("time_residuals.png", "relative residuals of the time models", SWEPT),
    "cpu_time_residuals": ("cpu_time_residuals.png",
                           "relative residuals of the CPU time models", SWEPT),
    "memory_residuals": ("memory_residuals.png", "relative residuals of the memory models",
                         SWEPT)}


def models_summary(results: Results, folder: str) -> List[str]:
    wall, cpu = results.get("time_models") or {}, results.get("cpu_time_models") or {}
    if not wall:
        return []
    rows = [[wall[k]["name"], short(wall[k]["r2"]),
             short(cpu[k]["r2"]) if k in cpu else "-", wall[k]["n"]] for k in wall]
    memory = [[label(k), short(m["coefficients"][0]), short(m["coefficients"][1]),
               short(m["r2"])] for k, m in (results.get("memory_models") or {}).items()]
    lines = ["Least-squares fits of every sweep's frames (time in ms; coefficients in the "
             "appendix). CPU time, all threads, measures the work on a machine shared with "
             "other jobs better than wall time.", "",
             short_table(["time model", "R^2 (wall)", "R^2 (CPU)", "points"], rows),
             "GPU memory, `M = c n + d w h L_s^2 + fixed` (n: tetrahedra, or particles "
             "times repetitions for PBVR):", "",
             short_table(["method", "c [bytes per cell or particle]", "d [bytes per sample]",
                          "R^2"], memory)]
    for spec in FIGURES.values():
        lines += figure(spec, folder)
    return lines


def _rows(models: Dict[str, Dict[str, object]], kind: str) -> List[List[object]]:
    return [[f"{kind}{m['name']}",
             ", ".join(f"{t} = {c:.4g}" for t, c in zip(m["terms"], m["coefficients"])),
             m["r2"], m["n"]] for m in models.values()]


def models_full(results: Results) -> List[str]:
    memory = results.get("memory_models") or {}
    lines = ["## Fitted models", "",
             "Time in milliseconds (wall time of the frame, and the CPU time of all the "
             "process's threads, which on a machine shared with other jobs measures the "
             "work without the waiting), memory in bytes. Weighted least squares (relative "
             "error), each with a fixed term that the paper's forms leave out. Residual "
             "plots: `time_residuals.png`, `cpu_time_residuals.png`, `memory_residuals.png`.",
             "", markdown(["model", "coefficients", "R^2", "points"],
                          _rows(results.get("time_models") or {}, "wall, ")
                          + _rows(results.get("cpu_time_models") or {}, "CPU, ")
                          + _rows(memory, "memory, "))]
    if "spt" in memory:
        lines += [f"SPT: {memory['spt']['coefficients'][0]:.1f} bytes per tetrahedron on the "
                  "GPU plus the framebuffers (the paper: "
                  f"{PAPER['spt_bytes_per_cell']} bytes per tetrahedron).", ""]
    return lines + ["![time residuals](time_residuals.png)", "",
                    "![CPU time residuals](cpu_time_residuals.png)", "",
                    "![memory residuals](memory_residuals.png)", ""]


MODELS = Section("Fitted models", SWEPT, models_summary, models_full, FIGURES)


def crossovers_summary(results: Results, folder: str) -> List[str]:
    cross = results.get("crossovers") or {}
    lines: List[str] = []
    if cross.get("memory"):
        lines += ["**Memory.** PBVR holds its particles for every repetition, SPT only the "
                  "mesh: above this repetition level PBVR needs more GPU memory than SPT.", "",
                  short_table(["scene", "cells", "particles per repetition",
                               "L at equal memory"],
                              [[m["scene"], f"{m['cells']:,}", m["particles_per_repetition"],
                                m["repetitions_at_equal_memory"]]
                               for m in sorted(cross["memory"], key=lambda m: m["cells"])])]
    if cross.get("time_at_equal_error"):
        chosen = [t for t in cross["time_at_equal_error"]
                  if t.get("spt") == "spt-visibility"] or cross["time_at_equal_error"]
        rows = [[t["scene"], label(t.get("spt", "spt")), label(t["havs"]), short(t["havs_rmse"]),
                 ("≤ " if t.get("at_most") else "") + short(t["spt_over_havs"])]
                for t in sorted(chosen, key=lambda t: (t["scene"], t["havs"]))]
        lines += ["**Time at equal error.** SPT's time to HAVS-like's error (interpolated on "
                  "its log-log curve) over HAVS-like's time; \"≤\": SPT's fewest repetitions "
                  "measured are already below that error.", "",
                  short_table(["scene", "SPT", "against", "its RMSE", "SPT / HAVS-like"], rows)]
    if cross.get("sampling"):
        lines += ["**Sampling.** 16 repetitions per traversal against the paper's one (the "
                  "same image), and the stratified repetitions that reach the error of the "
                  "most independent ones measured:", "",
                  short_table(["scene", "speed-up of 16 per pass", "independent L, RMSE",
                               "stratified L for it", "stratified slope"],
                              [[g["scene"], short(g.get("per_pass_speedup", "-")),
                                f"{g['independent_repetitions']}, {short(g['independent_rmse'])}",
                                short(g["stratified_repetitions"]), short(g["stratified_slope"])]
                               for g in cross["sampling"]])]
    return lines


def _equal_error_row(t: Entry) -> List[object]:
    bound = "≤ " if t.get("at_most") else ""
    return [t["scene"], t.get("spt", "spt"), t["havs"], t["havs_rmse"], t["havs_seconds"],
            bound + format_value(t["spt_repetitions"]), t["spt_seconds"],
            bound + format_value(t["spt_over_havs"])]


def crossovers_full(results: Results) -> List[str]:
    cross = results.get("crossovers") or {}
    lines: List[str] = []
    if cross.get("memory"):
        lines += ["## Crossovers", "", "Memory: PBVR needs more GPU memory than SPT above this "
                  "repetition level (particles per repetition from PBVR's own count):", "",
                  markdown(["scene", "cells", "particles per repetition", "L_r at equal memory"],
                           [[m["scene"], m["cells"], m["particles_per_repetition"],
                             m["repetitions_at_equal_memory"]] for m in cross["memory"]])]
    if cross.get("time_at_equal_error"):
        lines += ["Time at equal error: the repetitions SPT needs to reach HAVS-like's error "
                  "on each data set, and its time there (SPT's error interpolated on its "
                  "log-log curve):", "",
                  markdown(["scene", "SPT", "HAVS-like", "its RMSE", "its time [s]", "SPT L_r",
                            "SPT time [s]", "SPT / HAVS"],
                           [_equal_error_row(t) for t in cross["time_at_equal_error"]])]
    if cross.get("sampling"):
        lines += ["Beyond the paper: 16 repetitions per pass against the paper's one per pass "
                  "(the same image, so equal error), and the stratified repetitions that reach "
                  "the error of the most independent repetitions measured:", "",
                  markdown(["scene", "L_r", "1 per pass / 16 per pass (time)",
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


CROSSOVERS = Section("Crossovers", "cells,repetitions,subpixels,image,quality",
                     crossovers_summary, crossovers_full)


def large_summary(results: Results, folder: str) -> List[str]:
    large = results["large"]
    return [f"{large['cells']:,} tetrahedra at {large['width']} x {large['height']} with "
            f"{large['repetitions']} repetitions, as in the paper: {large['seconds']:.0f} s per "
            f"frame, {large.get('gpu_memory', 0) / 2 ** 20:.0f} MiB on the GPU. The fitted "
            f"models predict {large.get('predicted_seconds', NAN):.0f} s and "
            f"{large.get('predicted_memory', NAN) / 2 ** 20:.0f} MiB.", ""]


def large_full(results: Results) -> List[str]:
    large = results["large"]
    return ["## The paper's large case", "",
            f"{large['cells']} tetrahedra, {large['width']} x {large['height']}, "
            f"{large['repetitions']} repetitions: {large['seconds']:.1f} s per frame "
            f"({large.get('cpu_seconds', NAN):.1f} CPU seconds), "
            f"{large.get('gpu_memory', 0) / 2 ** 20:.0f} MiB on the GPU. The models fitted "
            "above predict: the paper's form (per pass) "
            f"{large.get('predicted_seconds', NAN):.1f} s "
            f"({large.get('predicted_cpu_seconds', NAN):.1f} CPU seconds); the fragment form "
            f"{large.get('predicted_seconds_fragments', NAN):.1f} s "
            f"({large.get('predicted_cpu_seconds_fragments', NAN):.1f} CPU seconds); memory "
            f"{large.get('predicted_memory', NAN) / 2 ** 20:.0f} MiB.", ""]


LARGE = Section("The paper's large case", "large", large_summary, large_full, key="large")
