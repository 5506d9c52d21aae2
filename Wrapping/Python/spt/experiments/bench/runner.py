"""A benchmark run: the chosen sections, the models fitted to everything measured, the plots
and the reports (``bench.md``, every table; ``results.md``, the summary for readers)."""

from __future__ import annotations

import dataclasses
import datetime
import json
import os
import pathlib
from typing import Dict, List, Optional, Sequence

from ... import render
from ...progress import Progress
from . import camera, host, parallel, paraview_view, race, sweeps
from .crossovers import crossovers, floor_ratios
from .methods import METHODS, generated_scene, record, time_method
from .models import memory_models, predict_large, time_models
from .results import write_results
from .settings import SECTIONS, Settings

Entry = Dict[str, object]


def renderer_name(window) -> str:
    """The OpenGL renderer that draws ``window``."""
    for line in (window.ReportCapabilities() or "").splitlines():
        if line.startswith("OpenGL renderer string:"):
            return line.split(":", 1)[1].strip()
    return "unknown OpenGL renderer"


def machine() -> str:
    """The cores and the OpenGL renderer that draws this process's windows."""
    window, _ = render.make_window(8, 8)
    window.Render()
    renderer = renderer_name(window)
    window.Finalize()
    return f"{os.cpu_count()} cores, {renderer}"


def large_case(settings: Settings, progress: Progress) -> Entry:
    """The paper's large case: one frame (after a one-repetition warm-up)."""
    s = generated_scene(settings.shape, settings.large_cells)
    timing = time_method(s, METHODS["spt"], settings.large_size, settings.large_repetitions,
                         1, frames=1)
    entry = record(s, METHODS["spt"], settings.large_size, settings.large_repetitions, 1,
                   timing, sweep="large")
    progress.step(f"large {entry['cells']} cells {timing.median:.1f} s")
    return entry


def steps(settings: Settings, section: str) -> int:
    """The progress steps of one section."""
    methods = len(sweeps.wanted(settings, settings.methods))
    swept = len(sweeps.wanted(settings, sweeps.REPETITION_METHODS))
    return {
        "race": race.steps(settings),
        "camera": camera.steps(settings),
        "cells": len(settings.cells) * methods,
        "repetitions": swept * len(settings.repetitions),
        "subpixels": swept * len(settings.subpixels),
        "image": len(settings.sizes) * methods,
        "quality": sweeps.quality_steps(settings),
        "host": len(settings.host_cells),
        "large": 1,
        "parallel": parallel.steps(settings),
        "paraview": paraview_view.steps(settings),
    }[section]


SWEEPS = {"cells": sweeps.sweep_cells, "repetitions": sweeps.sweep_repetitions,
          "subpixels": sweeps.sweep_subpixels, "image": sweeps.sweep_image}


def _measure(sections: Sequence[str], settings: Settings, previous: Dict[str, object],
             output: pathlib.Path) -> Dict[str, object]:
    entries: List[Entry] = [
        e for e in previous.get("entries", [])
        if e.get("sweep") not in sections or not settings.wants(e.get("method", ""))]
    progress = Progress(sum(steps(settings, s) for s in sections), "bench")
    measured = {key: previous.get(key)
                for key in ("race", "race_sizes", "camera", "host", "large", "parallel",
                            "paraview")}
    for section in sections:
        if section in SWEEPS:
            entries += SWEEPS[section](settings, progress)
        elif section == "quality":
            entries += sweeps.quality(settings, progress, output)
        elif section == "race":
            earlier = [previous.get("race")] + list(previous.get("race_sizes") or [])
            measured["race"], *others = race.races(settings, progress, output / "race",
                                                   [r for r in earlier if r])
            measured["race_sizes"] = others
        elif section == "paraview":
            measured["paraview"] = paraview_view.paraview(
                settings, progress, output / "paraview", previous.get("paraview"))
        elif section == "camera":
            measured["camera"] = camera.camera_section(settings, progress)
        elif section == "host":
            measured["host"] = host.host_time(settings, progress)
        elif section == "parallel":
            measured["parallel"] = parallel.parallel(settings, progress, output / "parallel")
        else:
            measured["large"] = large_case(settings, progress)
    measured["entries"] = entries
    return measured


def run(output: pathlib.Path, sections: Sequence[str] = SECTIONS,
        settings: Optional[Settings] = None) -> Dict[str, object]:
    """Run the chosen sections and write ``bench.json``, the plots, ``bench.md`` and
    ``results.md`` into ``output``; returns the results. Earlier results in
    ``output/bench.json`` of sections not run now are kept, so a long run can be done
    section by section."""
    settings = settings or Settings()
    unknown = [s for s in sections if s not in SECTIONS]
    if unknown:
        raise ValueError(f"unknown section(s) {', '.join(unknown)}; choose from "
                         f"{', '.join(SECTIONS)}")
    output.mkdir(parents=True, exist_ok=True)
    previous: Dict[str, object] = {}
    if (output / "bench.json").exists():
        previous = json.loads((output / "bench.json").read_text())
    results = _measure(sections, settings, previous, output)
    entries = results["entries"]
    today = datetime.datetime.now(datetime.timezone.utc).date().isoformat()
    results.update(date=today, machine=machine(), load_average=list(os.getloadavg()),
                   cores=os.cpu_count(), shape=settings.shape, frames=settings.frames,
                   settings=dataclasses.asdict(settings), time_models=time_models(entries),
                   cpu_time_models=time_models(entries, "cpu_seconds"),
                   memory_models=memory_models(entries))
    if results["large"]:
        predict_large(results["large"], results["time_models"], results["cpu_time_models"],
                      results["memory_models"])
    results["crossovers"] = crossovers(entries, results["memory_models"])
    results["floor_ratios"] = floor_ratios(entries)
    (output / "bench.json").write_text(json.dumps(results, indent=1, default=dataclasses.asdict))
    write_results(output / "bench.json", output / "results.md", figures=True)
    return results
