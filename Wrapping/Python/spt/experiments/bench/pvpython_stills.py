"""Still and interactive renders of one data set in a ParaView view, for the ``paraview``
benchmark section.

Run by pvpython with the SPT plugin (``--plugin``, or loaded from PV_PLUGIN_PATH) and the
spt package on PYTHONPATH. Shows the data set colored by ``--array`` with ParaView's default
transfer functions (rescaled to the data's range) in a view of ``--size`` pixels, the camera
turned by ``--azimuth`` and ``--elevation`` from ParaView's own and reset, and for each
representation in turn, at its defaults: three still renders (``StillRender``, finished with
``WaitForCompletion``; the first builds what the later ones reuse), the image the second
left in the view (over black: the premultiplied color), a screenshot over a transparent
background (its alpha too), and six interactive renders (``InteractiveRender``), the camera
turned by half a degree before each, as a drag turns it (the median of the last three is
reported). The exact
image of the same camera and size (spt.raycast, on the tetrahedra the representation draws
and its volume property) is the reference of both images; it is cached in ``--references``.
Writes a JSON report and each image as PNG into ``--output``.
"""

import argparse
import hashlib
import json
import pathlib
import time

import numpy as np
from paraview import simple
from vtkmodules.util.numpy_support import vtk_to_numpy

STILL_RENDERS = 3
# Interactive renders as while dragging: the first ones time and size what the later reuse.
INTERACTIVE_RENDERS = 6


def parse():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--data", required=True, help="a legacy .vtk or an Exodus II file")
    parser.add_argument("--array", required=True, help="the point array to color by")
    parser.add_argument("--scene", required=True, help="the scene's name in the report")
    parser.add_argument("--output", required=True, type=pathlib.Path)
    parser.add_argument("--references", required=True, type=pathlib.Path)
    parser.add_argument("--plugin", help="the SPT plugin (else PV_PLUGIN_PATH loads it)")
    parser.add_argument("--size", default="1280,800", help="WIDTH,HEIGHT")
    parser.add_argument("--representation", action="append", required=True)
    parser.add_argument("--azimuth", type=float, default=35.0)
    parser.add_argument("--elevation", type=float, default=25.0)
    return parser.parse_args()


def read(path, array):
    if path.endswith((".ex2", ".exo", ".e")):
        reader = simple.ExodusIIReader(FileName=[path])
        reader.PointVariables = [array]
        return simple.MergeBlocks(Input=reader)
    return simple.LegacyVTKReader(FileNames=[path])


def make_view(size):
    view = simple.CreateView("RenderView")
    view.ViewSize = list(size)
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [0.0, 0.0, 0.0]
    view.UseFXAA = 0  # FXAA would smooth a stochastic image's noise
    return view


def place_camera(view, azimuth, elevation):
    simple.ResetCamera(view)
    camera = view.GetActiveCamera()
    camera.Elevation(elevation)
    camera.Azimuth(azimuth)
    camera.OrthogonalizeViewUp()
    simple.ResetCamera(view)


def timed(render, window):
    start = time.perf_counter()
    render()
    window.WaitForCompletion()
    return time.perf_counter() - start


def spt_state(mapper):
    """The repetitions of the last SPT render and its estimated error, or {}."""
    import spt  # noqa: F401  (wraps the plugin's mapper as spt's class)

    if not hasattr(mapper, "GetLastRepetitionCount"):
        return {}
    return {"repetitions": int(mapper.GetLastRepetitionCount()),
            "estimated_error": float(mapper.GetEstimatedError()),
            "target_error": float(mapper.GetTargetError()),
            "repetition_level": int(mapper.GetRepetitionLevel()),
            "sample_distance": float(mapper.GetImageSampleDistance())}


def screenshot(view, path, size):
    """The view over a transparent background as premultiplied float RGBA (ParaView's
    transparent screenshots store straight color)."""
    from spt import metrics
    from vtkmodules.vtkIOImage import vtkPNGReader

    simple.SaveScreenshot(str(path), view, ImageResolution=list(size), TransparentBackground=1)
    reader = vtkPNGReader()
    reader.SetFileName(str(path))
    reader.Update()
    rgba = metrics.from_vtk_image(reader.GetOutput(), as_float_rgba=True)
    rgba[..., :3] *= rgba[..., 3:]
    return rgba


def file_name(representation):
    """The representation's name as a file name: Volume_SPT for "Volume (SPT)"."""
    return representation.replace(" ", "_").replace("(", "").replace(")", "")


def view_image(window):
    """What the view shows after its last render, over its black background: the volume's
    premultiplied color, as float RGB, row 0 at the top."""
    from spt import metrics
    from vtkmodules.vtkRenderingCore import vtkWindowToImageFilter

    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.SetInputBufferTypeToRGB()
    grab.ReadFrontBufferOff()
    grab.ShouldRerenderOff()
    grab.Update()
    return metrics.from_vtk_image(grab.GetOutput(), as_float_rgba=True)[..., :3]


def drag_renders(view, window):
    """The times of INTERACTIVE_RENDERS interactive renders, the camera turned by half a
    degree before each, as a drag turns it, and turned back after them."""
    camera = view.GetActiveCamera()
    times = []
    for _ in range(INTERACTIVE_RENDERS):
        camera.Azimuth(0.5)
        times.append(timed(view.SMProxy.InteractiveRender, window))
    camera.Azimuth(-0.5 * INTERACTIVE_RENDERS)
    return times


def measure(view, display, representation, size, output):
    """Still renders (the second timed and kept), a screenshot over a transparent
    background and interactive renders of one representation."""
    display.SetRepresentationType(representation)
    window = view.GetRenderWindow()
    still = [timed(view.StillRender, window) for _ in range(2)]
    shown = view_image(window)
    active = display.GetClientSideObject().GetActiveRepresentation()
    mapper, actor = active.GetActiveVolumeMapper(), active.GetActor()
    row = {"representation": representation, "mapper": mapper.GetClassName(),
           "still": spt_state(mapper)}
    still += [timed(view.StillRender, window) for _ in range(STILL_RENDERS - 2)]
    row.update(still_seconds=still, seconds=still[1])
    shot = output / f"{file_name(representation)}.png"
    image = {"shown": shown, "rgba": screenshot(view, shot, size)}
    interactive = drag_renders(view, window)
    row.update(interactive_seconds=float(np.median(interactive[-3:])),
               interactive_all_seconds=interactive,
               desired_update_rate=float(window.GetDesiredUpdateRate()),
               allotted_seconds=float(actor.GetAllocatedRenderTime()),
               used_lod=bool(view.GetClientSideObject().GetUsedLODForLastRender()),
               interactive=spt_state(mapper))
    view.StillRender()
    return row, image, mapper, actor


def rgb_rmse(shown, exact):
    """RMSE of the view's color against the reference's premultiplied color, over the pixels
    that either covers (the reference's alpha or the view's color above 1/255)."""
    covered = (exact[..., 3] > 1.0 / 255.0) | (shown.max(axis=-1) > 1.0 / 255.0)
    difference = (shown - exact[..., :3])[covered]
    return float(np.sqrt(np.mean(difference ** 2))) if difference.size else 0.0


def digest(grid, prop, camera, size):
    """A digest of what the reference depends on: the tetrahedra, the scalars, the transfer
    functions, the camera and the size."""
    value = hashlib.sha1()
    value.update(vtk_to_numpy(grid.GetPoints().GetData()).tobytes())
    value.update(vtk_to_numpy(grid.GetCells().GetConnectivityArray()).tobytes())
    scalars = grid.GetPointData().GetScalars()
    if scalars is not None:
        value.update(vtk_to_numpy(scalars).tobytes())
    functions = [prop.GetScalarOpacity(), prop.GetRGBTransferFunction()]
    low, high = functions[1].GetRange()
    samples = np.linspace(low, high, 257)
    value.update(np.array([functions[0].GetValue(x) for x in samples]).tobytes())
    colors = [0.0] * 3
    for x in samples:
        functions[1].GetColor(x, colors)
        value.update(np.array(colors).tobytes())
    value.update(np.array([prop.GetScalarOpacityUnitDistance(), *size]).tobytes())
    for get in (camera.GetPosition, camera.GetFocalPoint, camera.GetViewUp,
                camera.GetViewAngle, camera.GetClippingRange):
        value.update(np.atleast_1d(np.asarray(get(), dtype=float)).tobytes())
    return value.hexdigest()[:16]


def reference(view, mapper, actor, size, directory, arguments):
    """The exact image of the view's camera, cached, and the seconds it took (0 if read).
    The mapper's input with the colored array as its active scalars (ParaView's mappers draw
    the array by name)."""
    from spt import raycast

    drawn, prop = mapper.GetDataSetInput(), actor.GetProperty()
    grid = drawn.NewInstance()
    grid.ShallowCopy(drawn)
    grid.GetPointData().SetActiveScalars(arguments.array)
    scene = arguments.scene
    camera = view.GetRenderer().GetActiveCamera()
    path = directory / f"{scene}-{size[0]}x{size[1]}-{digest(grid, prop, camera, size)}.npy"
    if path.exists():
        return np.load(path), 0.0
    start = time.perf_counter()
    image = raycast.render(grid, prop, camera, tuple(size))
    seconds = time.perf_counter() - start
    directory.mkdir(parents=True, exist_ok=True)
    np.save(path, image)
    return image, seconds


def main():
    from spt import metrics

    arguments = parse()
    size = [int(v) for v in arguments.size.split(",")]
    arguments.output.mkdir(parents=True, exist_ok=True)
    if arguments.plugin:
        simple.LoadPlugin(arguments.plugin, remote=False)
    source = read(arguments.data, arguments.array)
    view = make_view(size)
    display = simple.Show(source, view)
    simple.ColorBy(display, ("POINTS", arguments.array))
    display.RescaleTransferFunctionToDataRange(False, True)
    place_camera(view, arguments.azimuth, arguments.elevation)
    rows, exact = [], None
    for representation in arguments.representation:
        row, image, mapper, actor = measure(view, display, representation, size,
                                            arguments.output)
        if exact is None:
            exact, seconds = reference(view, mapper, actor, size, arguments.references,
                                       arguments)
            metrics.write_png(arguments.output / "reference.png", exact)
            report = {"reference_seconds": seconds,
                      "read_back_floor": metrics.read_back_floor(exact),
                      "reference_alpha_mean": float(exact[..., 3].mean())}
        metrics.write_png(arguments.output / f"{file_name(representation)}-shown.png",
                          np.dstack([image["shown"], np.ones(image["shown"].shape[:2])]))
        row.update(scene=arguments.scene, cells=int(mapper.GetDataSetInput().GetNumberOfCells()),
                   width=size[0], height=size[1], rmse=rgb_rmse(image["shown"], exact),
                   rmse_rgba=metrics.rmse(image["rgba"], exact),
                   alpha_mean=float(image["rgba"][..., 3].mean()))
        rows.append(row)
    report.update(scene=arguments.scene, rows=rows,
                  unit_distance=float(display.ScalarOpacityUnitDistance))
    (arguments.output / "report.json").write_text(json.dumps(report, indent=1))
    simple.Hide(source, view)
    simple.Delete(view)
    simple.Delete(source)


main()
