"""The sweeps: cell count, repetition level, subpixel level and image size."""

from __future__ import annotations

from typing import Dict, List, Sequence

from ...progress import Progress
from ...scenes import Scene
from .methods import METHODS, generated_scene
from .settings import Settings
from .timing import record, time_method

#: The methods of the repetition and subpixel sweeps.
REPETITION_METHODS = ("spt", "spt-visibility", "spt-paper", "pbvr")


def wanted(settings: Settings, names: Sequence[str]) -> List[str]:
    """The methods of ``names`` that this run measures."""
    return [name for name in names if settings.wants(name)]


def sweep_level(settings: Settings, name: str) -> int:
    """The repetition level of ``name`` in the sweeps other than the repetition sweep."""
    return settings.paper_sweep_repetitions if name == "spt-paper" else settings.sweep_repetitions


def _entry(s: Scene, name: str, size: int, level: int, subpixels: int, settings: Settings,
           sweep: str) -> Dict[str, object]:
    """One point of a sweep: ``name``'s frames timed and recorded."""
    timing = time_method(s, METHODS[name], size, level, subpixels, settings.frames)
    return record(s, METHODS[name], size, level, subpixels, timing, sweep=sweep)


def sweep_cells(settings: Settings, progress: Progress) -> List[Dict[str, object]]:
    """Every method at every cell count, the floor next to each; a method whose frame took
    longer than ``frame_limit`` stops there."""
    results = []
    stopped = set()
    for cells in settings.cells:
        s = generated_scene(settings.shape, cells)
        for name in wanted(settings, settings.methods):
            if name in stopped:
                progress.step(f"{name} skipped")
                continue
            results.append(_entry(s, name, settings.size, sweep_level(settings, name), 1,
                                  settings, "cells"))
            if results[-1]["seconds"] > settings.frame_limit:
                stopped.add(name)
            progress.step(f"{name} {results[-1]['cells']} cells {results[-1]['seconds']:.2f} s")
    return results


def sweep_repetitions(settings: Settings, progress: Progress) -> List[Dict[str, object]]:
    """SPT's modes and PBVR at every repetition level."""
    s = generated_scene(settings.shape, settings.sweep_cells)
    results = []
    for name in wanted(settings, REPETITION_METHODS):
        for level in settings.repetitions:
            if name == "spt-paper" and level > settings.paper_repetitions:
                progress.step(f"{name} L={level} skipped")
                continue
            results.append(_entry(s, name, settings.size, level, 1, settings, "repetitions"))
            progress.step(f"{name} L={level} {results[-1]['seconds']:.2f} s")
    return results


def sweep_subpixels(settings: Settings, progress: Progress) -> List[Dict[str, object]]:
    """SPT's modes and PBVR at every subpixel level, at the smallest image size."""
    s = generated_scene(settings.shape, settings.sweep_cells)
    results = []
    for name in wanted(settings, REPETITION_METHODS):
        for subpixels in settings.subpixels:
            results.append(_entry(s, name, min(settings.sizes), sweep_level(settings, name),
                                  subpixels, settings, "subpixels"))
            progress.step(f"{name} Ls={subpixels} {results[-1]['seconds']:.2f} s")
    return results


def sweep_image(settings: Settings, progress: Progress) -> List[Dict[str, object]]:
    """Every method at every image size."""
    s = generated_scene(settings.shape, settings.sweep_cells)
    results = []
    for size in settings.sizes:
        for name in wanted(settings, settings.methods):
            results.append(_entry(s, name, size, sweep_level(settings, name), 1, settings,
                                  "image"))
            progress.step(f"{name} {size}^2 {results[-1]['seconds']:.2f} s")
    return results
