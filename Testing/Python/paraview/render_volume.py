"""Render a data set as "Volume (SPT)" with ParaView's own Python, for the plugin's tests.

Run by pvpython (on its own or connected to a pvserver) and by pvbatch (one rank, or several
under mpirun). Writes the view as a PNG over a black background, so that its RGB is the
volume's premultiplied color (or, with --transparent, as RGBA over a transparent background),
and a JSON report of what was rendered.

    pvpython render_volume.py --data mesh.vtk --output spt.png --report report [--plugin SPT.so]
"""

import argparse
import json
import sys

from paraview import servermanager, simple

# The SPT mapper's settings; a mapper with others names its own with --set.
SETTINGS = ("RepetitionLevel", "SubpixelLevel", "Seed", "PreIntegrationScalarResolution",
            "PreIntegrationThicknessResolution", "RepetitionsPerPass", "StratifiedSampling",
            "ProgressiveRefinement")


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
                        help="an integer setting of the representation, by its name")
    parser.add_argument("--repetitions", type=int, default=16)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--use-data-partitions", action="store_true",
                        help="keep the pieces where they were read (no redistribution)")
    parser.add_argument("--view-axis", choices=("x", "y", "z"), default="z",
                        help="look along this axis (ParaView's default: z)")
    parser.add_argument("--like", help="an earlier report (JSON) whose camera, scalar range and "
                        "unit distance to use, for a part of that data set")
    parser.add_argument("--transparent", action="store_true",
                        help="RGBA over a transparent background instead of RGB over black")
    return parser.parse_args(argv)


def load_plugin(path, connected):
    """Load the plugin where ParaView needs it: the server (if any) and this process."""
    if connected:
        simple.LoadPlugin(path, remote=True)
    simple.LoadPlugin(path, remote=False)


def rank_and_ranks():
    module = servermanager.vtkProcessModule.GetProcessModule()
    return module.GetPartitionId(), module.GetNumberOfLocalPartitions()


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
    vtkSPTVolumeRepresentation -> its volume mapper)."""
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


def settings_to_set(args):
    return {name: int(value) for name, value in (item.split("=", 1) for item in args.set)}


def setting_names(args):
    names = list(SETTINGS) if args.representation == "Volume (SPT)" else []
    return names + [name for name in settings_to_set(args) if name not in names]


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
    if args.representation == "Volume (SPT)":
        display.RepetitionLevel = args.repetitions
        display.Seed = args.seed
    for name, value in settings_to_set(args).items():
        display.SetPropertyWithName(name, value)
    display.UseDataPartitions = int(args.use_data_partitions)
    return display


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
    plugin's vtkSPTVolumeMapper as spt.vtkSPTVolumeMapper."""
    import spt

    info = {"spt_file": spt.__file__, "spt_libraries": loaded_libraries("SPT")}
    mapper = mapper_object(display)
    if mapper is not None:
        # Wrapped as its own class once spt (which re-exports the project's mappers) is
        # imported; the plugin's other mappers report what they have of the same.
        info["mapper_class"] = mapper.GetClassName()
        info["mapper_is_spt"] = isinstance(mapper, spt.vtkSPTVolumeMapper)
        if hasattr(mapper, "GetNumberOfTetrahedra"):
            info["tetrahedra"] = int(mapper.GetNumberOfTetrahedra())
        if hasattr(mapper, "GetInput") and mapper.GetInput() is not None:
            info["mapper_input_bounds"] = list(mapper.GetInput().GetBounds())
        info["mapper_settings"] = {name: int(getattr(mapper, "Get" + name)())
                                   for name in names if hasattr(mapper, "Get" + name)}
    return info


def report(display, reader, view, args):
    """Every rank makes the same ParaView calls (some gather over the ranks); each writes its
    own file."""
    rank, ranks = rank_and_ranks()
    info = {"rank": rank, "ranks": ranks}
    info["representation"] = display.SMProxy.GetProperty("Representation").GetElement(0)
    info["representation_types"] = list(display.GetProperty("Representation").Available)
    names = setting_names(args)
    info["settings"] = {name: int(display.GetPropertyValue(name)) for name in names}
    info["documentation"] = {name: documentation(display, name) for name in names}
    info["property_groups"] = property_groups(display)
    info["cells"] = int(reader.GetDataInformation().GetNumberOfCells())
    info["camera"] = get_camera(view)
    points = elements(simple.GetOpacityTransferFunction("field"), "Points")
    info["scalar_range"] = [points[0], points[-4]]
    info["unit_distance"] = elements(display, "ScalarOpacityUnitDistance")
    process_ids = simple.ProcessIdScalars(Input=reader)
    process_ids.UpdatePipeline()
    info["process_ids"] = list(process_ids.PointData["ProcessId"].GetRange())
    simple.Delete(process_ids)
    info.update(local_mapper_report(display, names))
    with open("%s.rank%d.json" % (args.report, rank), "w") as stream:
        json.dump(info, stream, indent=1)


def main(argv):
    args = parse_arguments(argv)
    connected = bool(args.connect)
    if connected:
        host, port = args.connect.rsplit(":", 1)
        simple.Connect(host, int(port))
    if args.plugin:
        load_plugin(args.plugin, connected)

    reader = simple.LegacyVTKReader(FileNames=[args.data])
    view = setup_view(args.size)
    like = None
    if args.like:
        with open(args.like) as stream:
            like = json.load(stream)
    display = show_volume(reader, view, args, like)
    if like:
        set_camera(view, like["camera"])
    else:
        look_along(view, args.view_axis)
    simple.SaveScreenshot(args.output, view, ImageResolution=[args.size, args.size],
                          TransparentBackground=int(args.transparent))
    report(display, reader, view, args)

    # Leave nothing behind for the exit: the view goes before the data.
    simple.Hide(reader, view)
    simple.Delete(view)
    simple.Delete(reader)
    if connected:
        simple.Disconnect()


if __name__ == "__main__":
    # No sys.exit(): under pvbatch every rank must leave the script normally, so that ParaView
    # finalizes MPI; an exception still makes the process fail.
    main(sys.argv[1:])
