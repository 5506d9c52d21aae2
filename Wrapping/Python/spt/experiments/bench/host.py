"""Host time per frame: the CPU time of the application thread outside the OpenGL driver,
the part of a frame that a real GPU would leave on the CPU.

It is measured with ``perf`` samples of the timed frames, split by thread and shared object.
Where ``perf`` cannot profile this process, the CPU time of the application thread during the
frames (``time.thread_time``) stands in: it includes the driver's work on that thread, so it
is an upper bound.
"""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import tempfile
import time
from typing import Callable, Dict, List, Optional, Tuple

from ...progress import Progress
from .methods import FramesHook, METHODS, Timing, generated_scene, time_method
from .settings import Settings

#: Where the emulated GPU runs: llvmpipe's JIT-compiled shaders, Mesa's driver, and LLVM, the
#: driver's shader compiler (it compiles a shader variant on the application thread the first
#: time a draw needs it; a GPU's driver compiles its shaders on the host too).
GPU_OBJECTS = ("[JIT]", "swrast_dri.so", "libgallium", "libLLVM", "[unknown]")
#: The kernel and the C library: on the application thread, mostly the memory that llvmpipe's
#: vertex stage maps and fills for every draw.
SYSTEM_OBJECTS = ("[kernel", "libc.so")
#: Samples per second of CPU time.
FREQUENCY = 1999


def perf_available() -> bool:
    """Whether ``perf`` is installed and may profile this user's processes."""
    if shutil.which("perf") is None:
        return False
    probe = subprocess.run(["perf", "stat", "-e", "cpu-clock", "true"],
                           capture_output=True, text=True)
    return probe.returncode == 0


def perf_attach(path: str) -> FramesHook:
    """An ``on_frames`` hook of :func:`time_method`: perf samples this process (all its
    threads) while the timed frames run."""
    def start() -> Callable[[], None]:
        process = subprocess.Popen(
            ["perf", "record", "-e", "cpu-clock", "-F", str(FREQUENCY), "-p", str(os.getpid()),
             "-o", path, "--quiet"],
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        time.sleep(1.0)   # let perf attach to every thread

        def stop() -> None:
            process.send_signal(signal.SIGINT)
            process.wait(timeout=120)
        return stop
    return start


def perf_seconds_by_object(path: str) -> Dict[Tuple[str, str], float]:
    """Seconds of CPU per (thread name, shared object) in a perf recording."""
    report = subprocess.run(
        ["perf", "report", "-i", path, "--stdio", "--sort", "comm,dso", "-g", "none", "-n",
         "--percent-limit", "0"], capture_output=True, text=True, check=True).stdout
    seconds: Dict[Tuple[str, str], float] = {}
    for line in report.splitlines():
        fields = line.split()
        if len(fields) < 4 or line.startswith("#") or not fields[0].endswith("%"):
            continue
        samples, comm, dso = int(fields[1]), fields[2], " ".join(fields[3:])
        key = (comm, dso)
        seconds[key] = seconds.get(key, 0.0) + samples / FREQUENCY
    return seconds


def application_objects(by_object: Dict[Tuple[str, str], float]) -> Dict[str, float]:
    """CPU seconds per shared object of every thread but llvmpipe's rasterizer threads."""
    main: Dict[str, float] = {}
    for (comm, dso), t in by_object.items():
        if not comm.startswith("llvmpipe"):
            main[dso] = main.get(dso, 0.0) + t
    return main


def _is_host(dso: str) -> bool:
    """Whether time in ``dso`` on the application thread is host time (not the driver's)."""
    return not dso.startswith(GPU_OBJECTS + SYSTEM_OBJECTS)


def split_by_role(by_object: Dict[Tuple[str, str], float]) -> Dict[str, float]:
    """CPU seconds of a recording by role: ``host`` (this project, VTK and Python on the
    application thread), ``project`` (this project's library alone), ``system`` (kernel and
    C library on that thread), ``application_thread`` (all of it) and ``worker`` (the
    rasterizer threads)."""
    main = application_objects(by_object)
    return {
        "host": sum(t for dso, t in main.items() if _is_host(dso)),
        "project": sum(t for dso, t in main.items() if "SPTRendering" in dso),
        "system": sum(t for dso, t in main.items() if dso.startswith(SYSTEM_OBJECTS)),
        "application_thread": sum(main.values()),
        "worker": sum(t for (comm, _), t in by_object.items() if comm.startswith("llvmpipe")),
    }


def host_objects(by_object: Dict[Tuple[str, str], float], frames: int,
                 count: int = 3) -> Dict[str, float]:
    """The shared objects that the host time of a recording is spent in, the largest
    ``count``, in seconds per frame: where a row's host time went, when it stands out."""
    host = [(dso, t / frames) for dso, t in application_objects(by_object).items()
            if _is_host(dso)]
    return dict(sorted(host, key=lambda item: -item[1])[:count])


def timed_with_host(run: Callable[[Optional[FramesHook]], Timing], frames: int,
                    use_perf: bool) -> Tuple[Timing, float, str, Dict[str, float]]:
    """Run ``run(on_frames)`` (a :func:`time_method` call of ``frames`` frames) and return
    its timing, the host seconds per frame, how they were measured (``perf`` or
    ``thread_time``) and, with ``perf``, the shared objects they were spent in."""
    if not use_perf:
        timing = run(None)
        return timing, timing.thread_median, "thread_time", {}
    timing, by_object = profiled(run)
    return (timing, split_by_role(by_object)["host"] / frames, "perf",
            host_objects(by_object, frames))


def profiled(run: Callable[[Optional[FramesHook]], Timing]
             ) -> Tuple[Timing, Dict[Tuple[str, str], float]]:
    """``run(on_frames)`` with perf sampling the timed frames: its timing and the CPU seconds
    per (thread name, shared object)."""
    with tempfile.TemporaryDirectory() as directory:
        path = os.path.join(directory, "perf.data")
        timing = run(perf_attach(path))
        return timing, perf_seconds_by_object(path)


def host_time(settings: Settings, progress: Progress) -> List[Dict[str, object]]:
    """Per frame, the CPU seconds of the application thread by where they are spent, as the
    cell count grows: this project's library, VTK and Python (the host part a real GPU would
    leave on the CPU; a per-cell loop per frame would grow it), the kernel and the C library
    (on this thread mostly llvmpipe's vertex-stage memory), and the emulated GPU itself."""
    if not perf_available():
        progress.step("perf not available")
        return []
    results = []
    frames = max(settings.frames, 3)
    for cells in settings.host_cells:
        s = generated_scene(settings.shape, cells)
        timing, by_object = profiled(lambda hook: time_method(
            s, METHODS["spt"], settings.size, 16, 1, frames, on_frames=hook))
        main = application_objects(by_object)
        results.append({
            "scene": s.name, "cells": s.grid.GetNumberOfCells(), "frames": frames,
            "frame_seconds": timing.median,
            **{f"{role}_seconds_per_frame": seconds / frames
               for role, seconds in split_by_role(by_object).items()},
            "top_objects": sorted(((t / frames, dso) for dso, t in main.items()),
                                  reverse=True)[:8]})
        progress.step(f"host {cells} cells")
    return results
