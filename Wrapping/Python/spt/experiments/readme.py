"""``python3 -m spt figures readme``: the README's pictures.

* ``interpenetrating.png``: the demo's interpenetrating drill and ring, exact, through VTK's
  projected tetrahedra and through SPT, with each one's difference from the exact image.
* ``race.png``: from the benchmark's race (``bench.json``), each scene's time to VTK PT's
  error as a multiple of VTK PT's frame, against its cells.

Both are written as palette PNGs, small enough to commit.
"""

from __future__ import annotations

import json
import pathlib
from typing import Dict, List

import numpy as np

from .. import metrics, render, volumes
from . import plots
from .demo import PAIR_CELLS, cached_reference

#: SPT's repetitions in the picture.
PICTURE_REPETITIONS = 64
#: The methods of the race plot: (summary method, label).
RACE_CURVES = (("spt", "SPT"), ("spt-slabs", "SPT, 8 depth slabs"))


def write_small_png(path: pathlib.Path, image: np.ndarray, colors: int = 255) -> None:
    """An RGB uint8 image as a PNG of at most ``colors`` colors (Pillow's quantizer)."""
    from PIL import Image

    picture = Image.fromarray(np.ascontiguousarray(image[..., :3]), "RGB")
    picture.quantize(colors=colors, method=Image.Quantize.MEDIANCUT).save(
        path, optimize=True)


def interpenetrating_picture(size: int = 256, cells: int = PAIR_CELLS) -> np.ndarray:
    """The interpenetrating scene exact, through VTK PT and SPT, and their differences."""
    s = volumes.interpenetrating(cells)
    exact = cached_reference(s, size).image
    shape = (size, size)
    pt = volumes.draw(s, render.projected_tetrahedra_mapper, shape).image
    spt = volumes.draw(s, lambda: render.spt_mapper(PICTURE_REPETITIONS), shape).image
    return metrics.side_by_side(
        [spt, pt, exact, metrics.difference_image(spt, exact),
         metrics.difference_image(pt, exact)],
        [f"SPT, L={PICTURE_REPETITIONS}: RMSE {metrics.rmse(spt, exact):.4f}",
         f"VTK PT: RMSE {metrics.rmse(pt, exact):.4f}", "exact (ray caster)",
         "|SPT - exact| x4", "|VTK PT - exact| x4"])


#: The HAVS-like curve's label: its frame, at its own error.
HAVS_LABEL = "HAVS-like k=6's frame (its own error)"
#: Scene names in the plot.
SCENE_NAMES = {"spx": "SPX", "torus": "torus", "bluntfin": "Blunt Fin", "post": "Oxygen Post",
               "drill-0.2M": "drill 0.2M", "drill-1M": "drill 1M", "drill-3M": "drill 3M"}


def race_curves(race: Dict[str, object]) -> Dict[str, List[tuple]]:
    """Per curve, (cells, time to VTK PT's error / VTK PT's frame, scene) of every scene
    that reached it, and HAVS-like k=6's frame / VTK PT's frame."""
    cells = {row["scene"]: row["cells"] for row in race["rows"]}
    frames = {(row["scene"], row["method"]): row["seconds"] for row in race["rows"]
              if not row["stochastic"]}
    curves: Dict[str, List[tuple]] = {label: [] for _, label in RACE_CURVES}
    curves[HAVS_LABEL] = []
    for entry in race["summary"]:
        for method, label in RACE_CURVES:
            reached = entry["reached"].get("VTK PT's error")
            if entry["method"] == method and reached:
                curves[label].append((cells[entry["scene"]], reached["ratio"], entry["scene"]))
    for scene in dict.fromkeys(row["scene"] for row in race["rows"]):
        if (scene, "havs6") in frames and (scene, "pt") in frames:
            curves[HAVS_LABEL].append(
                (cells[scene], frames[(scene, "havs6")] / frames[(scene, "pt")], scene))
    return {label: sorted(points) for label, points in curves.items()}


def race_plot(bench: Dict[str, object], path: pathlib.Path) -> None:
    """The race's times to VTK PT's error against cells, on log scales, each SPT point
    named by its scene."""
    from matplotlib.ticker import FixedLocator, NullFormatter, ScalarFormatter

    figure = plots.figure(6.4, 3.8)
    axes = figure.add_subplot(1, 1, 1)
    for index, (label, points) in enumerate(race_curves(bench["race"]).items()):
        if points:
            x, y, names = zip(*points)
            axes.plot(x, y, plots.line_style(index)[0], label=label)
            if index == 0:
                for point in zip(x, y, names):
                    axes.annotate(SCENE_NAMES.get(point[2], point[2]), point[:2], fontsize=7,
                                  xytext=(4, 3), textcoords="offset points")
    axes.axhline(1.0, color="black", linewidth=0.8)
    axes.set_xscale("log")
    axes.set_yscale("log")
    axes.yaxis.set_major_locator(FixedLocator([0.25, 0.5, 1.0, 2.0, 4.0, 8.0]))
    axes.yaxis.set_major_formatter(ScalarFormatter())
    axes.yaxis.set_minor_formatter(NullFormatter())
    size = bench["race"]["size"]
    plots.finish_axes(axes, "tetrahedra", "time / VTK PT's frame (below 1: faster)",
                      f"Time to VTK PT's error, {size} x {size}, {bench.get('machine', '')}")
    figure.tight_layout()
    figure.canvas.draw()
    write_small_png(path, np.asarray(figure.canvas.buffer_rgba()))


def readme_figures(output: pathlib.Path, bench_json: pathlib.Path, size: int = 256
                   ) -> List[pathlib.Path]:
    """Write the README's pictures to ``output``; returns their paths."""
    output.mkdir(parents=True, exist_ok=True)
    picture = output / "interpenetrating.png"
    write_small_png(picture, interpenetrating_picture(size))
    plot = output / "race.png"
    race_plot(json.loads(bench_json.read_text(encoding="utf-8")), plot)
    return [picture, plot]
