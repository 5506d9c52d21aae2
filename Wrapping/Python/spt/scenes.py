"""Scenes: a data set, its transfer functions and a camera, by name.

The figures, the benchmark and the tests draw the same named scenes, so that their numbers
can be put side by side.
"""

from __future__ import annotations

import dataclasses
from typing import Callable, Dict

from vtkmodules.vtkCommonDataModel import vtkUnstructuredGrid
from vtkmodules.vtkRenderingCore import vtkVolumeProperty

from . import data, render


@dataclasses.dataclass
class Scene:
    """A data set, its transfer functions and a camera."""

    name: str
    grid: vtkUnstructuredGrid
    property: vtkVolumeProperty
    view: render.View


def _default_scene() -> Scene:
    grid = data.make_default_mesh()
    return Scene("default", grid, data.default_transfer_function(grid), VIEWS["default"])


def data_scene(name: str, view: render.View, opacity_scale: float = 1.0
               ) -> Callable[[], Scene]:
    """A maker of the scene of the data set ``name`` (:func:`spt.data.load`) with the
    default transfer function scaled in opacity by ``opacity_scale``."""
    def make() -> Scene:
        grid = data.load(name)
        return Scene(name, grid, data.transfer_function(grid, opacity_scale=opacity_scale), view)
    return make


def generated_scene(name: str, shape: str, cells: int, view: render.View
                    ) -> Callable[[], Scene]:
    """A maker of the scene of a generated mesh (:func:`spt.meshes.generate`, cached on
    disk) of about ``cells`` tetrahedra."""
    def make() -> Scene:
        from . import meshes
        grid = meshes.generate(shape, cells)
        return Scene(name, grid, data.transfer_function(grid), view)
    return make


#: The cameras of the named scenes.
VIEWS: Dict[str, render.View] = {
    "drill": render.View(azimuth=30.0, elevation=25.0, zoom=1.3),
    "ring": render.View(azimuth=20.0, elevation=40.0),
    "default": render.View(azimuth=30.0, elevation=30.0),
    "spx": render.View(azimuth=30.0, elevation=30.0),
    "bluntfin": render.View(azimuth=40.0, elevation=25.0),
    "post": render.View(azimuth=30.0, elevation=20.0),
    "torus": render.View(azimuth=20.0, elevation=40.0),
    "ironprot_full": render.View(azimuth=35.0, elevation=25.0),
}

SCENES: Dict[str, Callable[[], Scene]] = {
    "drill": generated_scene("drill", "drill", 200_000, VIEWS["drill"]),
    "ring": generated_scene("ring", "torus", 200_000, VIEWS["ring"]),
    "default": _default_scene,
    "spx": data_scene("spx", VIEWS["spx"]),
    "bluntfin": data_scene("bluntfin", VIEWS["bluntfin"], 0.5),
    "post": data_scene("post", VIEWS["post"], 0.5),
    "torus": data_scene("torus", VIEWS["torus"]),
    "ironprot_full": data_scene("ironprot_full", VIEWS["ironprot_full"]),
}


def scene(name: str) -> Scene:
    """The named scene; raises ValueError for an unknown name."""
    if name not in SCENES:
        raise ValueError(f"unknown data set '{name}'; choose from {', '.join(SCENES)}")
    return SCENES[name]()
