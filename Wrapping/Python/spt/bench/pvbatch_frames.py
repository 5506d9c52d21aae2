"""Frames of one volume representation in pvbatch, for the ``parallel`` benchmark section.

Run by ``mpirun -np N pvbatch pvbatch_frames.py ...`` with the SPT plugin on every rank
(PV_PLUGIN_PATH): reads a .pvtk of pieces (one per rank), shows it as the given
representation, and times on rank 0 the reading, the first render (ParaView's redistribution
where the representation asks for it, and the frame) and later renders (the camera turned by
one degree each), in wall time. Writes a JSON report.
"""

import argparse
import json
import time

from paraview import simple

# The settings that make a render draw a fixed amount of work, by representation.
FIXED_WORK = {
    "Volume (SPT)": {"RepetitionLevel": 16, "TargetError": 0.0, "AutoAdjustRepetitions": 0},
    "Volume (PBVR)": {"PBVRRepetitionLevel": 16},
}


def parse():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--data", required=True)
    parser.add_argument("--representation", required=True)
    parser.add_argument("--output", required=True)
    parser.add_argument("--size", type=int, default=256)
    parser.add_argument("--frames", type=int, default=3)
    return parser.parse_args()


def set_property(display, name, value):
    prop = display.SMProxy.GetProperty(name)
    if prop is not None:
        prop.SetElement(0, value)
        display.SMProxy.UpdateVTKObjects()


def main():
    arguments = parse()
    view = simple.CreateView("RenderView")
    view.ViewSize = [arguments.size, arguments.size]
    view.OrientationAxesVisibility = 0
    view.UseFXAA = 0
    reader = simple.LegacyVTKReader(FileNames=[arguments.data])
    start = time.perf_counter()
    display = simple.Show(reader, view)  # reads the pieces
    read_seconds = time.perf_counter() - start
    arrays = reader.PointData.keys()
    simple.ColorBy(display, ("POINTS", arrays[0]))
    display.RescaleTransferFunctionToDataRange(False, True)
    display.SetRepresentationType(arguments.representation)
    for name, value in FIXED_WORK.get(arguments.representation, {}).items():
        set_property(display, name, value)
    simple.ResetCamera(view)
    frames = []
    for frame in range(arguments.frames):
        if frame:
            view.GetActiveCamera().Azimuth(1.0)
        begin = time.perf_counter()
        simple.Render(view)
        frames.append(time.perf_counter() - begin)
    with open(arguments.output, "w") as report:
        json.dump({"representation": arguments.representation, "frames": frames,
                   "read_seconds": read_seconds}, report)


main()
