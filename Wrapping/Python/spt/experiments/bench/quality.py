"""Time to quality on the real data sets: every method's error against the exact reference
next to its render time, at several repetition levels."""

from __future__ import annotations

import pathlib
from typing import Dict, List

from ... import metrics, render, scenes
from ...progress import Progress
from .methods import METHODS
from .settings import Settings
from .sweeps import wanted
from .timing import record, time_method

STOCHASTIC = ("spt", "spt-visibility", "spt-independent", "pbvr")
EXACT = ("havs2", "havs4", "havs6", "pt")


def steps(settings: Settings) -> int:
    """The progress steps of the quality section."""
    stochastic = len(wanted(settings, STOCHASTIC + ("spt-paper",)))
    return len(settings.quality_datasets) * (
        1 + stochastic * len(settings.quality_levels) + len(wanted(settings, EXACT)))


def _measure(s: scenes.Scene, name: str, level: int, settings: Settings, reference,
             output: pathlib.Path, progress: Progress) -> Dict[str, object]:
    size = settings.quality_size
    timing = time_method(s, METHODS[name], size, level, 1, settings.frames, keep_image=True)
    entry = record(s, METHODS[name], size, level, 1, timing, sweep="quality")
    entry["rmse"] = metrics.rmse(timing.image, reference)
    metrics.write_png(output / f"quality_{s.name}_{name}_{level}.png", timing.image)
    progress.step(f"{s.name} {name} L={level} {timing.median:.2f} s")
    return entry


def quality(settings: Settings, progress: Progress, output: pathlib.Path
            ) -> List[Dict[str, object]]:
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
            for method in wanted(settings, STOCHASTIC):
                results.append(_measure(s, method, level, settings, reference, output,
                                        progress))
            if not settings.wants("spt-paper"):
                continue
            if level <= settings.paper_repetitions:
                results.append(_measure(s, "spt-paper", level, settings, reference, output,
                                        progress))
            else:
                progress.step(f"{name} spt-paper L={level} skipped")
        for method in wanted(settings, EXACT):
            results.append(_measure(s, method, 1, settings, reference, output, progress))
    return results
