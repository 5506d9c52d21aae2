"""Beyond the paper, measured: several repetitions per pass, stratified thresholds, and
the time it takes each sampling mode to reach a given error.

``python3 -m spt figures sampling`` writes ``sampling.json``, ``sampling.md`` and
``sampling.png`` (error against repetitions, error against time) into its output folder.
All times are taken in one process, back to back, and reported next to the paper's mode
(independent thresholds, one repetition per pass).
"""

from __future__ import annotations

import json
import pathlib
from typing import Dict, List, Sequence

import numpy as np

from .. import metrics, render
from . import plots, tables
from ..progress import Progress
from ..scenes import Scene, scene

_SURVIVOR = {"estimator": "survivor", "exact_coverage": False}

#: The sampling modes compared: (label, stratified, repetitions per pass, estimator settings).
#: The first three are the paper's survivor estimator; the last is the mapper's default.
MODES = [("paper: independent, 1 per pass", False, 1, _SURVIVOR),
         ("independent, 16 per pass", False, 16, _SURVIVOR),
         ("stratified, 16 per pass", True, 16, _SURVIVOR),
         ("default: visibility, exact coverage, stratified, 16 per pass", True, 16, {})]


def _render(s: Scene, level: int, stratified: bool, per_pass: int, size: int,
            seed: int, estimator: Dict[str, object] = _SURVIVOR) -> render.Rendering:
    mapper = render.spt_mapper(level, seed=seed, stratified=stratified, per_pass=per_pass,
                               **estimator)
    return render.render(s.grid, s.property, mapper, s.view, (size, size))


def _curves(s: Scene, reference: np.ndarray, levels: Sequence[int], size: int,
            seed: int, progress: Progress) -> List[Dict[str, object]]:
    curves = []
    for label, stratified, per_pass, estimator in MODES:
        points = []
        for level in levels:
            rendering = _render(s, level, stratified, per_pass, size, seed, estimator)
            points.append({"repetitions": level, "seconds": rendering.seconds,
                           "rmse": metrics.rmse(rendering.image, reference)})
            progress.step(f"{label} L={level}")
        curves.append({"mode": label, "stratified": stratified, "per_pass": per_pass,
                       "points": points})
    return curves


def _plot(curves: List[Dict[str, object]], path: pathlib.Path, title: str) -> None:
    figure = plots.figure(10, 4.2)
    by_level, by_time = figure.add_subplot(1, 2, 1), figure.add_subplot(1, 2, 2)
    for curve in curves:
        levels = [p["repetitions"] for p in curve["points"]]
        errors = [p["rmse"] for p in curve["points"]]
        seconds = [p["seconds"] for p in curve["points"]]
        style = plots.line_style(len(by_level.lines))
        by_level.loglog(levels, errors, style, label=curve["mode"])
        by_time.loglog(seconds, errors, style, label=curve["mode"])
    for axes, xlabel in ((by_level, "RepetitionLevel"), (by_time, "render time [s]")):
        plots.finish_axes(axes, xlabel, "footprint RMSE against the exact reference")
    figure.suptitle(title)
    plots.save(figure, path)


def _repetitions_to_match(curve: Dict[str, object], target: float) -> object:
    """The fewest repetitions of ``curve`` whose error is at most ``target``, else None."""
    return next((p["repetitions"] for p in curve["points"] if p["rmse"] <= target), None)


def sampling_figure(dataset: str, levels: Sequence[int], size: int, output: pathlib.Path,
                    seed: int = 1) -> Dict[str, object]:
    """The sampling figure on one data set; returns the numbers it writes."""
    output.mkdir(parents=True, exist_ok=True)
    progress = Progress(3 + len(MODES) * len(levels), "sampling")
    s = scene(dataset)
    reference = render.reference(s.grid, s.property, s.view, (size, size)).image
    progress.step("reference")
    check_level = 64 if 64 in levels else levels[0]
    single = _render(s, check_level, False, 1, size, seed)
    progress.step(f"1 per pass, L={check_level}")
    several = _render(s, check_level, False, 16, size, seed)
    progress.step(f"16 per pass, L={check_level}")
    curves = _curves(s, reference, levels, size, seed, progress)
    paper, independent, stratified, default = curves
    target = independent["points"][-1]["rmse"]
    result = {
        "dataset": dataset, "size": size, "levels": list(levels), "curves": curves,
        "per_pass_check": {
            "repetitions": check_level, "seconds_1_per_pass": single.seconds,
            "seconds_16_per_pass": several.seconds,
            "speedup": single.seconds / several.seconds,
            "max_abs_difference": float(np.abs(single.image - several.image).max())},
        "independent_rmse_at_max": target,
        "stratified_repetitions_to_match": _repetitions_to_match(stratified, target),
        "default_repetitions_to_match": _repetitions_to_match(default, target),
    }
    rows = [[curve["mode"], point["repetitions"], point["rmse"], point["seconds"],
             paper_point["seconds"] / point["seconds"]]
            for curve in curves for paper_point, point in zip(paper["points"], curve["points"])]
    tables.write_table(output / "sampling.md", ["mode", "repetitions", "RMSE", "time [s]",
                                                "speed-up over the paper's mode"], rows)
    _plot(curves, output / "sampling.png", f"{dataset}, {size} x {size}")
    (output / "sampling.json").write_text(json.dumps(result, indent=2))
    return result
