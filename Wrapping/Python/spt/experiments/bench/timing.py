"""Timing one configuration: frames after a warm-up, the pipeline finished after each."""

from __future__ import annotations

import dataclasses
import time
from typing import Callable, Dict, List, Optional

import numpy as np
from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper

from ... import render
from ...scenes import Scene
from .methods import Method, face_polydata

#: Called right before the timed frames; returns what to call right after them.
FramesHook = Callable[[], Callable[[], None]]


@dataclasses.dataclass
class Timing:
    """The frames of one configuration: every frame's wall seconds, the CPU seconds of the
    whole process and of the application thread alone, what the mapper reported, and the
    image of the last frame."""

    seconds: List[float]
    report: Dict[str, float]
    image: Optional[np.ndarray] = None
    cpu_seconds: List[float] = dataclasses.field(default_factory=list)
    thread_seconds: List[float] = dataclasses.field(default_factory=list)

    @property
    def median(self) -> float:
        return float(np.median(self.seconds))

    @property
    def cpu_median(self) -> float:
        return float(np.median(self.cpu_seconds)) if self.cpu_seconds else float("nan")

    @property
    def thread_median(self) -> float:
        return float(np.median(self.thread_seconds)) if self.thread_seconds else float("nan")


def _add_floor(renderer, s: Scene) -> None:
    mapper = vtkPolyDataMapper()
    mapper.SetInputData(face_polydata(s.grid))
    mapper.ScalarVisibilityOff()
    actor = vtkActor()
    actor.SetMapper(mapper)
    renderer.AddActor(actor)


def timed_frames(window, frames: int) -> Timing:
    """``frames`` frames, each finished, timed in wall, process and thread time."""
    seconds, cpu_seconds, thread_seconds = [], [], []
    for _ in range(frames):
        start, cpu_start = time.perf_counter(), time.process_time()
        thread_start = time.thread_time()
        window.Render()
        window.WaitForCompletion()
        seconds.append(time.perf_counter() - start)
        cpu_seconds.append(time.process_time() - cpu_start)
        thread_seconds.append(time.thread_time() - thread_start)
    return Timing(seconds, {}, None, cpu_seconds, thread_seconds)


def time_method(s: Scene, method: Method, size: int, repetitions: int = 16,
                subpixels: int = 1, frames: int = 3, keep_image: bool = False,
                on_frames: Optional[FramesHook] = None) -> Timing:
    """Render ``s`` with ``method`` ``frames`` times after one untimed frame; every frame
    does the whole work (SPT's progressive refinement is off). ``on_frames``, if given, is
    called right before the timed frames and returns what to call right after them (the
    host-time profiler uses it)."""
    window, renderer = render.make_window(size, size)
    volume_mapper = None
    if method.make is None:
        _add_floor(renderer, s)
    else:
        volume_mapper = method.make(repetitions, subpixels)
        render.add_volume(renderer, s.grid, s.property, volume_mapper)
    render.place_camera(renderer, s.grid.GetBounds(), s.view)
    if volume_mapper is not None:
        render.warm_up(window, volume_mapper)
    else:
        window.Render()
        window.WaitForCompletion()
    finish = on_frames() if on_frames is not None else None
    timing = timed_frames(window, frames)
    if finish is not None:
        finish()
    if volume_mapper is not None:
        timing.report = render.mapper_report(volume_mapper)
        if hasattr(volume_mapper, "GetLastSortTime"):
            timing.report["sort_seconds"] = volume_mapper.GetLastSortTime()
        if hasattr(volume_mapper, "GetLastRepetitionCount"):
            timing.report["repetitions_drawn"] = float(volume_mapper.GetLastRepetitionCount())
    timing.image = render.read_rgba(window) if keep_image else None
    renderer.RemoveAllViewProps()
    window.Finalize()
    return timing


def record(s: Scene, method: Method, size: int, repetitions: int, subpixels: int,
           timing: Timing, **extra) -> Dict[str, object]:
    """One entry of the results: the configuration, the median times, what the mapper
    reported, and ``extra``."""
    entry: Dict[str, object] = {
        "scene": s.name, "method": method.name, "cells": s.grid.GetNumberOfCells(),
        "points": s.grid.GetNumberOfPoints(), "width": size, "height": size,
        "repetitions": repetitions if method.stochastic else 1,
        "subpixels": subpixels if method.name.startswith(("spt", "pbvr")) else 1,
        "seconds": timing.median, "frames": timing.seconds,
        "cpu_seconds": timing.cpu_median}
    entry.update(timing.report)
    entry.update(extra)
    return entry
