"""The sweeps: cell count, repetition level, subpixel level and image size."""

from __future__ import annotations

from typing import Dict, List, Sequence

from ...progress import Progress
from .methods import METHODS
from .methods import generated_scene
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
            repetitions = sweep_level(settings, name)
            timing = time_method(s, METHODS[name], settings.size, repetitions, 1,
                                 settings.frames)
            results.append(record(s, METHODS[name], settings.size, repetitions, 1, timing,
                                  sweep="cells"))
            if timing.median > settings.frame_limit:
                stopped.add(name)
            progress.step(f"{name} {s.grid.GetNumberOfCells()} cells {timing.median:.2f} s")
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
            timing = time_method(s, METHODS[name], settings.size, level, 1, settings.frames)
            results.append(record(s, METHODS[name], settings.size, level, 1, timing,
                                  sweep="repetitions"))
            progress.step(f"{name} L={level} {timing.median:.2f} s")
    return results


def sweep_subpixels(settings: Settings, progress: Progress) -> List[Dict[str, object]]:
    """SPT's modes and PBVR at every subpixel level, at the smallest image size."""
    s = generated_scene(settings.shape, settings.sweep_cells)
    size = min(settings.sizes)
    results = []
    for name in wanted(settings, REPETITION_METHODS):
        level = sweep_level(settings, name)
        for subpixels in settings.subpixels:
            timing = time_method(s, METHODS[name], size, level, subpixels, settings.frames)
            results.append(record(s, METHODS[name], size, level, subpixels, timing,
                                  sweep="subpixels"))
            progress.step(f"{name} Ls={subpixels} {timing.median:.2f} s")
    return results


def sweep_image(settings: Settings, progress: Progress) -> List[Dict[str, object]]:
    """Every method at every image size."""
    s = generated_scene(settings.shape, settings.sweep_cells)
    results = []
    for size in settings.sizes:
        for name in wanted(settings, settings.methods):
            level = sweep_level(settings, name)
            timing = time_method(s, METHODS[name], size, level, 1, settings.frames)
            results.append(record(s, METHODS[name], size, level, 1, timing, sweep="image"))
            progress.step(f"{name} {size}^2 {timing.median:.2f} s")
    return results
