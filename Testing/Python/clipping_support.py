"""Clipping planes for the mappers' tests: the tetrahedral default scene cut by one oblique
plane, or by two planes with the volume moved, rotated and scaled by its matrix, and the exact
reference of the clipped volume (spt.raycast with the same planes and matrix)."""

import math
import os
import pathlib
from dataclasses import dataclass
from functools import lru_cache
from typing import Sequence, Tuple

import numpy as np
import vtk

from spt import metrics, raycast, render

from image_statistics import Estimate, estimate
from robustness_support import ONE, property_for, split_box, volume_property, watch
from scene_support import scene
from statistics_checks import BIAS_FLOOR, Z


def plane(origin, normal) -> vtk.vtkPlane:
    """A vtkPlane; a mapper keeps the side its normal points to."""
    result = vtk.vtkPlane()
    result.SetOrigin(*origin)
    result.SetNormal(*normal)
    return result


def moved() -> vtk.vtkTransform:
    """The volume's matrix of the transformed cases: not rigid, so lengths in the data's own
    coordinates differ from the world's."""
    transform = vtk.vtkTransform()
    transform.Translate(1.0, 2.0, 0.5)
    transform.RotateZ(30.0)
    transform.RotateX(-20.0)
    transform.Scale(1.5, 1.0, 0.8)
    return transform


@lru_cache(maxsize=None)
def coarse():
    """Few large cells (a box of 3 x 3 x 3 unit cubes split into tetrahedra) under a field
    that varies across each of them and a transfer function that follows it closely: a cut
    segment is much of its ray, so its colour must be the cut segment's own."""
    grid = split_box((3, 3, 3), lambda p: (0.5 + 0.5 * np.sin(
        1.3 * p[:, 0] + 0.9 * p[:, 1] - 0.7 * p[:, 2])).astype(np.float32), (-1.5, -1.5, -1.5))
    prop = volume_property([(0.0, 0.1, 0.3, 1.0), (1.0, 1.0, 0.7, 0.1)], [(0.0, 0.0), (1.0, 1.0)],
                           1.5)
    return grid, prop


def _scene(mesh: str):
    """The grid, property and view of a case's mesh."""
    if mesh == "coarse":
        return coarse() + (render.View(30.0, 20.0),)
    if mesh == "one":
        return ONE, property_for(unit=0.5, opacity=0.8), render.View(30.0, 20.0)
    s = scene("default")
    return s.grid, s.property, s.view


@dataclass(frozen=True)
class Case:
    """Planes as (origin, normal) in world coordinates, whether the volume is moved, and the
    mesh (the default scene's or coarse())."""

    planes: Tuple[Tuple[Tuple[float, ...], Tuple[float, ...]], ...]
    moved: bool = False
    mesh: str = "default"

    def vtk_planes(self):
        return [plane(origin, normal) for origin, normal in self.planes]


#: The moved volume's centre in world coordinates (the default mesh is centred on the origin).
MOVED_CENTER = (1.0, 2.0, 0.5)
CASES = {
    "none": Case(()),
    "one oblique": Case((((0.2, 0.0, 0.0), (1.0, 0.3, 0.2)),)),
    "the other side": Case((((0.2, 0.0, 0.0), (-1.0, -0.3, -0.2)),)),
    "moved, none": Case((), moved=True),
    "two, moved": Case(((MOVED_CENTER, (1.0, 0.3, 0.2)), (MOVED_CENTER, (0.0, -0.4, 1.0))),
                       moved=True),
    "one tetrahedron, none": Case((), mesh="one"),
    "one tetrahedron, one": Case((((0.25, 0.25, 0.25), (1.0, -0.5, 0.3)),), mesh="one"),
    "coarse, none": Case((), mesh="coarse"),
    "coarse, two": Case((((0.3, 0.0, 0.0), (1.0, 0.4, -0.3)), ((0.0, 0.0, 0.4), (0.2, -0.5, -1.0))),
                        mesh="coarse"),
}


@dataclass
class Window:
    """A window showing the default scene through a mapper with a case's planes."""

    window: vtk.vtkRenderWindow
    renderer: vtk.vtkRenderer
    volume: vtk.vtkVolume
    planes: Sequence[vtk.vtkPlane]
    case: Case

    def image(self) -> np.ndarray:
        self.window.Render()
        return render.read_rgba(self.window)

    def reference(self) -> np.ndarray:
        """The exact image of the clipped volume with this window's camera."""
        grid, prop, _ = _scene(self.case.mesh)
        size = tuple(self.window.GetSize())
        return raycast.render(grid, prop, self.renderer.GetActiveCamera(), size,
                              matrix=self.volume.GetMatrix(),
                              clipping_planes=self.volume.GetMapper().GetClippingPlanes())


def window_with(mapper, case: Case, size: int, dolly: float = 1.0,
                parallel: bool = False) -> Window:
    """The case's mesh through ``mapper`` with the case's planes, the camera framing the
    (moved) volume, dollied in by ``dolly`` (8: the near plane cuts the mesh), in parallel
    projection or perspective."""
    grid, prop, view = _scene(case.mesh)
    view = render.View(view.azimuth, view.elevation, view.zoom, parallel)
    window, renderer = render.make_window(size, size)
    volume = render.add_volume(renderer, grid, prop, mapper)
    if case.moved:
        volume.SetUserTransform(moved())
    planes = case.vtk_planes()
    for p in planes:
        mapper.AddClippingPlane(p)
    render.place_camera(renderer, volume.GetBounds(), view)
    if dolly != 1.0:
        renderer.GetActiveCamera().Dolly(dolly)
        renderer.ResetCameraClippingRange(volume.GetBounds())
    return Window(window, renderer, volume, planes, case)


def image(mapper, case: Case, size: int, dolly: float = 1.0, parallel: bool = False
          ) -> np.ndarray:
    """One render of the case through ``mapper``."""
    w = window_with(mapper, case, size, dolly, parallel)
    result = w.image()
    w.window.Finalize()
    return result


@lru_cache(maxsize=None)
def reference(name: str, size: int, dolly: float = 1.0, parallel: bool = False) -> np.ndarray:
    """The exact reference of a case of CASES."""
    w = window_with(vtk.vtkUnstructuredGridVolumeRayCastMapper(), CASES[name], size, dolly,
                    parallel)
    result = w.reference()
    w.window.Finalize()
    return result


def unclipped_name(name: str) -> str:
    """The case of CASES without planes on the same mesh."""
    return next(other for other, case in CASES.items()
                if not case.planes and case.mesh == CASES[name].mesh
                and case.moved == CASES[name].moved)


def check_bad_planes(mapper, size: int) -> None:
    """Seven planes: an error that says why, nothing drawn, no crash; with six, it draws. A
    plane with NaN in its normal: an error, nothing drawn."""
    messages = watch(mapper)
    planes = [plane((0.0, 0.0, 0.0), (1.0, 0.0, -1.0)) for _ in range(7)]
    w = window_with(mapper, CASES["none"], size)
    for p in planes:
        mapper.AddClippingPlane(p)
    drawn = w.image()
    assert messages.errors and "at most 6" in messages.errors[0], messages.errors
    assert drawn[..., 3].max() == 0.0, "an image from more planes than the mapper honours"
    mapper.RemoveClippingPlane(planes[0])
    assert w.image()[..., 3].max() > 0.2, "six planes must draw"
    messages.errors.clear()
    mapper.RemoveAllClippingPlanes()
    mapper.AddClippingPlane(plane((0.0, 0.0, 0.0), (float("nan"), 0.0, 1.0)))
    drawn = w.image()
    assert messages.errors and "not finite" in messages.errors[0], messages.errors
    assert drawn[..., 3].max() == 0.0, "an image from a plane that is not finite"
    w.window.Finalize()


def estimate_case(mappers, name: str, size: int, level: int, dolly: float = 1.0):
    """The estimate of two renders of the case of CASES, one through each of ``mappers`` (of
    two seeds at ``level`` repetitions), against its reference; and the two images."""
    first, second = (image(mapper, CASES[name], size, dolly) for mapper in mappers)
    return estimate(first, second, reference(name, size, dolly), level), (first, second)


def check_clipped_is_unbiased(label: str, make, name: str, size: int, level: int) -> Estimate:
    """The case's bias (mappers ``make(seed)`` of seeds 1 and 2) is the unclipped case's to
    within Z standard errors and at most BIAS_FLOOR; against the unclipped reference it is
    many times larger (the planes are honoured). Keeps a render and the reference."""
    clipped, images = estimate_case([make(1), make(2)], name, size, level)
    unclipped, _ = estimate_case([make(1), make(2)], unclipped_name(name), size, level)
    keep_images(f"{label} clipping {name}", [images[0], reference(name, size)])
    tolerance = Z * math.hypot(clipped.bias2_error, unclipped.bias2_error)
    assert clipped.bias2 <= unclipped.bias2 + tolerance, (
        f"{name}: bias {clipped.bias:.4f}, unclipped {unclipped.bias:.4f}")
    assert clipped.bias <= BIAS_FLOOR, f"{name}: bias {clipped.bias:.4f}"
    ignored = estimate(*images, reference(unclipped_name(name), size), level)
    assert ignored.bias > 5.0 * max(clipped.bias, 0.005), (
        f"{name}: bias {clipped.bias:.4f}, against the unclipped volume {ignored.bias:.4f}")
    return clipped


def keep_images(name: str, images: Sequence[np.ndarray]) -> None:
    """Side by side, as a PNG in the tests' artifacts (SPT_TEST_ARTIFACTS), if set."""
    directory = os.environ.get("SPT_TEST_ARTIFACTS")
    if directory:
        path = pathlib.Path(directory)
        path.mkdir(parents=True, exist_ok=True)
        file_name = "".join(c if c.isalnum() else "_" for c in name) + ".png"
        metrics.write_png(path / file_name, metrics.side_by_side(list(images)))
