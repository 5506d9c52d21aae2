"""Tables of results as Markdown files, and numbers as the tables print them."""

import math
import pathlib
from typing import Iterable, Sequence


def format_value(value: object) -> str:
    """A table cell: floats to four significant digits, infinity as "inf"."""
    if isinstance(value, float):
        return "inf" if math.isinf(value) else f"{value:.4g}"
    return str(value)


def markdown(header: Sequence[str], rows: Iterable[Sequence[object]]) -> str:
    """``rows`` under ``header`` as a Markdown table."""
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for row in rows:
        lines.append("| " + " | ".join(format_value(v) for v in row) + " |")
    return "\n".join(lines) + "\n"


def write_table(path: pathlib.Path, header: Sequence[str],
                rows: Iterable[Sequence[object]]) -> None:
    """Write ``rows`` under ``header`` as a Markdown table to ``path``."""
    path.write_text(markdown(header, rows))


def print_table(header: Sequence[str], rows: Sequence[Sequence[object]]) -> None:
    """``rows`` under ``header`` as aligned columns on standard output."""
    cells = [list(header)] + [[format_value(v) for v in row] for row in rows]
    widths = [max(len(row[i]) for row in cells) for i in range(len(header))]
    for index, row in enumerate(cells):
        print("  ".join(value.ljust(width) for value, width in zip(row, widths)))
        if index == 0:
            print("  ".join("-" * width for width in widths))
