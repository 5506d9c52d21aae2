"""Host time per frame: where an SPT frame's CPU time goes as the cell count grows, from
``perf`` samples, by thread and shared object."""

from __future__ import annotations

from typing import List

from ...tables import markdown
from .markdown import Results, Section, short_table


def summary(results: Results, folder: str) -> List[str]:
    host = results["host"]
    return ["Where an SPT frame's CPU time goes (`perf`): *host* is this project's library, "
            "VTK and Python on the application thread, the part a GPU would leave on the "
            "CPU; the rest is the software rasterizer.", "",
            short_table(["cells", "frame [s]", "host [ms]", "application thread [s]",
                         "llvmpipe workers [s]"],
                        [[f"{h['cells']:,}", h["frame_seconds"],
                          f"{1000.0 * h['host_seconds_per_frame']:.1f}",
                          h["application_thread_seconds_per_frame"],
                          h["worker_seconds_per_frame"]] for h in host])]


def full(results: Results) -> List[str]:
    host = results["host"]
    return ["## Host time per frame", "",
            "CPU seconds per SPT frame (16 repetitions), from `perf` samples of the timed "
            "frames, by thread and shared object. Host: this project's library, VTK and "
            "Python on the application thread, the part a real GPU leaves on the CPU. Kernel "
            "and C library: on that thread, mostly the memory that llvmpipe's vertex stage "
            "maps for every draw. The rest is the emulated GPU (llvmpipe's shaders and Mesa's "
            "driver on the application thread, the rasterizer threads).", "",
            markdown(["cells", "frame [s]", "host [s]", "SPT library [s]", "kernel + libc [s]",
                      "application thread [s]", "llvmpipe workers [s]"],
                     [[h["cells"], h["frame_seconds"], h["host_seconds_per_frame"],
                       h["project_seconds_per_frame"], h.get("system_seconds_per_frame", "-"),
                       h["application_thread_seconds_per_frame"],
                       h["worker_seconds_per_frame"]] for h in host])]


HOST = Section("Host time per frame", "host", summary, full, key="host")
