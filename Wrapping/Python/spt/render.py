"""Rendering helpers: one scene, several volume mappers, float RGBA images back.

Every renderer of the comparison (SPT, the HAVS-like sorted baseline, PBVR, VTK's projected
tetrahedra, the reference ray caster) is drawn through :func:`render`, with the same camera,
transfer functions and window size, on a transparent black background, so that the image read
back is the volume's own premultiplied RGBA.
"""

from __future__ import annotations

import dataclasses
import os
import time
from typing import Callable, Dict, Optional, Sequence, Tuple

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import (
    VTK_TETRA,
    vtkDataSet,
    vtkUnstructuredGrid,
)
from vtkmodules.vtkRenderingCore import (
    vtkAbstractVolumeMapper,
    vtkProp,
    vtkRenderer,
    vtkRenderWindow,
    vtkVolume,
    vtkVolumeProperty,
    vtkWindowToImageFilter,
)
from vtkmodules.vtkRenderingVolume import (
    vtkProjectedTetrahedraMapper,
    vtkUnstructuredGridLinearRayIntegrator,
    vtkUnstructuredGridVolumeRayCastMapper,
)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (OpenGL render window factories)
import vtkmodules.vtkRenderingVolumeOpenGL2  # noqa: F401  (vtkOpenGLProjectedTetrahedraMapper)

from . import meshes, metrics, raycast
from . import HAVE_BASELINES, vtkHeadlessEGLRenderWindow, vtkSPTVolumeMapper

if HAVE_BASELINES:
    from . import vtkHAVSVolumeMapper, vtkPBVRVolumeMapper


@dataclasses.dataclass(frozen=True)
class View:
    """A camera placed around a data set's bounding box."""

    azimuth: float = 30.0
    elevation: float = 20.0
    zoom: float = 1.0
    parallel: bool = False


#: SPT as the paper draws it: the survivor estimator, independent thresholds, no exact
#: coverage (``render.spt_mapper(level, **PAPER_SAMPLING)``). RepetitionsPerPass is left at
#: the default, which draws the same images as one repetition per pass.
PAPER_SAMPLING = {"stratified": False, "estimator": "survivor", "exact_coverage": False}
#: The survivor estimator with stratified thresholds, without exact coverage.
STRATIFIED_SURVIVOR_SAMPLING = {"stratified": True, "estimator": "survivor",
                                "exact_coverage": False}

_ESTIMATORS = {"survivor": vtkSPTVolumeMapper.SURVIVOR_ESTIMATOR,
               "visibility": vtkSPTVolumeMapper.VISIBILITY_ESTIMATOR}


#: The error target that the demo, the command line and the ParaView plugin use by default
#: (RMSE of premultiplied RGBA, about 1.3 levels of an 8-bit image).
DEFAULT_TARGET_ERROR = 0.005


def _stochastic(mapper, repetitions: int, subpixels: int, seed: int):
    """``mapper`` with the given RepetitionLevel, SubpixelLevel and Seed, and the time budget
    off: its image has exactly ``repetitions`` repetitions (unless an error target stops it)."""
    mapper.SetRepetitionLevel(repetitions)
    mapper.SetSubpixelLevel(subpixels)
    mapper.SetSeed(seed)
    mapper.SetAutoAdjustRepetitions(False)
    return mapper


def spt_mapper(repetitions: int = 32, subpixels: int = 1, seed: int = 0,
               stratified: Optional[bool] = None, per_pass: Optional[int] = None,
               estimator: Optional[str] = None, exact_coverage: Optional[bool] = None,
               target_error: Optional[float] = None,
               depth_slabs: Optional[int] = None) -> vtkSPTVolumeMapper:
    """An SPT mapper with the given RepetitionLevel, SubpixelLevel and Seed, its time budget off;
    ``stratified``, ``per_pass``, ``estimator`` ("survivor" or "visibility"), ``exact_coverage``
    and ``depth_slabs`` (1 to 8) set StratifiedSampling, RepetitionsPerPass, Estimator,
    ExactCoverage and DepthSlabs (None keeps the mapper's defaults). With ``target_error``,
    rendering stops once the error the mapper estimates (its noise and the rounding to the
    framebuffer's bits) is at most that, and ``repetitions`` is the cap."""
    if target_error is not None and not 0.0 <= target_error <= 1.0:
        raise ValueError(f"the target error must be in 0..1, not {target_error}")
    if depth_slabs is not None and not 1 <= depth_slabs <= 8:
        raise ValueError(f"the depth slabs must be 1 to 8, not {depth_slabs}")
    mapper = _stochastic(vtkSPTVolumeMapper(), repetitions, subpixels, seed)
    if estimator is not None:
        if estimator not in _ESTIMATORS:
            raise ValueError(f"unknown estimator {estimator!r}; choose from "
                             f"{', '.join(_ESTIMATORS)}")
        mapper.SetEstimator(_ESTIMATORS[estimator])
    for setter, value in ((mapper.SetStratifiedSampling, stratified),
                          (mapper.SetRepetitionsPerPass, per_pass),
                          (mapper.SetExactCoverage, exact_coverage),
                          (mapper.SetTargetError, target_error),
                          (mapper.SetDepthSlabs, depth_slabs)):
        if value is not None:
            setter(value)
    return mapper


def _require_baselines() -> None:
    if not HAVE_BASELINES:
        raise RuntimeError("this build of spt has no HAVS-like and PBVR mappers (configured "
                           "with SPT_BUILD_BASELINES=OFF)")


def havs_mapper(kbuffer_size: int = 6) -> "vtkHAVSVolumeMapper":
    """The HAVS-like sorted baseline (faces radix-sorted by centroid distance on the CPU, a
    k-buffer of ``kbuffer_size`` fragments per pixel on the GPU)."""
    if not 2 <= kbuffer_size <= 6:
        raise ValueError(f"the k-buffer size must be 2..6, not {kbuffer_size}")
    _require_baselines()
    mapper = vtkHAVSVolumeMapper()
    mapper.SetKBufferSize(kbuffer_size)
    return mapper


def pbvr_mapper(repetitions: int = 32, subpixels: int = 1, seed: int = 0,
                cell_average: bool = False) -> "vtkPBVRVolumeMapper":
    """A PBVR mapper of ``repetitions`` particle sets, as :func:`spt_mapper`; ``cell_average``
    selects the papers' one-density-per-cell sampling instead of exact rejection sampling."""
    _require_baselines()
    mapper = _stochastic(vtkPBVRVolumeMapper(), repetitions, subpixels, seed)
    if cell_average:
        mapper.SetSamplingModeToCellAverage()
    return mapper


def projected_tetrahedra_mapper() -> vtkProjectedTetrahedraMapper:
    """VTK's own projected tetrahedra (cell-centre visibility sort on the CPU)."""
    return vtkProjectedTetrahedraMapper()


def reference_mapper() -> vtkUnstructuredGridVolumeRayCastMapper:
    """The reference: VTK's ray caster with the exact piecewise-linear integrator, one ray per
    pixel and no adaptive sampling. :func:`render` corrects three faults of VTK 9.2 for it,
    see :func:`reference_property`, :data:`REFERENCE_SUPERSAMPLING` and
    :func:`reference_grid`."""
    mapper = vtkUnstructuredGridVolumeRayCastMapper()
    mapper.SetRayIntegrator(vtkUnstructuredGridLinearRayIntegrator())
    mapper.SetImageSampleDistance(1.0)
    mapper.SetAutoAdjustSampleDistances(0)
    return mapper


def is_reference(mapper: vtkAbstractVolumeMapper) -> bool:
    """Whether ``mapper`` is VTK's unstructured-grid ray caster."""
    return isinstance(mapper, vtkUnstructuredGridVolumeRayCastMapper)


def reference_property(prop: vtkVolumeProperty) -> vtkVolumeProperty:
    """A copy of ``prop`` that VTK 9.2's linear ray integrator integrates exactly.

    vtkUnstructuredGridLinearRayIntegrator splits ray segments at the transfer functions'
    control points, but its loop over the opacity function stops after the first point, so
    only the color function's points are used and the opacity is interpolated linearly between
    them. Adding a color point, of the color already there, at every opacity point leaves the
    color function unchanged (RGB interpolation) and makes the integration exact.
    """
    copy = vtkVolumeProperty()
    copy.DeepCopy(prop)
    opacity = copy.GetScalarOpacity()
    nodes = []
    for i in range(opacity.GetSize()):
        node = [0.0] * 4
        opacity.GetNodeValue(i, node)
        nodes.append(node[0])
    if copy.GetColorChannels() == 1:
        gray = copy.GetGrayTransferFunction()
        for x in nodes:
            gray.AddPoint(x, gray.GetValue(x))
    else:
        color = copy.GetRGBTransferFunction()
        for x in nodes:
            color.AddRGBPoint(x, *color.GetColor(x))
    return copy


def reference_grid(grid: vtkDataSet) -> vtkDataSet:
    """``grid``, or, if it has inverted or flat tetrahedra, a copy that VTK 9.2's ray caster
    renders without holes.

    The ray caster walks from cell to cell through shared faces and loses rays on meshes with
    inverted tetrahedra (negative volume, as in about half of the torus) and flat ones (zero
    volume): the torus shows holes. The copy lists every inverted tetrahedron with two points
    swapped and leaves out the flat ones (which hold no volume); it is the same field on the
    same points. Grids with other cells than tetrahedra are returned as they are.
    """
    if not isinstance(grid, vtkUnstructuredGrid) or grid.GetNumberOfCells() == 0:
        return grid
    types = grid.GetDistinctCellTypesArray()
    if types is None or types.GetNumberOfTuples() != 1 or types.GetValue(0) != VTK_TETRA:
        return grid
    points = vtk_to_numpy(grid.GetPoints().GetData()).astype(np.float64)
    cells = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).reshape(-1, 4)
    a, b, c, d = (points[cells[:, i]] for i in range(4))
    volumes = np.einsum("ij,ij->i", np.cross(b - a, c - a), d - a)
    flat = np.abs(volumes) <= 1e-9 * max(np.abs(volumes).max(), np.finfo(float).tiny)
    inverted = (volumes < 0.0) & ~flat
    if not flat.any() and not inverted.any():
        return grid
    repaired = cells.copy()
    repaired[inverted, 0], repaired[inverted, 1] = cells[inverted, 1], cells[inverted, 0]
    copy = vtkUnstructuredGrid()
    copy.SetPoints(grid.GetPoints())
    copy.SetCells(VTK_TETRA, meshes.cell_array(repaired[~flat]))
    copy.GetPointData().ShallowCopy(grid.GetPointData())
    cell_data = grid.GetCellData()
    for index in range(cell_data.GetNumberOfArrays()):
        array = cell_data.GetAbstractArray(index)
        kept = numpy_to_vtk(vtk_to_numpy(array)[~flat], deep=True)
        kept.SetName(array.GetName())
        copy.GetCellData().AddArray(kept)
    if cell_data.GetScalars() is not None:
        copy.GetCellData().SetActiveScalars(cell_data.GetScalars().GetName())
    return copy


# VTK's unstructured ray caster casts its rays through pixel corners, half a pixel off the pixel
# centres that OpenGL rasterization (SPT, VTK's projected tetrahedra) samples, and shows its image
# as a linearly filtered texture, so shifting its camera by half a pixel blurs the silhouette.
# Instead it renders at twice the size: the corners of that grid include the centres of this
# one, and every second ray (odd columns, even rows counted from the top) is a pixel-centre ray.
# Measured on SPX at 1024 repetitions: SPT's mean alpha difference to it is -0.0006, against
# -0.0058 with the plain ray caster.
REFERENCE_SUPERSAMPLING = 2


MAPPERS: Dict[str, Callable[[], vtkAbstractVolumeMapper]] = {
    "spt": spt_mapper,
    "havs": havs_mapper,
    "pbvr": pbvr_mapper,
    "pt": projected_tetrahedra_mapper,
    "reference": reference_mapper,
}


def new_render_window() -> vtkRenderWindow:
    """A render window for this process: VTK's own (X, GLX) when there is an X display, else
    the EGL window, which needs no X server (``spt.vtkHeadlessEGLRenderWindow``). Without X, a
    RuntimeError names what is missing when EGL gives no OpenGL 3.2 context: nothing could
    be drawn, and VTK would read back uninitialized pixels."""
    if os.environ.get("DISPLAY"):
        return vtkRenderWindow()
    window = vtkHeadlessEGLRenderWindow()
    if not window.SupportsOpenGL():
        raise RuntimeError("no DISPLAY, and no OpenGL through EGL either: "
                           + window.GetOpenGLSupportMessage())
    return window


def make_window(width: int, height: int) -> Tuple[vtkRenderWindow, vtkRenderer]:
    """An off-screen window with alpha planes and a transparent black background: with X, or
    through EGL when there is no X display (:func:`new_render_window`)."""
    window = new_render_window()
    window.SetOffScreenRendering(1)
    window.SetAlphaBitPlanes(1)
    window.SetMultiSamples(0)
    window.SetSize(width, height)
    renderer = vtkRenderer()
    renderer.SetBackground(0.0, 0.0, 0.0)
    renderer.SetBackgroundAlpha(0.0)
    window.AddRenderer(renderer)
    return window, renderer


def add_volume(renderer: vtkRenderer, grid: vtkDataSet, prop: vtkVolumeProperty,
               mapper: vtkAbstractVolumeMapper) -> vtkVolume:
    """Show ``grid`` through ``mapper`` with ``prop`` in ``renderer``; returns the volume."""
    mapper.SetInputData(grid)
    volume = vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)
    renderer.AddVolume(volume)
    return volume


def place_camera(renderer: vtkRenderer, bounds, view: View) -> None:
    """Look at the bounding box from the view's direction, framing it with the view's zoom."""
    camera = renderer.GetActiveCamera()
    center = [(bounds[2 * i] + bounds[2 * i + 1]) / 2.0 for i in range(3)]
    camera.SetFocalPoint(center)
    camera.SetPosition(center[0], center[1] - 1.0, center[2])
    camera.SetViewUp(0.0, 0.0, 1.0)
    camera.Azimuth(view.azimuth)
    camera.Elevation(view.elevation)
    camera.OrthogonalizeViewUp()
    camera.SetParallelProjection(view.parallel)
    renderer.ResetCamera(bounds)
    camera.Zoom(view.zoom)
    renderer.ResetCameraClippingRange(bounds)


def read_rgba(window: vtkRenderWindow) -> np.ndarray:
    """The back buffer as float premultiplied RGBA in [0, 1], row 0 at the top."""
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.SetInputBufferTypeToRGBA()
    grab.ReadFrontBufferOff()
    grab.ShouldRerenderOff()
    grab.Update()
    return metrics.from_vtk_image(grab.GetOutput(), as_float_rgba=True)


#: How far around the scene's view :func:`after_another_view` turns the camera, in degrees.
ANOTHER_VIEW_AZIMUTH = 10.0


def after_another_view(mapper: vtkSPTVolumeMapper, grid: vtkDataSet, prop: vtkVolumeProperty,
                       view: View, size: Tuple[int, int]) -> vtkSPTVolumeMapper:
    """Render ``grid`` once through ``mapper`` from ``view`` turned by
    ``ANOTHER_VIEW_AZIMUTH`` degrees, in a window of its own, and return the mapper. Its next
    image is then a new one, whose error target aims at once with the noise per repetition
    this render measured, as when a user turns the camera and the view renders still."""
    turned = dataclasses.replace(view, azimuth=view.azimuth + ANOTHER_VIEW_AZIMUTH)
    render(grid, prop, mapper, turned, size, frames=0)
    return mapper


def warm_up(window: vtkRenderWindow, mapper: vtkAbstractVolumeMapper) -> None:
    """One untimed render that builds what later frames reuse (shaders, buffers, tables).
    SPT does it with one traversal group: its shaders are compiled for the repetitions a
    group draws, and its other caches do not depend on the count; with an error target, at
    its full count, whose rounds compile their own. PBVR does it at its full count: its
    particles (one set per repetition) are what it reuses."""
    repetitions = None
    if isinstance(mapper, vtkSPTVolumeMapper) and mapper.GetTargetError() <= 0.0:
        repetitions = mapper.GetRepetitionLevel()
        mapper.SetRepetitionLevel(min(repetitions, mapper.GetRepetitionsPerPass()))
    window.Render()
    window.WaitForCompletion()
    if repetitions is not None:
        mapper.SetRepetitionLevel(repetitions)


@dataclasses.dataclass
class Rendering:
    """An image and what it cost. ``report`` holds what the mapper reported right after the
    timed render, before the window released its resources: ``gpu_memory`` (bytes) for the
    project's mappers, and ``particles``, ``particle_sets``, ``generation_seconds`` and
    ``generation_count`` for PBVR."""

    image: np.ndarray
    seconds: float
    mapper: Optional[vtkAbstractVolumeMapper]
    report: Dict[str, float] = dataclasses.field(default_factory=dict)


def best_frame(window: vtkRenderWindow, mapper: vtkAbstractVolumeMapper, frames: int,
               warm: bool = True) -> float:
    """The best of ``frames`` renders of ``window``, in seconds, each finished on the GPU;
    after an untimed one (:func:`warm_up`) if ``warm``."""
    if warm:
        warm_up(window, mapper)
    seconds = float("inf")
    for _ in range(max(1, frames)):
        start = time.perf_counter()
        window.Render()
        window.WaitForCompletion()
        seconds = min(seconds, time.perf_counter() - start)
    return seconds


def mapper_report(mapper: vtkAbstractVolumeMapper) -> Dict[str, float]:
    """What a mapper of this project says about its last render (empty for VTK's own)."""
    report: Dict[str, float] = {}
    if hasattr(mapper, "GetGPUMemorySize"):
        report["gpu_memory"] = float(mapper.GetGPUMemorySize())
    if hasattr(mapper, "GetFrameStatistics"):
        statistics = mapper.GetFrameStatistics()
        report["point_cells"] = float(statistics.GetPointCellCount())
        report["computed_cells"] = float(statistics.GetComputedCellCount())
        report["depth_slabs"] = float(statistics.GetDepthSlabs())
    if HAVE_BASELINES and isinstance(mapper, vtkPBVRVolumeMapper):
        report["particles"] = float(mapper.GetNumberOfParticles())
        report["particle_sets"] = float(mapper.GetNumberOfParticleSets())
        report["generation_seconds"] = mapper.GetGenerationTime()
        report["generation_count"] = float(mapper.GetGenerationCount())
    return report


def render(grid: vtkDataSet, prop: vtkVolumeProperty, mapper: vtkAbstractVolumeMapper,
           view: View = View(), size: Tuple[int, int] = (256, 256),
           actors: Sequence[vtkProp] = (), frames: int = 1) -> Rendering:
    """Render ``grid`` with ``mapper`` (and any opaque ``actors``) in a window of its own and
    return the image and the wall time of the render.

    The time covers one ``Render()`` finished on the GPU (``WaitForCompletion``), the best of
    ``frames`` such renders; a first, untimed render builds the caches (tables, buffers,
    shaders) that later frames reuse. ``frames=0`` renders once, without that first render,
    for when only the image is wanted (the project's mappers draw the same image either way);
    the time is then that of a cold frame.
    """
    reference = is_reference(mapper)
    scale = REFERENCE_SUPERSAMPLING if reference else 1
    window, renderer = make_window(size[0] * scale, size[1] * scale)
    if reference:
        add_volume(renderer, reference_grid(grid), reference_property(prop), mapper)
    else:
        add_volume(renderer, grid, prop, mapper)
    for actor in actors:
        renderer.AddActor(actor)
    place_camera(renderer, grid.GetBounds(), view)
    seconds = best_frame(window, mapper, frames, warm=frames > 0)
    report = mapper_report(mapper)
    image = read_rgba(window)
    if reference:
        image = np.ascontiguousarray(image[0::REFERENCE_SUPERSAMPLING, 1::REFERENCE_SUPERSAMPLING])
    renderer.RemoveAllViewProps()
    window.Finalize()
    return Rendering(image=image, seconds=seconds, mapper=mapper, report=report)


#: How :func:`reference` renders: the project's exact ray caster (:mod:`spt.raycast`), or
#: VTK's unstructured-grid ray caster, which also honours opaque geometry in the scene.
REFERENCE_METHODS = ("exact", "vtk")


def reference(grid: vtkDataSet, prop: vtkVolumeProperty, view: View = View(),
              size: Tuple[int, int] = (256, 256), method: str = "exact",
              actors: Sequence[vtkProp] = ()) -> Rendering:
    """The reference image of a scene, with the camera that :func:`render` uses.

    ``exact`` is the default: VTK's ray caster misses or doubles segments of rays that graze
    a curved boundary (on the Oxygen Post its silhouette is off by up to 0.2 in alpha, see
    Documentation/baselines.md), while :mod:`spt.raycast` clips every ray against every
    tetrahedron it may cross. ``vtk`` is needed when opaque ``actors`` cut the volume.
    """
    if method not in REFERENCE_METHODS:
        raise ValueError(f"unknown reference method '{method}'; choose from "
                         f"{', '.join(REFERENCE_METHODS)}")
    if method == "vtk":
        return render(grid, prop, reference_mapper(), view, size, actors=actors)
    if actors:
        raise ValueError("the exact reference cannot draw opaque actors; use method='vtk'")
    return exact_reference([(grid, prop)], grid.GetBounds(), view, size)


def exact_reference(volumes: Sequence[tuple], bounds: Sequence[float], view: View,
                    size: Tuple[int, int]) -> Rendering:
    """The exact image of ``volumes`` (:func:`spt.raycast.render_volumes`), with the camera
    that :func:`place_camera` places around ``bounds``."""
    window, renderer = make_window(*size)
    place_camera(renderer, bounds, view)
    start = time.perf_counter()
    image = raycast.render_volumes(volumes, renderer.GetActiveCamera(), size)
    seconds = time.perf_counter() - start
    window.Finalize()
    return Rendering(image=image, seconds=seconds, mapper=None)
