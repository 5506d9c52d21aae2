"""The sweeps: cell count, repetition level, subpixel level and image size; and time to
quality on the real data sets, every method's error against the exact reference next to its
render time at several repetition levels."""

from __future__ import annotations

import pathlib
from typing import Dict, List, Sequence

from ... import metrics, render, scenes
from ...progress import Progress
from ...scenes import Scene
from .methods import METHODS, generated_scene, record, time_method
from .settings import Settings

Entry = Dict[str, object]

#: The methods of the repetition and subpixel sweeps.
REPETITION_METHODS = ("spt", "spt-visibility", "spt-paper", "pbvr")
#: The methods of the quality section; the paper's mode is measured up to paper_repetitions.
QUALITY_STOCHASTIC = ("spt", "spt-visibility", "spt-independent", "pbvr")
QUALITY_EXACT = ("havs2", "havs4", "havs6", "pt")


def wanted(settings: Settings, names: Sequence[str]) -> List[str]:
    """The methods of ``names`` that this run measures."""
    return [name for name in names if settings.wants(name)]


def sweep_level(settings: Settings, name: str) -> int:
    """The repetition level of ``name`` in the sweeps other than the repetition sweep."""
    return settings.paper_sweep_repetitions if name == "spt-paper" else settings.sweep_repetitions


def _entry(s: Scene, name: str, size: int, level: int, subpixels: int, settings: Settings,
           sweep: str, progress: Progress, point: str) -> Entry:
    """One point of a sweep: ``name``'s frames timed and recorded, the progress told."""
    timing = time_method(s, METHODS[name], size, level, subpixels, settings.frames)
    entry = record(s, METHODS[name], size, level, subpixels, timing, sweep=sweep)
    progress.step(f"{name} {point} {entry['seconds']:.2f} s")
    return entry


def sweep_cells(settings: Settings, progress: Progress) -> List[Entry]:
    """Every method at every cell count, the floor next to each; a method whose frame took
    longer than ``frame_limit`` stops there."""
    results: List[Entry] = []
    stopped = set()
    for cells in settings.cells:
        s = generated_scene(settings.shape, cells)
        for name in wanted(settings, settings.methods):
            if name in stopped:
                progress.step(f"{name} skipped")
                continue
            results.append(_entry(s, name, settings.size, sweep_level(settings, name), 1,
                                  settings, "cells", progress,
                                  f"{s.grid.GetNumberOfCells()} cells"))
            if results[-1]["seconds"] > settings.frame_limit:
                stopped.add(name)
    return results


def sweep_repetitions(settings: Settings, progress: Progress) -> List[Entry]:
    """SPT's modes and PBVR at every repetition level."""
    s = generated_scene(settings.shape, settings.sweep_cells)
    results = []
    for name in wanted(settings, REPETITION_METHODS):
        for level in settings.repetitions:
            if name == "spt-paper" and level > settings.paper_repetitions:
                progress.step(f"{name} L={level} skipped")
            else:
                results.append(_entry(s, name, settings.size, level, 1, settings,
                                      "repetitions", progress, f"L={level}"))
    return results


def sweep_subpixels(settings: Settings, progress: Progress) -> List[Entry]:
    """SPT's modes and PBVR at every subpixel level, at the smallest image size."""
    s = generated_scene(settings.shape, settings.sweep_cells)
    return [_entry(s, name, min(settings.sizes), sweep_level(settings, name), subpixels,
                   settings, "subpixels", progress, f"Ls={subpixels}")
            for name in wanted(settings, REPETITION_METHODS) for subpixels in settings.subpixels]


def sweep_image(settings: Settings, progress: Progress) -> List[Entry]:
    """Every method at every image size."""
    s = generated_scene(settings.shape, settings.sweep_cells)
    return [_entry(s, name, size, sweep_level(settings, name), 1, settings, "image", progress,
                   f"{size}^2")
            for size in settings.sizes for name in wanted(settings, settings.methods)]


def quality_steps(settings: Settings) -> int:
    """The progress steps of the quality section."""
    stochastic = len(wanted(settings, QUALITY_STOCHASTIC + ("spt-paper",)))
    return len(settings.quality_datasets) * (
        1 + stochastic * len(settings.quality_levels) + len(wanted(settings, QUALITY_EXACT)))


def _quality_entry(s: Scene, name: str, level: int, settings: Settings, reference,
                   output: pathlib.Path, progress: Progress) -> Entry:
    size = settings.quality_size
    timing = time_method(s, METHODS[name], size, level, 1, settings.frames, keep_image=True)
    entry = record(s, METHODS[name], size, level, 1, timing, sweep="quality")
    entry["rmse"] = metrics.rmse(timing.image, reference)
    metrics.write_png(output / f"quality_{s.name}_{name}_{level}.png", timing.image)
    progress.step(f"{s.name} {name} L={level} {timing.median:.2f} s")
    return entry


def quality(settings: Settings, progress: Progress, output: pathlib.Path) -> List[Entry]:
    """Image error against the exact reference and render time, for every method on the real
    data sets. The paper's mode draws the same image as 16 independent repetitions per pass
    (tested), so its error is that image's; only its time is measured separately, up to
    ``paper_repetitions``."""
    results = []
    size = settings.quality_size
    for name in settings.quality_datasets:
        s = scenes.scene(name)
        reference = render.reference(s.grid, s.property, s.view, (size, size)).image
        metrics.write_png(output / f"quality_{name}_reference.png", reference)
        progress.step(f"{name} reference")
        for level in settings.quality_levels:
            for method in wanted(settings, QUALITY_STOCHASTIC):
                results.append(_quality_entry(s, method, level, settings, reference, output,
                                              progress))
            if not settings.wants("spt-paper"):
                continue
            if level <= settings.paper_repetitions:
                results.append(_quality_entry(s, "spt-paper", level, settings, reference,
                                              output, progress))
            else:
                progress.step(f"{name} spt-paper L={level} skipped")
        for method in wanted(settings, QUALITY_EXACT):
            results.append(_quality_entry(s, method, 1, settings, reference, output, progress))
    return results
