"""Several volumes in one view, each with its own data and transfer functions.

VTK draws the volumes of a renderer one after the other, so a sorted renderer (VTK's
projected tetrahedra, the HAVS-like k-buffer) composites them in the wrong order wherever they
interpenetrate; the SPT volumes of a renderer share one set of buffers and composite exactly.

    from spt import volumes
    s = volumes.interpenetrating(200_000)   # a drill and a ring through it
    image = volumes.draw(s, lambda: render.spt_mapper(64), (256, 256)).image
    exact = volumes.reference(s, (256, 256)).image
"""

from __future__ import annotations

import dataclasses
from typing import Callable, Iterator, List, Sequence, Tuple

from vtkmodules.vtkCommonDataModel import vtkUnstructuredGrid
from vtkmodules.vtkCommonTransforms import vtkTransform
from vtkmodules.vtkFiltersGeneral import vtkTransformFilter
from vtkmodules.vtkRenderingCore import vtkAbstractVolumeMapper, vtkVolumeProperty

from . import data, render

Volume = Tuple[vtkUnstructuredGrid, vtkVolumeProperty]

#: The camera of the interpenetrating scene.
INTERPENETRATING_VIEW = render.View(azimuth=35.0, elevation=20.0, zoom=1.25)
#: The ring's colors: dark violet through teal to yellow, (t, r, g, b) over its field's range.
RING_COLORS = ((0.0, 0.27, 0.00, 0.33), (0.5, 0.13, 0.57, 0.55), (1.0, 0.99, 0.91, 0.14))


@dataclasses.dataclass
class VolumesScene:
    """Volumes that share one space, and a camera."""

    name: str
    volumes: List[Volume]
    view: render.View

    def bounds(self) -> Tuple[float, ...]:
        """The bounding box of all the volumes."""
        boxes = [grid.GetBounds() for grid, _ in self.volumes]
        return tuple((min if i % 2 == 0 else max)(box[i] for box in boxes) for i in range(6))

    def cells(self) -> int:
        return sum(grid.GetNumberOfCells() for grid, _ in self.volumes)


def _through_the_drill(ring: vtkUnstructuredGrid) -> vtkUnstructuredGrid:
    """The ring stood up (its plane through the drill's axis) around the drill's body, so
    that its tube passes through the drill twice."""
    transform = vtkTransform()
    transform.Translate(0.0, 0.0, 2.4)
    transform.RotateX(90.0)
    moved = vtkTransformFilter()
    moved.SetInputData(ring)
    moved.SetTransform(transform)
    moved.Update()
    result = vtkUnstructuredGrid()
    result.ShallowCopy(moved.GetOutput())
    return result


def interpenetrating(cells: int = 200_000) -> VolumesScene:
    """The generated drill and a ring through it, about ``cells`` tetrahedra in all (half
    each; :func:`spt.meshes.generate`, cached), each with its own field and transfer
    functions: the drill's cool to warm, the ring's violet to yellow."""
    from . import meshes

    drill = meshes.generate("drill", cells // 2)
    ring = _through_the_drill(meshes.generate("torus", cells // 2, seed=1))
    # The ring's own transfer functions: other colors than the drill's, and more opaque.
    ring_property = data.property_from_points(ring, RING_COLORS, [(0.0, 0.05), (1.0, 1.0)],
                                              1.0 / 40.0)
    return VolumesScene("interpenetrating", [(drill, data.transfer_function(drill)),
                                             (ring, ring_property)], INTERPENETRATING_VIEW)


def _open(s: VolumesScene, mappers: Sequence[vtkAbstractVolumeMapper],
          size: Tuple[int, int]):
    window, renderer = render.make_window(*size)
    for (grid, prop), mapper in zip(s.volumes, mappers):
        render.add_volume(renderer, grid, prop, mapper)
    render.place_camera(renderer, s.bounds(), s.view)
    return window, renderer


def _close(window, renderer) -> None:
    renderer.RemoveAllViewProps()
    window.Finalize()


def draw(s: VolumesScene, make_mapper: Callable[[], vtkAbstractVolumeMapper],
         size: Tuple[int, int] = (256, 256), frames: int = 1) -> render.Rendering:
    """Every volume of ``s`` through a mapper of its own (``make_mapper()``) in one renderer,
    as :func:`spt.render.render` draws one: an untimed frame, then the best of ``frames``.
    The rendering's mapper is the first volume's (the one that draws all SPT volumes)."""
    mappers = [make_mapper() for _ in s.volumes]
    window, renderer = _open(s, mappers, size)
    seconds = render.best_frame(window, mappers[0], frames)
    rendering = render.Rendering(image=render.read_rgba(window), seconds=seconds,
                                 mapper=mappers[0], report=render.mapper_report(mappers[0]))
    _close(window, renderer)
    return rendering


def draw_levels(s: VolumesScene, levels: Sequence[int], size: Tuple[int, int] = (256, 256),
                frames: int = 1) -> Iterator[render.Rendering]:
    """SPT's image of ``s`` at each repetition level of ``levels`` in turn, the best of
    ``frames`` each, in one window whose mappers keep their buffers and tables from level to
    level: only the first level has an untimed frame before (a level's first frame may
    compile shaders for its group of repetitions, which the best of two leaves out). The
    caller may stop early."""
    mappers = [render.spt_mapper(levels[0]) for _ in s.volumes]
    window, renderer = _open(s, mappers, size)
    try:
        for index, level in enumerate(levels):
            mappers[0].SetRepetitionLevel(level)  # the first SPT volume draws them all
            seconds = render.best_frame(window, mappers[0], frames, warm=index == 0)
            yield render.Rendering(image=render.read_rgba(window), seconds=seconds,
                                   mapper=mappers[0])
    finally:
        _close(window, renderer)


def reference(s: VolumesScene, size: Tuple[int, int] = (256, 256)) -> render.Rendering:
    """The exact image of every volume of ``s``, with the camera that :func:`draw` uses."""
    return render.exact_reference(s.volumes, s.bounds(), s.view, size)


def single(grid: vtkUnstructuredGrid, prop: vtkVolumeProperty, name: str,
           view: render.View) -> VolumesScene:
    """One volume as a scene of this module, so that one code path draws both."""
    return VolumesScene(name, [(grid, prop)], view)
