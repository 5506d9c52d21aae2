"""The benchmark's plots, in the style of :mod:`spt.experiments.plots`."""

from __future__ import annotations

import math
import pathlib
from typing import Dict, Sequence

import numpy as np

from .. import plots
from .methods import METHODS, label
from .models import time_key
from .race import STOCHASTIC_METHODS

Entry = Dict[str, object]


def plot_sweep(entries: Sequence[Entry], sweep: str, x_key: str, xlabel: str,
               path: pathlib.Path) -> None:
    """Time and GPU memory of every method along one sweep."""
    chosen = [e for e in entries if e.get("sweep") == sweep]
    if not chosen:
        return
    key = time_key(chosen)
    figure = plots.figure(10, 4.2)
    axes_time, axes_memory = figure.add_subplot(1, 2, 1), figure.add_subplot(1, 2, 2)
    for index, name in enumerate(METHODS):
        points = sorted((e for e in chosen if e["method"] == name), key=lambda e: e[x_key])
        if not points:
            continue
        x = [e[x_key] if x_key != "width" else e["width"] * e["height"] for e in points]
        style = plots.line_style(index)
        axes_time.loglog(x, [e[key] for e in points], style, label=label(name))
        memory = [(xx, e["gpu_memory"]) for xx, e in zip(x, points) if e.get("gpu_memory")]
        if memory:
            axes_memory.loglog(*zip(*memory), style, label=label(name))
    unit = "CPU seconds (all threads)" if key == "cpu_seconds" else "seconds"
    plots.finish_axes(axes_time, xlabel, f"{unit} per frame")
    plots.finish_axes(axes_memory, xlabel, "GPU bytes the mapper reports", legend=False)
    plots.save(figure, path)


def plot_residuals(models: Dict[str, Entry], path: pathlib.Path, unit: str) -> None:
    """The relative residuals of every fitted model (as bench.json holds them)."""
    if not models:
        return
    columns = min(4, len(models))
    rows = math.ceil(len(models) / columns)
    figure = plots.figure(3.2 * columns, 2.8 * rows)
    for index, (name, model) in enumerate(models.items()):
        axes = figure.add_subplot(rows, columns, index + 1)
        observed, predicted = np.array(model["observed"]), np.array(model["predicted"])
        axes.semilogx(predicted, (observed - predicted) / observed, "o", markersize=3)
        axes.axhline(0.0, color="gray", linewidth=0.8)
        plots.finish_axes(axes, f"predicted [{unit}]", "relative residual",
                          f"{name} (R^2 {model['r2']:.3f})", legend=False)
    plots.save(figure, path)


def _error_against_time(axes, points: Sequence[Entry], methods: Sequence[str],
                        stochastic: Sequence[str], key: str) -> None:
    """One scene's panel; each method keeps its color (its place in ``methods``) in every
    panel, whichever methods the scene has."""
    for name in stochastic:
        curve = sorted((e for e in points if e["method"] == name), key=lambda e: e[key])
        if curve:
            index = methods.index(name)
            axes.loglog([e[key] for e in curve], [e["rmse"] for e in curve],
                        plots.line_style(index), color=f"C{index % 10}", markersize=4,
                        label=curve[0].get("label", label(name)))
    for e in points:
        if e["method"] not in stochastic:
            index = methods.index(e["method"])
            axes.loglog([e[key]], [e["rmse"]], "s", color=f"C{index % 10}", markersize=6,
                        label=e.get("label", label(e["method"])))


def plot_error_against_time(entries: Sequence[Entry], path: pathlib.Path,
                            stochastic: Sequence[str], key: str = "") -> None:
    """Per scene, each method's error against its frame time: curves for the stochastic
    methods, single points for the others."""
    scenes = list(dict.fromkeys(e["scene"] for e in entries))
    if not scenes:
        return
    key = key or time_key(entries)
    methods = list(stochastic) + [m for m in dict.fromkeys(e["method"] for e in entries)
                                  if m not in stochastic]
    figure = plots.figure(4.2 * len(scenes), 4.8)
    for index, scene in enumerate(scenes):
        axes = figure.add_subplot(1, len(scenes), index + 1)
        _error_against_time(axes, [e for e in entries if e["scene"] == scene], methods,
                            stochastic, key)
        plots.finish_axes(axes, "CPU seconds per frame, all threads" if key == "cpu_seconds"
                          else "frame time [s]", "RMSE against the exact reference", scene,
                          legend=False)
    # One legend under the panels (inside them it hid the lowest curves), of every method.
    legend = {}
    for axes in figure.axes:
        for handle, text in zip(*axes.get_legend_handles_labels()):
            legend.setdefault(text, handle)
    figure.legend(list(legend.values()), list(legend), loc="lower center", ncol=4,
                  fontsize=plots.LEGEND_FONT_SIZE)
    figure.tight_layout(rect=(0.0, 0.12, 1.0, 1.0))
    figure.savefig(str(path), dpi=plots.DPI)


def plot_results(results: Dict[str, object], output: pathlib.Path) -> None:
    """Draw the benchmark's figures from its results into ``output``."""
    entries = results["entries"]
    for sweep, x_key, xlabel in (("cells", "cells", "tetrahedra"),
                                 ("repetitions", "repetitions", "RepetitionLevel"),
                                 ("subpixels", "subpixels", "SubpixelLevel"),
                                 ("image", "width", "pixels")):
        plot_sweep(entries, sweep, x_key, xlabel, output / f"{sweep}.png")
    for kind, unit in (("time", "ms"), ("cpu_time", "ms"), ("memory", "bytes")):
        plot_residuals(results[f"{kind}_models"], output / f"{kind}_residuals.png", unit)
    plot_error_against_time(
        [e for e in entries if e.get("sweep") == "quality" and "rmse" in e],
        output / "quality.png", ("spt-visibility", "spt", "spt-independent", "spt-paper", "pbvr"))
    if results.get("race"):
        plot_error_against_time(results["race"]["rows"], output / "race.png",
                                [m.name for m in STOCHASTIC_METHODS], key="seconds")
