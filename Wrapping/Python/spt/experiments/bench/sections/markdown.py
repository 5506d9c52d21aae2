"""What the sections' text shares: a section's description, numbers and tables as the
summaries print them, a sweep's entries, and a figure with its commands."""

from __future__ import annotations

import math
from typing import Callable, Dict, List, NamedTuple, Optional, Sequence, Tuple

from ...tables import format_value, markdown

Entry = Dict[str, object]
Results = Dict[str, object]
#: A figure: its file, its caption and the sections whose run draws it again.
Figure = Tuple[str, str, str]

#: The experiments' command line: they run from a build tree (an install does not hold them).
SPT = "build/bin/spt-python -m spt"
BENCH_COMMAND = SPT + " bench --sections {sections} --output out/bench"


class Section(NamedTuple):
    """A benchmark section in the two documents: the heading of its summary in
    ``results.md`` and the sections that measure it, the summary (no lines where the run did
    not measure it), its full tables in ``bench.md``, its figures by name, and the key of
    ``bench.json`` without which neither document has lines of it."""

    heading: str
    measure: str
    summary: Callable[[Results, str], List[str]]
    full: Callable[[Results], List[str]]
    figures: Dict[str, Figure] = {}
    key: str = ""

    def lines(self, results: Results, folder: Optional[str] = None) -> List[str]:
        """The summary (with ``folder``, where the figures are) or else the full tables."""
        if self.key and not results.get(self.key):
            return []
        return self.full(results) if folder is None else self.summary(results, folder)


def short(value: object) -> str:
    """A number as the summaries print it: three significant digits."""
    if isinstance(value, float) and math.isfinite(value):
        return f"{value:.3g}"
    return format_value(value)


def short_table(header: Sequence[str], rows: Sequence[Sequence[object]]) -> str:
    """A summary's Markdown table, its numbers as :func:`short` prints them."""
    return markdown(header, [[short(v) for v in row] for row in rows])


def swept(results: Results, sweep: str) -> List[Entry]:
    """The run's entries of one sweep."""
    return [e for e in results["entries"] if e.get("sweep") == sweep]


def figure(spec: Figure, folder: str) -> List[str]:
    """A figure, its caption and the commands that draw it and measure it again."""
    path, caption, sections = spec
    return [f"![{caption}]({folder}{path})", "",
            f"*Figure: {caption}.* Drawn from `bench.json` by `{SPT} report --figures`; "
            f"measured and drawn again by `{BENCH_COMMAND.format(sections=sections)}`.", ""]
