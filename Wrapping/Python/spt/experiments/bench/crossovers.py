"""Where one method overtakes another: in memory, in time at equal error, and what SPT's
sampling modes gain; SPT's time against the floor."""

from __future__ import annotations

import math
from typing import Dict, List, Sequence, Tuple

import numpy as np

from .models import Fit, time_key

Entry = Dict[str, object]


def memory_crossover(entries: Sequence[Entry], memory: Dict[str, Fit]) -> List[Entry]:
    """PBVR keeps ``L_r`` particle sets of ``n_p`` particles, SPT one copy of the mesh; PBVR
    needs more once ``L_r > c_SPT n_c / (c_PBVR n_p)``. One row per scene."""
    if "spt" not in memory or "pbvr" not in memory:
        return []
    c_spt, c_pbvr = memory["spt"].coefficients[0], memory["pbvr"].coefficients[0]
    rows, seen = [], set()
    for e in entries:
        if e["method"] != "pbvr" or not e.get("particles") or e["scene"] in seen:
            continue
        seen.add(e["scene"])
        per_repetition = e["particles"] / max(e.get("particle_sets", 1.0), 1.0)
        level = c_spt * e["cells"] / (c_pbvr * per_repetition) if c_pbvr > 0 else math.inf
        rows.append({"scene": e["scene"], "cells": e["cells"],
                     "particles_per_repetition": per_repetition,
                     "repetitions_at_equal_memory": level})
    return rows


def _level_at(curve: Sequence[Entry], error: float) -> Tuple[float, float]:
    """Where the line fitted to ``curve``'s log error against log L reaches ``error`` (inf
    where the error does not fall), and the line's slope."""
    slope, intercept = np.polyfit(np.log([e["repetitions"] for e in curve]),
                                  np.log([e["rmse"] for e in curve]), 1)
    return (math.exp((math.log(error) - intercept) / slope) if slope < 0 else math.inf), slope


def _equal_error(scene: str, name: str, spt: List[Entry], havs: Entry) -> Entry:
    key = time_key(spt)
    level = _level_at(spt, havs["rmse"])[0]
    time_slope, time_intercept = np.polyfit(np.log([e["repetitions"] for e in spt]),
                                            np.log([e[key] for e in spt]), 1)
    spt_seconds = math.exp(time_intercept + time_slope * math.log(max(level, 1.0)))
    # Already below HAVS-like's error at the lowest level measured: that level and its
    # measured time are an upper bound, not an extrapolation.
    below = spt[0]["rmse"] <= havs["rmse"]
    if below:
        level, spt_seconds = spt[0]["repetitions"], spt[0][key]
    return {"scene": scene, "spt": name, "havs": havs["method"], "havs_rmse": havs["rmse"],
            "havs_seconds": havs[key], "spt_repetitions": level, "time": key,
            "spt_seconds": spt_seconds, "spt_over_havs": spt_seconds / havs[key],
            "at_most": below}


def time_at_equal_error(quality: Sequence[Entry]) -> List[Entry]:
    """On each data set, the repetition level at which SPT's error falls to HAVS-like's
    (interpolated on the log-log curve), and the times there."""
    rows = []
    for scene, name in sorted({(e["scene"], e["method"]) for e in quality
                               if e["method"] in ("spt", "spt-visibility")}):
        spt = curve(quality, scene, name)
        if len(spt) < 2:
            continue
        for havs in (e for e in quality
                     if e["scene"] == scene and e["method"].startswith("havs")):
            rows.append(_equal_error(scene, name, spt, havs))
    return rows


def crossovers(entries: Sequence[Entry], memory: Dict[str, Fit]) -> Dict[str, object]:
    """Where one method overtakes another: memory (SPT against PBVR), time at equal error
    (SPT against HAVS-like), and the gains of SPT's sampling modes."""
    quality = [e for e in entries if e.get("sweep") == "quality" and "rmse" in e]
    return {"memory": memory_crossover(entries, memory),
            "time_at_equal_error": time_at_equal_error(quality),
            "sampling": sampling_gains(quality)}


def curve(entries: Sequence[Entry], scene: str, method: str) -> List[Entry]:
    """The entries of one method on one scene, by repetition level."""
    return sorted((e for e in entries if e["scene"] == scene and e["method"] == method),
                  key=lambda e: e["repetitions"])


def sampling_gains(entries: Sequence[Entry]) -> List[Entry]:
    """Beyond the paper, per data set: how much faster 16 repetitions per pass are than the
    paper's one per pass at equal error (they draw the same image, so at equal L_r), and how
    many stratified repetitions reach the error of the most independent ones measured."""
    rows = []
    for scene in sorted({e["scene"] for e in entries}):
        paper = curve(entries, scene, "spt-paper")
        independent = curve(entries, scene, "spt-independent")
        stratified = curve(entries, scene, "spt")
        if not independent or not stratified:
            continue
        key = time_key(paper + independent + stratified)
        row: Entry = {"scene": scene, "time": key}
        pairs = [(p, i) for p in paper for i in independent if p["repetitions"] == i["repetitions"]]
        if pairs:
            p, i = pairs[-1]
            row["per_pass_repetitions"] = p["repetitions"]
            row["per_pass_speedup"] = p[key] / i[key]
            row["per_pass_rmse"] = (p["rmse"], i["rmse"])
        target = independent[-1]
        needed, slope = _level_at(stratified, target["rmse"])
        row.update({"independent_repetitions": target["repetitions"],
                    "independent_rmse": target["rmse"], "stratified_repetitions": needed,
                    "stratified_slope": slope})
        rows.append(row)
    return rows


def floor_ratios(entries: Sequence[Entry]) -> List[Entry]:
    """SPT's time per repetition as a multiple of the floor, at each cell count."""
    cells = [e for e in entries if e.get("sweep") == "cells"]
    rows = []
    for floor in (e for e in cells if e["method"] == "floor"):
        row: Entry = {"cells": floor["cells"], "floor_seconds": floor["seconds"]}
        for name in ("spt", "spt-paper", "spt-visibility"):
            for e in cells:
                if e["method"] == name and e["cells"] == floor["cells"]:
                    row[name] = e["seconds"] / e["repetitions"] / floor["seconds"]
                    if np.isfinite(e.get("cpu_seconds", float("nan"))):
                        row[name + " cpu"] = (e["cpu_seconds"] / e["repetitions"] /
                                              floor["cpu_seconds"])
        rows.append(row)
    return rows
