"""Progress of long commands on standard error."""

from __future__ import annotations

import sys
import time


class Progress:
    """A progress bar on standard error: redrawn in place on a terminal, one line per step
    otherwise (logs)."""

    def __init__(self, total: int, title: str, stream=sys.stderr) -> None:
        self.total = max(total, 1)
        self.done = 0
        self.title = title
        self.stream = stream
        self.start = time.perf_counter()
        self.tty = hasattr(stream, "isatty") and stream.isatty()

    @staticmethod
    def silent() -> "Progress":
        """A progress that counts its steps and shows nothing (for library calls)."""
        return Progress(1, "", stream=None)

    def step(self, label: str) -> None:
        self.done += 1
        if self.stream is None:
            return
        elapsed = time.perf_counter() - self.start
        remaining = elapsed / self.done * (self.total - self.done)
        filled = int(30 * self.done / self.total)
        bar = "#" * filled + "." * (30 - filled)
        text = (f"{self.title} [{bar}] {self.done}/{self.total} {label} "
                f"({elapsed:.0f} s, ~{remaining:.0f} s left)")
        if self.tty:
            self.stream.write("\r" + text[:160].ljust(160))
            if self.done == self.total:
                self.stream.write("\n")
        else:
            self.stream.write(text + "\n")
        self.stream.flush()
