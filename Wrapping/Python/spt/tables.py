"""Tables of results as Markdown files, and numbers as the tables print them."""

import math
import pathlib
from typing import Sequence


def format_value(value: object) -> str:
    """A table cell: floats to four significant digits, infinity as "inf"."""
    if isinstance(value, float):
        return "inf" if math.isinf(value) else f"{value:.4g}"
    return str(value)


def write_table(path: pathlib.Path, header: Sequence[str],
                rows: Sequence[Sequence[object]]) -> str:
    """Write ``rows`` under ``header`` as a Markdown table to ``path``; returns the text."""
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for row in rows:
        lines.append("| " + " | ".join(format_value(v) for v in row) + " |")
    text = "\n".join(lines) + "\n"
    path.write_text(text)
    return text
