"""Drag the mouse in a ParaView render view showing "Volume (SPT)", for the time-budget test.

Run by pvpython. The drags go through ParaView's own interaction path: the view's interactor
(set up by vtkSMRenderViewProxy), ParaView's interactor style, and the helper that calls the
view proxy's InteractiveRender() while the mouse moves and StillRender() when it is released,
as the GUI does. After every render of the view the report records the render window's desired
update rate (ParaView sets 5 for interactive renders and 0.002 for still ones), the time the
renderer allotted to the volume, whether ParaView drew its level-of-detail stand-in, and the
repetitions in the SPT image and its sample distance. Writes REPORT.json and the views as
PNG in the output directory.

    pvpython interactive_renders.py --plugin SPT.so --data mesh.vtk --output DIR
"""

import argparse
import json
import pathlib
import sys

from paraview import simple

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import render_volume  # noqa: E402  (setup_view, look_along)


def parse_arguments(argv):
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--plugin", required=True)
    parser.add_argument("--data", required=True, help="a legacy .vtk file")
    parser.add_argument("--output", required=True, help="directory for report.json and PNGs")
    parser.add_argument("--size", type=int, default=160)
    parser.add_argument("--repetitions", type=int, default=16)
    return parser.parse_args(argv)


class Recorder:
    """What each render of the view drew, in order, under the name of the current step."""

    def __init__(self, view, display):
        import spt  # noqa: F401 -- wraps the plugin's mapper (GetLastRepetitionCount, ...)

        self.view = view.GetClientSideObject()
        representation = display.GetClientSideObject().GetActiveRepresentation()
        self.mapper = representation.GetActiveVolumeMapper()
        self.volume = representation.GetActor()
        self.step = "start"
        self.renders = []
        view.SMProxy.AddObserver("EndEvent", self.record)

    def record(self, caller, event):
        self.renders.append({
            "step": self.step,
            "desired_update_rate": self.view.GetRenderWindow().GetDesiredUpdateRate(),
            "allotted_seconds": self.volume.GetAllocatedRenderTime(),
            "used_lod": bool(self.view.GetUsedLODForLastRender()),
            "repetitions": self.mapper.GetLastRepetitionCount(),
            "seconds_per_repetition": self.mapper.GetTimePerRepetition(),
            "sample_distance": self.mapper.GetImageSampleDistance(),
        })


def drag(view, moves, size):
    """Press the left button in the middle of the view, move right in steps, release."""
    interactor = view.GetInteractor()
    middle = size // 2
    interactor.SetEventInformation(middle, middle)
    interactor.InvokeEvent("LeftButtonPressEvent")
    for step in range(1, moves + 1):
        interactor.SetEventInformation(middle + 4 * step, middle)
        interactor.InvokeEvent("MouseMoveEvent")
    interactor.InvokeEvent("LeftButtonReleaseEvent")


def screenshot(view, path, size, interactive):
    """ParaView's own screenshot, taken with an interactive render if asked."""
    view.UseInteractiveRenderingForScreenshots = int(interactive)
    simple.SaveScreenshot(str(path), view, ImageResolution=[size, size])
    view.UseInteractiveRenderingForScreenshots = 0


def drag_and_screenshots(view, recorder, output, size, moves, prefix=""):
    """Steps PREFIXdrag (a drag of `moves` moves), PREFIXscreenshot_interactive and
    PREFIXscreenshot_still (PREFIXinteractive.png and PREFIXstill.png)."""
    recorder.step = f"{prefix}drag"
    drag(view, moves, size)
    for interactive, name in ((True, "interactive"), (False, "still")):
        recorder.step = f"{prefix}screenshot_{name}"
        screenshot(view, output / f"{prefix}{name}.png", size, interactive)


def main(argv):
    args = parse_arguments(argv)
    output = pathlib.Path(args.output)
    simple.LoadPlugin(args.plugin, remote=False)
    reader = simple.LegacyVTKReader(FileNames=[args.data])
    view = render_volume.setup_view(args.size)
    display = simple.Show(reader, view)
    simple.ColorBy(display, ("POINTS", "field"))
    display.RescaleTransferFunctionToDataRange(False, True)
    display.SetRepresentationType("Volume (SPT)")
    display.TargetError = 0.0  # every still render draws RepetitionLevel repetitions
    display.RepetitionLevel = args.repetitions
    # The repetitions' budget alone first; the image's sample distance in the last steps.
    display.AutoAdjustSampleDistances = 0
    render_volume.look_along(view, "z")
    recorder = Recorder(view, display)

    simple.Render(view)
    drag_and_screenshots(view, recorder, output, args.size, 3)

    display.ProgressiveRefinement = 1
    recorder.step = "progressive_still"
    simple.Render(view)
    simple.Render(view)
    recorder.step = "progressive_drag"
    drag(view, 2, args.size)
    recorder.step = "progressive_after"
    simple.Render(view)
    display.ProgressiveRefinement = 0

    # Data above the LOD threshold: ParaView draws its stand-in while the mouse moves.
    view.LODThreshold = 0.0
    recorder.step = "lod_still"
    simple.Render(view)
    recorder.step = "lod_drag"
    drag(view, 2, args.size)
    view.LODThreshold = 1000.0

    display.AutoAdjustRepetitions = 0
    recorder.step = "unadjusted_drag"
    drag(view, 1, args.size)
    display.AutoAdjustRepetitions = 1

    # Where not even one repetition fits an interactive frame (16 samples per pixel here), the
    # image has fewer pixels while the mouse moves, and all of them again when it is released.
    display.AutoAdjustSampleDistances = 1
    display.SubpixelLevel = 4
    recorder.step = "distance_still"
    simple.Render(view)
    drag_and_screenshots(view, recorder, output, args.size, 6, prefix="distance_")

    (output / "report.json").write_text(json.dumps({
        "repetition_level": args.repetitions,
        "renderers": recorder.view.GetRenderWindow().GetRenderers().GetNumberOfItems(),
        "renders": recorder.renders}, indent=1))
    simple.Hide(reader, view)
    simple.Delete(view)
    simple.Delete(reader)


if __name__ == "__main__":
    main(sys.argv[1:])
