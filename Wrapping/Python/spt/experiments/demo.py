"""``python3 -m spt demo``: the race on one scene. SPT at its error target, VTK's projected
tetrahedra, the HAVS-like k-buffer and PBVR, each against the exact reference, and the time SPT
takes to reach VTK PT's error.
"""

from __future__ import annotations

import pathlib
from typing import List, Sequence, Tuple

from .. import metrics, render
from ..progress import Progress
from ..scenes import DEMO_SCENE, Scene, scene
from . import tables

PathLike = pathlib.Path
#: A row of the race before the table: its label and its rendering.
LabelledRendering = Tuple[str, render.Rendering]

#: The demo's row of SPT at VTK PT's error once it has drawn the scene from another view.
TURNED_LABEL = "SPT at VTK PT's error, after another view"
#: The depth slabs of the demo's row with slabs, and its label.
DEMO_DEPTH_SLABS = 8
SLABS_LABEL = f"SPT at VTK PT's error, {DEMO_DEPTH_SLABS} depth slabs"

#: The demo's columns.
DEMO_TABLE_HEADER = ["method", "RMSE", "PSNR [dB]", "pixels off > 0.05", "time [s]",
                     "time / VTK PT", "repetitions"]


def _demo_methods(repetitions: int, seed: int, target_error: float) -> List[tuple]:
    """(label, mapper) of the race's methods but SPT at VTK PT's error."""
    return [(f"SPT (target error {target_error:g})",
             render.spt_mapper(repetitions, seed=seed, target_error=target_error)),
            ("VTK PT", render.projected_tetrahedra_mapper()),
            ("HAVS-like k=2", render.havs_mapper(2)),
            ("HAVS-like k=6", render.havs_mapper(6)),
            ("PBVR (32 repetitions)", render.pbvr_mapper(32, seed=seed))]


def _at_pt_error(s: Scene, shape: Tuple[int, int], repetitions: int, seed: int,
                 pt_error: float, progress: Progress) -> List[LabelledRendering]:
    """SPT with VTK PT's error as its target: on its first image, once it has drawn another
    view, and with depth slabs."""
    race = render.render(s.grid, s.property,
                         render.spt_mapper(repetitions, seed=seed, target_error=pt_error),
                         s.view, shape, frames=2)
    progress.step("SPT at VTK PT's error")
    # The same once the mapper has drawn another view: its first step aims with the noise
    # per repetition it measured there, as while a user turns the camera.
    turned = render.after_another_view(
        render.spt_mapper(repetitions, seed=seed, target_error=pt_error), s.grid, s.property,
        s.view, shape)
    turned_rendering = render.render(s.grid, s.property, turned, s.view, shape, frames=2)
    progress.step(TURNED_LABEL)
    # With depth slabs: far less noise per repetition on a mesh of small cells.
    slabs = render.spt_mapper(repetitions, seed=seed, target_error=pt_error,
                              depth_slabs=DEMO_DEPTH_SLABS)
    slabs_rendering = render.render(s.grid, s.property, slabs, s.view, shape, frames=2)
    progress.step(SLABS_LABEL)
    return [("SPT at VTK PT's error", race), (TURNED_LABEL, turned_rendering),
            (SLABS_LABEL, slabs_rendering)]


def _write_images(output: PathLike, results: Sequence[LabelledRendering],
                  reference: render.Rendering) -> None:
    """SPT's, VTK PT's and the reference's images, and their side-by-side comparison."""
    spt, pt = results[0][1], results[1][1]
    for name, rendering in (("spt", spt), ("vtk_pt", pt), ("reference", reference)):
        metrics.write_png(output / f"{name}.png", rendering.image)
    comparison = metrics.side_by_side(
        [spt.image, pt.image, reference.image,
         metrics.difference_image(spt.image, reference.image),
         metrics.difference_image(pt.image, reference.image)],
        [results[0][0], "VTK projected tetrahedra", "reference (exact ray caster)",
         "|SPT - reference| x4", "|VTK PT - reference| x4"])
    metrics.write_png(output / "comparison.png", comparison)


def _table_rows(results: Sequence[LabelledRendering], reference: render.Rendering,
                pt: render.Rendering) -> List[List[object]]:
    rows = []
    for label, rendering in list(results) + [("reference", reference)]:
        count = rendering.mapper.GetLastRepetitionCount() if hasattr(
            rendering.mapper, "GetLastRepetitionCount") else ""
        rows.append([label, metrics.rmse(rendering.image, reference.image),
                     metrics.psnr(rendering.image, reference.image),
                     metrics.fraction_off(rendering.image, reference.image),
                     rendering.seconds, rendering.seconds / pt.seconds, count])
    return rows


def demo(output: PathLike, size: int = 384, repetitions: int = 256,
         dataset: str = DEMO_SCENE, seed: int = 0,
         target_error: float = render.DEFAULT_TARGET_ERROR) -> List[List[object]]:
    """The main job: the race on one scene. SPT at its error target, VTK's projected
    tetrahedra, the HAVS-like k-buffer (k = 2 and 6) and PBVR, each against the exact reference
    (error, and time as the best of two frames), and SPT with VTK PT's error as its target: the
    time SPT takes to reach VTK PT's error, as a multiple of VTK PT's frame, with one depth
    slab and with 8. Writes the images, a side-by-side comparison and the table; returns the
    table rows."""
    output.mkdir(parents=True, exist_ok=True)
    s = scene(dataset)
    shape = (size, size)
    progress = Progress(9, f"demo on {dataset}")
    reference = render.reference(s.grid, s.property, s.view, shape)
    progress.step("reference")
    results = []
    for label, mapper in _demo_methods(repetitions, seed, target_error):
        results.append((label, render.render(s.grid, s.property, mapper, s.view, shape,
                                             frames=2)))
        progress.step(label)
    pt = results[1][1]
    pt_error = metrics.rmse(pt.image, reference.image)
    results[2:2] = _at_pt_error(s, shape, repetitions, seed, pt_error, progress)
    _write_images(output, results, reference)
    rows = _table_rows(results, reference, pt)
    tables.write_table(output / "table.md", DEMO_TABLE_HEADER, rows)
    return rows
