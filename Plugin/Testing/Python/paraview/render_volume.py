"""Render a data set as "Volume (SPT)", "Volume (HAVS-like)" or "Volume (PBVR)" with ParaView's own
Python, for the plugin's tests.

Run by pvpython (on its own or connected to a pvserver) and by pvbatch (one rank, or several
under mpirun). Writes the view as a PNG over a black background, so that its RGB is the
volume's premultiplied color (or, with --transparent, as RGBA over a transparent background),
and a JSON report of what was rendered. With --plain, the same data, camera, transfer functions
and settings rendered once more by a new mapper of the same class in a plain VTK window, for
comparison. With --fly-in, the camera then flies into the data in steps, each with a screenshot
and the exact image of its camera.

    pvpython render_volume.py --data mesh.vtk --output spt.png --report report [--plugin SPT.so]

Several scenes in one process (and one connection): their arguments separated by --then,
each a full set; the first's --connect and --plugin hold for all.
"""

import argparse
import json
import os
import sys

from paraview import servermanager, simple

# Each representation type of the plugin: the group of its settings in the Properties panel, the
# prefix of the settings whose names two mappers share (the mapper's own name is without it), and
# the settings that this script's options set.
METHODS = {
    "Volume (SPT)": {"group": "SPT Volume Rendering", "prefix": "",
                     "repetitions": "RepetitionLevel", "seed": "Seed", "target": "TargetError"},
    "Volume (HAVS-like)": {"group": "HAVS-like Volume Rendering", "prefix": "HAVS"},
    "Volume (PBVR)": {"group": "PBVR Volume Rendering", "prefix": "PBVR",
                      "repetitions": "PBVRRepetitionLevel", "seed": "PBVRSeed"},
}


def parse_arguments(argv):
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--data", required=True, help="a legacy .vtk file or a .pvtk of pieces")
    parser.add_argument("--output", required=True, help="the PNG to write")
    parser.add_argument("--report", required=True, help="JSON reports go to REPORT.rankN.json")
    parser.add_argument("--plugin", help="load this plugin (else PV_PLUGIN_PATH has loaded it)")
    parser.add_argument("--connect", help="host:port of a pvserver to connect to")
    parser.add_argument("--size", type=int, default=200)
    parser.add_argument("--representation", default="Volume (SPT)")
    parser.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                        type=lambda item: item.split("=", 1),
                        help="a setting of the representation, by its name")
    parser.add_argument("--repetitions", type=int, default=16)
    parser.add_argument("--target-error", type=float, default=0.0,
                        help="SPT's Target Error (default 0: exactly --repetitions)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--other-seed", type=int,
                        help="then draw the view again with this seed (every volume's), into "
                        "OUTPUT with .seedN before its suffix")
    parser.add_argument("--view-axis", choices=("x", "y", "z"), default="z",
                        help="look along this axis (ParaView's default: z)")
    parser.add_argument("--like", help="an earlier report (JSON) whose camera, scalar range and "
                        "unit distance to use, for a part of that data set")
    parser.add_argument("--transparent", action="store_true",
                        help="RGBA over a transparent background instead of RGB over black")
    parser.add_argument("--second-offset", metavar="FX,FY,FZ",
                        help="show the data a second time, in a second representation of the "
                        "same kind, moved by these fractions of its extent (its Translation)")
    parser.add_argument("--second-before", action="store_true",
                        help="show the second representation before the first")
    parser.add_argument("--opaque-sphere", action="store_true",
                        help="also show an opaque sphere in the middle of the data: ParaView's "
                        "Sphere source, of which each rank makes a part")
    parser.add_argument("--fly-in", type=float, nargs="+", metavar="DOLLY",
                        help="then turn the camera and dolly it in by these factors from the "
                        "framed view, increasing: for each, a screenshot over a transparent "
                        "background (OUTPUT with .dollyDOLLY before its suffix) and the exact "
                        "image of its camera by spt.raycast (the same with .npy)")
    parser.add_argument("--plain", help="also write this PNG: the same scene rendered by a "
                        "plain VTK pipeline (pvpython on its own only)")
    return parser.parse_args(argv)


def documentation(display, name):
    doc = display.GetProperty(name).SMProperty.GetDocumentation()
    return " ".join(doc.GetDescription().split()) if doc else ""


def property_groups(display):
    proxy = display.SMProxy
    groups = {}
    for index in range(proxy.GetNumberOfPropertyGroups()):
        group = proxy.GetPropertyGroup(index)
        names = [group.GetPropertyName(i) for i in range(group.GetNumberOfProperties())]
        groups[group.GetXMLLabel() or ""] = names
    return groups


def mapper_object(display):
    """This process's mapper of the active representation (vtkPVCompositeRepresentation ->
    vtkTetrahedralVolumeRepresentation -> its volume mapper)."""
    active = display.GetClientSideObject().GetActiveRepresentation()
    return active.GetActiveVolumeMapper() if hasattr(active, "GetActiveVolumeMapper") else None


def setup_view(size):
    view = simple.CreateView("RenderView")
    view.ViewSize = [size, size]
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [0.0, 0.0, 0.0]
    # ParaView 5.11 turns FXAA on by default and applies it where the image is composited or
    # sent to a client (pvbatch under MPI, pvserver), not in a single pvpython: it smooths the
    # noise of a stochastic image, so images of the three would not compare. (With FXAA and a
    # transparent background it also clears some opaque pixels.)
    view.UseFXAA = 0
    return view


def mapper_settings(display, args):
    """Exposed name: the mapper's own name, of every setting in the representation's group."""
    chosen = METHODS[args.representation]
    prefix = chosen["prefix"]
    return {name: name[len(prefix):] if prefix and name.startswith(prefix) else name
            for name in property_groups(display)[chosen["group"]]}


def _is_double(display, name):
    return display.SMProxy.GetProperty(name).IsA("vtkSMDoubleVectorProperty")


def get_setting(display, name):
    """A setting as its number (an enumeration's value, not its text)."""
    value = display.SMProxy.GetProperty(name).GetElement(0)
    return float(value) if _is_double(display, name) else int(value)


def set_setting(display, name, value):
    value = float(value) if _is_double(display, name) else int(value)
    display.SMProxy.GetProperty(name).SetElement(0, value)
    display.SMProxy.UpdateVTKObjects()


def show_volume(reader, view, args, like):
    display = simple.Show(reader, view)
    simple.ColorBy(display, ("POINTS", "field"))
    if like:
        for function in (simple.GetColorTransferFunction("field"),
                         simple.GetOpacityTransferFunction("field")):
            function.RescaleTransferFunction(*like["scalar_range"])
        display.ScalarOpacityUnitDistance = like["unit_distance"]
    else:
        display.RescaleTransferFunctionToDataRange(False, True)
    display.SetRepresentationType(args.representation)
    # What the representation starts with: the defaults the plugin's XML declares.
    defaults = {name: get_setting(display, name) for name in mapper_settings(display, args)}
    chosen = METHODS[args.representation]
    if "target" in chosen:
        set_setting(display, chosen["target"], args.target_error)
    if "repetitions" in chosen:
        set_setting(display, chosen["repetitions"], args.repetitions)
        set_setting(display, chosen["seed"], args.seed)
    for name, value in args.set:
        set_setting(display, name, value)
    return display, defaults


def show_second(view, args, like):
    """The data once more, from a second reader, in a second representation of the same kind
    and settings, moved into the first by its own transform (the representation's Translation,
    named Position before ParaView 5.13; its vtkVolume's)."""
    reader = simple.LegacyVTKReader(FileNames=[args.data])
    bounds = reader.GetDataInformation().GetBounds()
    fractions = [float(f) for f in args.second_offset.split(",")]
    display, _ = show_volume(reader, view, args, like)
    offset = [f * (bounds[2 * a + 1] - bounds[2 * a]) for a, f in enumerate(fractions)]
    name = "Translation" if "Translation" in display.ListProperties() else "Position"
    setattr(display, name, offset)
    return reader, display


def show_sphere(reader, view):
    """An opaque, unlit sphere in the middle of the data, with a quarter of its smallest
    extent as radius. The Sphere source makes a part of it on each rank (its pieces), so
    under MPI each rank draws opaque geometry that the others do not."""
    bounds = reader.GetDataInformation().GetBounds()
    sphere = simple.Sphere(
        Center=[(bounds[2 * a] + bounds[2 * a + 1]) / 2.0 for a in range(3)],
        Radius=0.25 * min(bounds[2 * a + 1] - bounds[2 * a] for a in range(3)),
        ThetaResolution=48, PhiResolution=48)
    display = simple.Show(sphere, view)
    display.ColorArrayName = ["POINTS", ""]
    display.AmbientColor = display.DiffuseColor = [0.9, 0.55, 0.2]
    display.Ambient = 1.0
    display.Diffuse = 0.0
    display.Specular = 0.0
    return sphere


def look_along(view, axis):
    """Look along the axis from its negative side, the whole data set in view."""
    direction = {"x": (1.0, 0.0, 0.0), "y": (0.0, 1.0, 0.0), "z": (0.0, 0.0, 1.0)}[axis]
    view.CameraFocalPoint = [0.0, 0.0, 0.0]
    view.CameraPosition = [-d for d in direction]
    view.CameraViewUp = [0.0, 1.0, 0.0] if axis == "z" else [0.0, 0.0, 1.0]
    simple.ResetCamera(view)


def loaded_libraries(word):
    """The shared libraries of this process whose file name contains ``word`` (Linux)."""
    try:
        with open("/proc/self/maps") as maps:
            paths = {line.split()[-1] for line in maps if "/" in line}
    except OSError:
        return []
    return sorted(path for path in paths if word in path.rsplit("/", 1)[-1])


CAMERA = ("CameraPosition", "CameraFocalPoint", "CameraViewUp", "CameraViewAngle",
          "CameraParallelScale")


def elements(proxy, name):
    prop = proxy.SMProxy.GetProperty(name)
    values = [prop.GetElement(i) for i in range(prop.GetNumberOfElements())]
    return values if len(values) > 1 else values[0]


def get_camera(view):
    return {name: elements(view, name) for name in CAMERA}


def set_camera(view, camera):
    for name in CAMERA:
        view.SetPropertyWithName(name, camera[name])


def local_mapper_report(display, names):
    """What this process's mapper drew. Importing spt inside ParaView's Python wraps the
    plugin's mappers as spt.vtkSPTVolumeMapper, spt.vtkHAVSVolumeMapper, ..."""
    import spt

    info = {"spt_file": spt.__file__, "spt_libraries": loaded_libraries("SPT")}
    mapper = mapper_object(display)
    if mapper is not None:
        info["mapper_class"] = mapper.GetClassName()
        info["mapper_is_spt"] = isinstance(mapper, spt.vtkSPTVolumeMapper)
        info["mapper_is_wrapped"] = isinstance(mapper, getattr(spt, mapper.GetClassName(), ()))
        if hasattr(mapper, "GetNumberOfTetrahedra"):
            info["tetrahedra"] = int(mapper.GetNumberOfTetrahedra())
        if hasattr(mapper, "GetInput") and mapper.GetInput() is not None:
            info["mapper_input_bounds"] = list(mapper.GetInput().GetBounds())
        info["mapper_settings"] = {
            exposed: getattr(mapper, "Get" + own)()
            for exposed, own in names.items() if hasattr(mapper, "Get" + own)}
    return info


def render_plain(display, view, args):
    """The scene as this process drew it (the mapper's input, the volume property, the camera
    and the settings), drawn again by a new mapper of the same class in a plain VTK render
    window over black: what a VTK user of the spt package gets."""
    import spt
    from spt import metrics, render

    representation = display.GetClientSideObject().GetActiveRepresentation()
    drawn = representation.GetActiveVolumeMapper()
    mapper = getattr(spt, drawn.GetClassName())()
    for own in mapper_settings(display, args).values():
        getattr(mapper, "Set" + own)(getattr(drawn, "Get" + own)())
    window, renderer = render.make_window(args.size, args.size)
    volume = render.add_volume(renderer, drawn.GetInput(), representation.GetActor().GetProperty(),
                               mapper)
    renderer.GetActiveCamera().DeepCopy(view.GetRenderer().GetActiveCamera())
    renderer.ResetCameraClippingRange()
    window.Render()
    metrics.write_png(args.plain, render.read_rgba(window)[..., :3])
    renderer.RemoveVolume(volume)
    window.Finalize()


def save_with_other_seed(displays, view, args):
    """The view once more, each volume with Seed --other-seed: an image independent of the
    first, of the same scene."""
    chosen = METHODS[args.representation]
    if "seed" not in chosen:
        raise SystemExit(f"--other-seed: {args.representation} has no seed")
    for display in displays:
        set_setting(display, chosen["seed"], args.other_seed)
    stem, suffix = os.path.splitext(args.output)
    simple.SaveScreenshot(f"{stem}.seed{args.other_seed}{suffix}", view,
                          ImageResolution=[args.size, args.size],
                          TransparentBackground=int(args.transparent))


def report(display, defaults, reader, view, args, flight):
    """Every rank makes the same ParaView calls (some gather over the ranks); each writes its
    own file."""
    module = servermanager.vtkProcessModule.GetProcessModule()
    rank = module.GetPartitionId()
    info = {"rank": rank, "ranks": module.GetNumberOfLocalPartitions(), "fly_in": flight}
    info["representation"] = display.SMProxy.GetProperty("Representation").GetElement(0)
    info["representation_types"] = list(display.GetProperty("Representation").Available)
    names = mapper_settings(display, args)
    info["settings"] = {name: get_setting(display, name) for name in names}
    info["defaults"] = defaults
    info["documentation"] = {name: documentation(display, name) for name in names}
    info["property_groups"] = property_groups(display)
    info["panel_visibility"] = {name: display.GetProperty(name).SMProperty.GetPanelVisibility()
                                for name in names}
    info["cells"] = int(reader.GetDataInformation().GetNumberOfCells())
    info["camera"] = get_camera(view)
    points = elements(simple.GetOpacityTransferFunction("field"), "Points")
    info["scalar_range"] = [points[0], points[-4]]
    info["unit_distance"] = elements(display, "ScalarOpacityUnitDistance")
    if hasattr(simple, "ProcessIdScalars"):  # ParaView 5
        process_ids = simple.ProcessIdScalars(Input=reader)
        array = "ProcessId"
    else:  # ParaView 6 has only its successor, "Process Ids"
        process_ids = simple.ProcessIds(Input=reader)
        array = "PointProcessIds"
    process_ids.UpdatePipeline()
    info["process_ids"] = list(process_ids.PointData[array].GetRange())
    simple.Delete(process_ids)
    info.update(local_mapper_report(display, names))
    with open("%s.rank%d.json" % (args.report, rank), "w") as stream:
        json.dump(info, stream, indent=1)


def fly_in(display, view, args, references):
    """Turn the camera, then dolly it in by each --fly-in factor, with a screenshot and the
    exact image of each step (``references`` keeps those by camera, for the next scene); each
    step's dolly factor and clipping range, as ParaView reset it."""
    import numpy as np
    from spt import raycast

    camera = view.GetActiveCamera()
    camera.Elevation(25.0)
    camera.Azimuth(35.0)
    simple.ResetCamera(view)
    stem, _ = os.path.splitext(args.output)
    steps, done = [], 1.0
    for dolly in args.fly_in:
        camera.Dolly(dolly / done)
        done = dolly
        simple.SaveScreenshot(f"{stem}.dolly{dolly:g}.png", view,
                              ImageResolution=[args.size, args.size], TransparentBackground=1)
        drawn = view.GetRenderer().GetActiveCamera()
        # What places the camera's rays: the same key, the same exact image.
        key = (drawn.GetPosition(), drawn.GetFocalPoint(), drawn.GetViewUp(),
               drawn.GetViewAngle(), drawn.GetClippingRange(), drawn.GetParallelProjection(),
               drawn.GetParallelScale())
        if key not in references:
            volume = display.GetClientSideObject().GetActiveRepresentation().GetActor()
            references[key] = raycast.render(mapper_object(display).GetInput(),
                                             volume.GetProperty(), drawn, (args.size, args.size))
        np.save(f"{stem}.dolly{dolly:g}.npy", references[key])
        steps.append({"dolly": dolly, "clipping_range": list(drawn.GetClippingRange())})
    return steps


def render_scene(args, references):
    """Show, screenshot and report one scene, then delete what it made; ``references`` holds
    the exact images of the fly-ins so far."""
    reader = simple.LegacyVTKReader(FileNames=[args.data])
    view = setup_view(args.size)
    like = None
    if args.like:
        with open(args.like) as stream:
            like = json.load(stream)
    second = show_second(view, args, like) if args.second_before else None
    display, defaults = show_volume(reader, view, args, like)
    if args.second_offset and not args.second_before:
        second = show_second(view, args, like)
    sphere = show_sphere(reader, view) if args.opaque_sphere else None
    if like:
        set_camera(view, like["camera"])
    else:
        look_along(view, args.view_axis)
    simple.SaveScreenshot(args.output, view, ImageResolution=[args.size, args.size],
                          TransparentBackground=int(args.transparent))
    flight = fly_in(display, view, args, references) if args.fly_in else None
    report(display, defaults, reader, view, args, flight)
    if args.other_seed is not None:
        save_with_other_seed([display] + ([second[1]] if second else []), view, args)
    if args.plain:
        render_plain(display, view.GetClientSideObject(), args)

    # Leave nothing behind for the exit or the next scene: the view goes before the data.
    sources = [reader] + ([second[0]] if second else []) + ([sphere] if sphere else [])
    for source in sources:
        simple.Hide(source, view)
    simple.Delete(view)
    for source in sources[1:] + sources[:1]:
        simple.Delete(source)


def scenes_of(argv):
    """The argument lists of the scenes, separated by --then."""
    scenes = [[]]
    for argument in argv:
        if argument == "--then":
            scenes.append([])
        else:
            scenes[-1].append(argument)
    return [parse_arguments(scene) for scene in scenes]


def main(argv):
    scenes = scenes_of(argv)
    first = scenes[0]
    connected = bool(first.connect)
    if connected:
        host, port = first.connect.rsplit(":", 1)
        simple.Connect(host, int(port))
    if first.plugin:
        # Where ParaView needs it: on the server, if any, and in this process.
        if connected:
            simple.LoadPlugin(first.plugin, remote=True)
        simple.LoadPlugin(first.plugin, remote=False)
    references = {}
    for args in scenes:
        render_scene(args, references)
    if connected:
        simple.Disconnect()


if __name__ == "__main__":
    # No sys.exit(): under pvbatch every rank must leave the script normally, so that ParaView
    # finalizes MPI; an exception still makes the process fail.
    main(sys.argv[1:])
