"""The paper's figures on real data: scenes, convergence against repetitions, the influence of
visibility sorting, accuracy, and PBVR against SPT with a steep transfer function.

Every figure writes PNG images, a plot, a JSON file of the numbers and a Markdown table into
its output folder, and returns the numbers.
"""

from __future__ import annotations

import json
import math
import pathlib
from typing import Callable, Dict, List, Sequence

import numpy as np
from .. import data, metrics, render
from . import accuracy, plots, tables
from ..progress import Progress
from ..scenes import Scene, scene

PathLike = pathlib.Path


def compare(s: Scene, levels: Sequence[int], size: int, output: PathLike, seed: int,
            progress: Progress) -> Dict[str, object]:
    """Reference, VTK's projected tetrahedra and SPT at each repetition level on one scene:
    images, difference images, footprint RMSE and PSNR, and render times."""
    shape = (size, size)
    reference = render.reference(s.grid, s.property, s.view, shape)
    progress.step(f"{s.name} reference")
    pt = render.render(s.grid, s.property, render.projected_tetrahedra_mapper(), s.view, shape)
    progress.step(f"{s.name} VTK PT")
    metrics.write_png(output / f"{s.name}_reference.png", reference.image)
    metrics.write_png(output / f"{s.name}_vtk_pt.png", pt.image)
    result = {"dataset": s.name, "tetrahedra": s.grid.GetNumberOfCells(), "size": size,
              "reference_seconds": reference.seconds, "pt_seconds": pt.seconds,
              "pt_rmse": metrics.rmse(pt.image, reference.image),
              "pt_psnr": metrics.psnr(pt.image, reference.image), "levels": []}
    for level in levels:
        entry = {"repetitions": level}
        # The paper's sampling (the survivor estimator, independent thresholds), the survivor
        # estimator with stratified thresholds, and the mapper's default (the visibility
        # estimator with exact coverage, stratified); all drawn 16 repetitions per pass,
        # which gives the same images as one per pass.
        for mode, sampling in (("", render.PAPER_SAMPLING),
                               ("stratified_", render.STRATIFIED_SURVIVOR_SAMPLING),
                               ("default_", {})):
            mapper = render.spt_mapper(level, seed=seed, **sampling)
            spt = render.render(s.grid, s.property, mapper, s.view, shape)
            metrics.write_png(output / f"{s.name}_spt_{mode}{level}.png", spt.image)
            metrics.write_png(output / f"{s.name}_spt_{mode}{level}_difference.png",
                              metrics.difference_image(spt.image, reference.image))
            entry.update({f"{mode}rmse": metrics.rmse(spt.image, reference.image),
                          f"{mode}psnr": metrics.psnr(spt.image, reference.image),
                          f"{mode}seconds": spt.seconds})
            progress.step(f"{s.name} SPT {mode}L={level}")
        result["levels"].append(entry)
    return result


def _plot_convergence(results: List[Dict[str, object]], path: PathLike) -> None:
    figure = plots.figure(6.5, 4.5)
    axes = figure.add_subplot()
    for index, result in enumerate(results):
        color = f"C{index}"
        levels = [entry["repetitions"] for entry in result["levels"]]
        errors = [entry["rmse"] for entry in result["levels"]]
        axes.loglog(levels, errors, "o-", color=color,
                    label=f"{result['dataset']} SPT, paper's sampling")
        stratified = [entry["stratified_rmse"] for entry in result["levels"]]
        axes.loglog(levels, stratified, "s-.", color=color,
                    label=f"{result['dataset']} SPT, survivor stratified")
        default = [entry["default_rmse"] for entry in result["levels"]]
        axes.loglog(levels, default, "^-", color=color, linewidth=2.0,
                    label=f"{result['dataset']} SPT default (visibility, exact coverage)")
        axes.axhline(result["pt_rmse"], color=color, linestyle=":",
                     label=f"{result['dataset']} VTK PT")
        guide = errors[0] * np.sqrt(levels[0] / np.asarray(levels, dtype=float))
        axes.loglog(levels, guide, "--", color=color, alpha=0.35)
    plots.finish_axes(axes, "RepetitionLevel", "footprint RMSE against the reference",
                      "SPT convergence (dashed: 1/sqrt(L) from the first level)")
    plots.save(figure, path)


def convergence(datasets: Sequence[str], levels: Sequence[int], size: int,
                output: PathLike, seed: int = 0) -> List[Dict[str, object]]:
    """The convergence figure: RMSE of SPT against the reference per repetition level, next to
    VTK's projected tetrahedra, for each data set."""
    output.mkdir(parents=True, exist_ok=True)
    progress = Progress(len(datasets) * (2 + 3 * len(levels)), "convergence")
    results = [compare(scene(name), levels, size, output, seed, progress) for name in datasets]
    _plot_convergence(results, output / "convergence.png")
    (output / "convergence.json").write_text(json.dumps(results, indent=2))
    rows = []
    for result in results:
        for entry in result["levels"]:
            for mode, label in (("", "SPT paper"), ("stratified_", "SPT survivor stratified"),
                                ("default_", "SPT default")):
                rows.append([result["dataset"], f"{label} L={entry['repetitions']}",
                             entry[f"{mode}rmse"], entry[f"{mode}psnr"], entry[f"{mode}seconds"],
                             entry[f"{mode}seconds"] / result["pt_seconds"]])
        rows.append([result["dataset"], "VTK PT", result["pt_rmse"], result["pt_psnr"],
                     result["pt_seconds"], 1.0])
        rows.append([result["dataset"], "reference", 0.0, math.inf, result["reference_seconds"],
                     result["reference_seconds"] / result["pt_seconds"]])
    tables.write_table(output / "convergence.md",
                       ["data set", "method", "RMSE", "PSNR [dB]", "time [s]", "time / VTK PT"],
                       rows)
    return results


def _sorting_methods(repetitions: int, seed: int) -> List[tuple]:
    """(file key, label, mapper factory) of the sorting figure's methods."""
    return [
        ("spt", f"SPT L={repetitions}", lambda: render.spt_mapper(repetitions, seed=seed)),
        ("havs_k2", "HAVS-like k=2", lambda: render.havs_mapper(2)),
        ("havs_k6", "HAVS-like k=6", lambda: render.havs_mapper(6)),
        ("vtk_pt", "VTK PT", render.projected_tetrahedra_mapper),
    ]


def sorting_scene(s: Scene, size: int, output: PathLike, repetitions: int, seed: int,
                  progress: Progress) -> Dict[str, object]:
    """One scene of the sorting figure: the reference, SPT, HAVS-like with k = 2 and 6 and
    VTK's projected tetrahedra, each with its difference image, error and render time."""
    shape = (size, size)
    reference = render.reference(s.grid, s.property, s.view, shape)
    metrics.write_png(output / f"{s.name}_reference.png", reference.image)
    progress.step(f"{s.name} reference")
    result = {"dataset": s.name, "tetrahedra": s.grid.GetNumberOfCells(), "size": size,
              "reference_seconds": reference.seconds, "methods": []}
    images, differences, labels = [reference.image], [], ["reference"]
    for key, label, make in _sorting_methods(repetitions, seed):
        rendering = render.render(s.grid, s.property, make(), s.view, shape)
        difference = metrics.difference_image(rendering.image, reference.image)
        metrics.write_png(output / f"{s.name}_{key}.png", rendering.image)
        metrics.write_png(output / f"{s.name}_{key}_difference.png", difference)
        entry = {"method": label, "key": key,
                 "rmse": metrics.rmse(rendering.image, reference.image),
                 "psnr": metrics.psnr(rendering.image, reference.image),
                 "seconds": rendering.seconds}
        if key.startswith("havs"):
            entry["sort_seconds"] = rendering.mapper.GetLastSortTime()
            entry["gpu_seconds"] = rendering.mapper.GetLastGPUTime()
        result["methods"].append(entry)
        images.append(rendering.image)
        differences.append(difference)
        labels.append(label)
        progress.step(f"{s.name} {label}")
    top = metrics.side_by_side(images, labels)
    bottom = metrics.side_by_side([np.zeros_like(differences[0])] + differences,
                                  [""] + [f"|{label} - ref| x4" for label in labels[1:]])
    width = max(top.shape[1], bottom.shape[1])  # the two rows, 4 pixels apart
    metrics.write_png(output / f"{s.name}_comparison.png", np.concatenate(
        [np.pad(row, ((0, 4), (0, width - row.shape[1]), (0, 0))) for row in (top, bottom)]))
    return result


SORTING_HEADER = ["data set", "method", "RMSE", "PSNR [dB]", "time [s]", "sort [s]", "GPU [s]"]


def sorting(datasets: Sequence[str], size: int, output: PathLike, repetitions: int = 144,
            seed: int = 0) -> List[List[object]]:
    """The paper's "influence of visibility sorting" figure: per data set, the reference, SPT
    (no sorting), HAVS-like (sorted, k = 2 and 6) and VTK's projected tetrahedra (cell-centre
    sort), with difference images, footprint RMSE and PSNR and render times from one run.
    Writes PNGs, sorting.md and sorting.json into ``output``; returns the table rows."""
    output.mkdir(parents=True, exist_ok=True)
    progress = Progress(len(datasets) * (1 + len(_sorting_methods(repetitions, seed))),
                        "sorting")
    results = [sorting_scene(scene(name), size, output, repetitions, seed, progress)
               for name in datasets]
    (output / "sorting.json").write_text(json.dumps(results, indent=2))
    rows = []
    for result in results:
        for entry in result["methods"]:
            rows.append([result["dataset"], entry["method"], entry["rmse"], entry["psnr"],
                         entry["seconds"], entry.get("sort_seconds", ""),
                         entry.get("gpu_seconds", "")])
        rows.append([result["dataset"], "reference", 0.0, math.inf,
                     result["reference_seconds"], "", ""])
    tables.write_table(output / "sorting.md", SORTING_HEADER, rows)
    return rows


def _steep_scene(name: str, center: float, view: render.View) -> Callable[[], Scene]:
    def make() -> Scene:
        grid = data.load(name)
        return Scene(name, grid, data.transfer_function(grid, "steep", steep_center=center), view)
    return make


#: Scenes of the PBVR figure, with the "steep" preset: opacity rising from 0 to 0.9 and back
#: within 10 % of the scalar range ("varies precipitously"). Oxygen Post keeps the preset's
#: peak at 65 % of its velocity range (the post's wake, seen from above); on Blunt Fin only a
#: sliver of the fin's nose has densities there, so its peak is at 30 % (a thin shell of the
#: flow around the fin).
STEEP_SCENES: Dict[str, Callable[[], Scene]] = {
    "bluntfin": _steep_scene("bluntfin", 0.3, render.View(azimuth=40.0, elevation=25.0)),
    "post": _steep_scene("post", 0.65, render.View(azimuth=30.0, elevation=70.0, zoom=1.8)),
    "spx": _steep_scene("spx", 0.65, render.View(azimuth=30.0, elevation=30.0)),
    "default": _steep_scene("default", 0.5, render.View(azimuth=30.0, elevation=30.0)),
}

#: The methods of the PBVR figure: (label, file stem, mapper for a repetition level and seed).
#: SPT as users get it (the defaults) and as the paper samples (the survivor estimator with
#: independent thresholds, the Monte Carlo sampling that PBVR's independent particle sets also
#: have).
PBVR_METHODS = [
    ("SPT", "spt", lambda level, seed: render.spt_mapper(level, seed=seed)),
    ("SPT, paper's sampling", "spt_independent",
     lambda level, seed: render.spt_mapper(level, seed=seed, **render.PAPER_SAMPLING)),
    ("PBVR", "pbvr", lambda level, seed: render.pbvr_mapper(level, seed=seed)),
    ("PBVR, cell average", "pbvr_cell_average",
     lambda level, seed: render.pbvr_mapper(level, seed=seed, cell_average=True)),
]


def _method_entry(rendering: render.Rendering, reference: np.ndarray, level: int
                  ) -> Dict[str, object]:
    entry: Dict[str, object] = {
        "repetitions": level, "rmse": metrics.rmse(rendering.image, reference),
        "psnr": metrics.psnr(rendering.image, reference),
        "pixels_off": metrics.fraction_off(rendering.image, reference),
        "seconds": rendering.seconds}
    entry.update(rendering.report)
    if rendering.report.get("generation_seconds"):
        entry["particles_per_second"] = (rendering.report["particles"]
                                         / rendering.report["generation_seconds"])
    return entry


def pbvr_compare(s: Scene, repetitions: int, levels: Sequence[int], size: int,
                 output: PathLike, seed: int, progress: Progress) -> Dict[str, object]:
    """The reference and every method of PBVR_METHODS on one scene: images and difference
    images at `repetitions`, and the RMSE at every level of `levels` (which gets `repetitions`
    added) for the convergence curves."""
    shape = (size, size)
    levels = sorted(set(levels) | {repetitions})
    reference = render.reference(s.grid, s.property, s.view, shape)
    metrics.write_png(output / f"{s.name}_reference.png", reference.image)
    progress.step(f"{s.name} reference")
    result: Dict[str, object] = {
        "dataset": s.name, "tetrahedra": s.grid.GetNumberOfCells(), "size": size,
        "repetitions": repetitions, "reference_seconds": reference.seconds, "methods": {}}
    images = [reference.image]
    differences = []
    for label, stem, make in PBVR_METHODS:
        entries = []
        for level in levels:
            rendering = render.render(s.grid, s.property, make(level, seed), s.view, shape)
            entries.append(_method_entry(rendering, reference.image, level))
            progress.step(f"{s.name} {label} L={level}")
            if level == repetitions:
                difference = metrics.difference_image(rendering.image, reference.image)
                metrics.write_png(output / f"{s.name}_{stem}_{level}.png", rendering.image)
                metrics.write_png(output / f"{s.name}_{stem}_{level}_difference.png", difference)
                images.append(rendering.image)
                differences.append(difference)
        result["methods"][label] = entries
    short = [label.replace(", cell average", " cell avg.").replace(
        ", paper's sampling", " paper") for label, _, _ in PBVR_METHODS]
    labels = (["reference"] + [f"{label}, L={repetitions}" for label in short]
              + [f"|{label} - ref.| x4" for label in short])
    metrics.write_png(output / f"{s.name}_comparison.png",
                      metrics.side_by_side(images + differences, labels))
    return result


PBVR_TABLE_HEADER = ["data set", "method", "RMSE", "PSNR [dB]", "pixels off > 0.05",
                     "render [s]", "particles", "GPU memory [MiB]", "generation [s]",
                     "particles / s"]


def _pbvr_rows(result: Dict[str, object]) -> List[List[object]]:
    rows: List[List[object]] = [[result["dataset"], "reference (exact ray caster)", 0.0,
                                 math.inf, 0.0, result["reference_seconds"], "-", "-", "-", "-"]]
    for label, entries in result["methods"].items():
        entry = next(e for e in entries if e["repetitions"] == result["repetitions"])
        particles = entry.get("particles")
        rows.append([result["dataset"], f"{label}, L={entry['repetitions']}", entry["rmse"],
                     entry["psnr"], entry["pixels_off"], entry["seconds"],
                     int(particles) if particles is not None else "-",
                     entry["gpu_memory"] / 2.0 ** 20,
                     entry.get("generation_seconds", "-"),
                     entry.get("particles_per_second", "-")])
    return rows


def _plot_pbvr_convergence(results: List[Dict[str, object]], path: PathLike) -> None:
    figure = plots.figure(5.0 * len(results), 4.2)
    for index, result in enumerate(results):
        axes = figure.add_subplot(1, len(results), index + 1)
        for number, (label, entries) in enumerate(result["methods"].items()):
            levels = np.asarray([e["repetitions"] for e in entries], dtype=float)
            errors = [e["rmse"] for e in entries]
            axes.loglog(levels, errors, plots.line_style(number), color=f"C{number}",
                        label=label, markersize=5)
            axes.loglog(levels, errors[0] * np.sqrt(levels[0] / levels), "--",
                        color=f"C{number}", alpha=0.3)
        plots.finish_axes(axes, "RepetitionLevel", "footprint RMSE against the reference",
                          f"{result['dataset']}, steep transfer function (faint: 1/sqrt(L))")
    plots.save(figure, path)


def pbvr_figure(datasets: Sequence[str], repetitions: int, levels: Sequence[int], size: int,
                output: PathLike, seed: int = 0) -> List[List[object]]:
    """The "PBVR vs. SPT" figure: for each data set with a steep transfer function, the
    reference, SPT (the defaults and the paper's sampling), PBVR and PBVR with cell-average
    density at `repetitions`: images,
    difference images, RMSE, render times, particles, memory (pbvr.md); and the convergence
    of all three against the repetition level (pbvr_convergence.png / .md). Returns the rows of
    the main table."""
    output.mkdir(parents=True, exist_ok=True)
    for name in datasets:
        if name not in STEEP_SCENES:
            raise ValueError(f"unknown data set '{name}'; choose from {', '.join(STEEP_SCENES)}")
    count = len(set(levels) | {repetitions})
    progress = Progress(len(datasets) * (1 + len(PBVR_METHODS) * count), "pbvr")
    results = [pbvr_compare(STEEP_SCENES[name](), repetitions, levels, size, output, seed,
                            progress) for name in datasets]
    (output / "pbvr.json").write_text(json.dumps(results, indent=2))
    rows = [row for result in results for row in _pbvr_rows(result)]
    tables.write_table(output / "pbvr.md", PBVR_TABLE_HEADER, rows)
    _plot_pbvr_convergence(results, output / "pbvr_convergence.png")
    curves = [[result["dataset"], label] + [e["rmse"] for e in entries]
              for result in results for label, entries in result["methods"].items()]
    level_list = [e["repetitions"] for e in results[0]["methods"]["SPT"]] if results else []
    tables.write_table(output / "pbvr_convergence.md",
                       ["data set", "method"] + [f"L={level}" for level in level_list], curves)
    return rows


def accuracy_figure(output: PathLike, n_rays: int = 1000, seed: int = 2009) -> Dict[str, object]:
    """The paper's "accuracy of stochastic volume rendering" along one ray."""
    output.mkdir(parents=True, exist_ok=True)
    result = accuracy.run(n_rays=n_rays, seed=seed,
                          progress=Progress(len(accuracy.DEFAULT_LEVELS), "accuracy"))
    accuracy.plot(result, output / "accuracy.png")
    serializable = {k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in result.items()}
    (output / "accuracy.json").write_text(json.dumps(serializable, indent=2))
    return result
