"""Fly ParaView's camera into a volume, for the plugin's tests.

Run by pvpython. Shows a data set as one of the plugin's representation types, then dollies
the view's own camera towards the focal point in steps, from outside the data to deep inside
it, and renders each step as ParaView does (the view resets its clipping range). For each
step it writes the screenshot over a transparent background (premultiplied RGBA), and the
exact image of the same camera from spt.raycast as a NumPy array. Each representation type
given flies in turn, in one process, into DIR/<its index>/; the exact image of a camera that
an earlier flight saw is computed once:

    pvpython fly_in.py --data mesh.vtk --plugin SPT.so --output-dir DIR --dolly 1 4 ... \
        --representation "Volume (SPT)" "Volume (HAVS-like)"
"""

import argparse
import json
import pathlib
import sys

import numpy as np
from paraview import simple

import render_volume as rv


def parse_arguments(argv):
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--data", required=True, help="a legacy .vtk file")
    parser.add_argument("--plugin", required=True, help="the plugin to load")
    parser.add_argument("--output-dir", required=True, type=pathlib.Path)
    parser.add_argument("--representation", nargs="+", default=["Volume (SPT)"])
    parser.add_argument("--size", type=int, default=96)
    parser.add_argument("--repetitions", type=int, default=16)
    parser.add_argument("--dolly", type=float, nargs="+", required=True,
                        help="the camera's dolly factors from the framed view, increasing")
    return parser.parse_args(argv)


def volume_arguments(args, representation):
    """What render_volume's show_volume() needs: the representation and its settings, with
    no error target, so that the repetitions are the ones asked for."""
    return rv.parse_arguments([
        "--data", args.data, "--output", "unused.png", "--report", "unused",
        "--representation", representation, "--repetitions", str(args.repetitions),
        "--seed", "1", "--target-error", "0"])


def camera_key(camera):
    """What places a camera's rays: two cameras with the same key see the same image."""
    return (camera.GetPosition(), camera.GetFocalPoint(), camera.GetViewUp(),
            camera.GetViewAngle(), camera.GetClippingRange(), camera.GetParallelProjection(),
            camera.GetParallelScale())


def fly_in(display, view, args, directory, references):
    """Fly the view's camera in, writing each step's screenshot and exact image to
    ``directory``; ``references`` holds the exact images by camera_key()."""
    from spt import raycast

    representation = display.GetClientSideObject().GetActiveRepresentation()
    rv.look_along(view, "z")
    camera = view.GetActiveCamera()
    camera.Elevation(25.0)
    camera.Azimuth(35.0)
    simple.ResetCamera(view)
    steps = []
    done = 1.0
    for dolly in args.dolly:
        camera.Dolly(dolly / done)
        done = dolly
        name = f"dolly{dolly:g}"
        simple.SaveScreenshot(str(directory / f"{name}.png"), view,
                              ImageResolution=[args.size, args.size], TransparentBackground=1)
        renderer_camera = view.GetRenderer().GetActiveCamera()
        key = camera_key(renderer_camera)
        if key not in references:
            references[key] = raycast.render(rv.mapper_object(display).GetInput(),
                                             representation.GetActor().GetProperty(),
                                             renderer_camera, (args.size, args.size))
        np.save(directory / f"{name}.npy", references[key])
        steps.append({"dolly": dolly, "name": name,
                      "representation": display.SMProxy.GetProperty("Representation")
                      .GetElement(0),
                      "mapper_class": rv.mapper_object(display).GetClassName(),
                      "clipping_range": list(renderer_camera.GetClippingRange()),
                      "position": list(renderer_camera.GetPosition())})
    (directory / "steps.json").write_text(json.dumps(steps, indent=1))


def main(argv):
    args = parse_arguments(argv)
    rv.load_plugin(args.plugin, False)
    reader = simple.LegacyVTKReader(FileNames=[args.data])
    view = rv.setup_view(args.size)
    references = {}
    for index, representation in enumerate(args.representation):
        directory = args.output_dir / str(index)
        directory.mkdir(parents=True, exist_ok=True)
        display, _ = rv.show_volume(reader, view, volume_arguments(args, representation), None)
        fly_in(display, view, args, directory, references)
    simple.Hide(reader, view)
    simple.Delete(view)
    simple.Delete(reader)


if __name__ == "__main__":
    main(sys.argv[1:])
