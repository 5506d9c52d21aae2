"""One style for every plot of the figures and the benchmark.

Plots are drawn with Matplotlib's object API on an Agg canvas (no display, no global state),
with the same font sizes, grid, line styles and resolution everywhere.
"""

from __future__ import annotations

import pathlib
from typing import Union

#: Marker and line styles in the order curves are drawn: distinct markers and dashes keep
#: curves that coincide visible.
LINE_STYLES = ("o-", "s--", "^:", "v-.", "D-", "P--", "X:", "*-.")

LEGEND_FONT_SIZE = 7
TITLE_FONT_SIZE = 9
DPI = 110


def figure(width: float, height: float):
    """A Matplotlib figure of ``width`` x ``height`` inches on an Agg canvas."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    result = Figure(figsize=(width, height))
    FigureCanvasAgg(result)
    return result


def line_style(index: int) -> str:
    """The marker and line style of the ``index``-th curve of a plot."""
    return LINE_STYLES[index % len(LINE_STYLES)]


def finish_axes(axes, xlabel: str, ylabel: str, title: str = "", legend: bool = True) -> None:
    """Labels, a light grid on both scales, and the legend, in the common style."""
    axes.set_xlabel(xlabel)
    axes.set_ylabel(ylabel)
    if title:
        axes.set_title(title, fontsize=TITLE_FONT_SIZE)
    axes.grid(True, which="both", alpha=0.3)
    if legend and axes.get_legend_handles_labels()[0]:
        axes.legend(fontsize=LEGEND_FONT_SIZE)


def save(result, path: Union[str, pathlib.Path]) -> None:
    """Lay out and write ``result`` as a PNG."""
    result.tight_layout()
    result.savefig(str(path), dpi=DPI)
