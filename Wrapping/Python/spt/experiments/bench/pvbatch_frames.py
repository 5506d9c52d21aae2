"""Frames of one volume representation in pvbatch, for the ``parallel`` benchmark section.

Run by ``mpirun -np N pvbatch --symmetric pvbatch_frames.py ...`` with the SPT plugin on every
rank (PV_PLUGIN_PATH): reads a .pvtk of pieces (one per rank), shows it as the given
representation, and times the reading, the first render (ParaView's redistribution where the
representation asks for it, and the frame) and later renders (the camera turned by one degree
each): wall time on rank 0, and process CPU time (all threads), the largest over the ranks.
SPT draws with the plugin's error target and cap (--target-error, --repetitions). Rank 0
writes a JSON report: those times (later renders: their median) and SPT's repetitions.
"""

import argparse
import json
import statistics
import time

from paraview import simple
from paraview.modules.vtkRemotingCore import vtkProcessModule
from vtkmodules.vtkCommonCore import vtkDoubleArray
from vtkmodules.vtkParallelCore import vtkCommunicator

# Fixed work per render, by representation (SPT's is set from the arguments).
FIXED_WORK = {
    "Volume (PBVR)": {"PBVRRepetitionLevel": 16},
}


def parse():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--data", required=True)
    parser.add_argument("--representation", required=True)
    parser.add_argument("--output", required=True)
    parser.add_argument("--size", type=int, default=256)
    parser.add_argument("--frames", type=int, default=3)
    parser.add_argument("--repetitions", type=int, default=256,
                        help="SPT's RepetitionLevel, the cap with an error target")
    parser.add_argument("--target-error", type=float, default=0.005, help="SPT's TargetError")
    return parser.parse_args()


def over_ranks(values, operation):
    """Each of ``values`` reduced over the ranks with ``operation`` (every rank runs this
    script)."""
    controller = vtkProcessModule.GetProcessModule().GetGlobalController()
    local, result = vtkDoubleArray(), vtkDoubleArray()
    for value in values:
        local.InsertNextValue(value)
    if controller is None or controller.GetNumberOfProcesses() == 1:
        return list(values)
    controller.AllReduce(local, result, operation)
    return [result.GetValue(i) for i in range(result.GetNumberOfTuples())]


def largest_over_ranks(values):
    """Each of ``values``, the largest over the ranks."""
    return over_ranks(values, vtkCommunicator.MAX_OP)


def rescale_to_the_whole(array):
    """The array's color and opacity functions over the range of every rank's data: in
    symmetric mode each rank's data information is its own piece's, and ranks that rescale to
    it draw with transfer functions of their own (SPT refuses them)."""
    low, high = array.GetRange()
    low = over_ranks([low], vtkCommunicator.MIN_OP)[0]
    high = largest_over_ranks([high])[0]
    simple.GetColorTransferFunction(array.Name).RescaleTransferFunction(low, high)
    simple.GetOpacityTransferFunction(array.Name).RescaleTransferFunction(low, high)


def later(frames):
    """The median of the frames after the first (NaN without any)."""
    return statistics.median(frames[1:]) if len(frames) > 1 else float("nan")


def set_property(display, name, value):
    prop = display.SMProxy.GetProperty(name)
    if prop is not None:
        prop.SetElement(0, value)
        display.SMProxy.UpdateVTKObjects()


def spt_counts(display):
    """Rank 0's SPT mapper's repetitions and noise estimate of the last render, or None."""
    import spt  # noqa: F401  (wraps the plugin's mappers as their own classes)

    active = display.GetClientSideObject().GetActiveRepresentation()
    mapper = active.GetActiveVolumeMapper() if hasattr(active, "GetActiveVolumeMapper") else None
    if mapper is None or not hasattr(mapper, "GetLastRepetitionCount"):
        return None
    return [mapper.GetLastRepetitionCount(), mapper.GetEstimatedError()]


def main():
    arguments = parse()
    view = simple.CreateView("RenderView")
    view.ViewSize = [arguments.size, arguments.size]
    view.OrientationAxesVisibility = 0
    view.UseFXAA = 0
    reader = simple.LegacyVTKReader(FileNames=[arguments.data])
    start, cpu = time.perf_counter(), time.process_time()
    display = simple.Show(reader, view)  # reads the pieces
    read_seconds = time.perf_counter() - start
    cpu_seconds = [time.process_time() - cpu]
    arrays = reader.PointData.keys()
    simple.ColorBy(display, ("POINTS", arrays[0]))
    rescale_to_the_whole(reader.PointData[arrays[0]])
    display.SetRepresentationType(arguments.representation)
    work = dict(FIXED_WORK)
    work["Volume (SPT)"] = {"RepetitionLevel": arguments.repetitions,
                            "TargetError": arguments.target_error}
    for name, value in work.get(arguments.representation, {}).items():
        set_property(display, name, value)
    simple.ResetCamera(view)
    frames, counts = [], []
    for frame in range(arguments.frames):
        if frame:
            view.GetActiveCamera().Azimuth(1.0)
        begin, cpu = time.perf_counter(), time.process_time()
        simple.Render(view)
        frames.append(time.perf_counter() - begin)
        cpu_seconds.append(time.process_time() - cpu)
        counts.append(spt_counts(display))
    cpu_seconds = largest_over_ranks(cpu_seconds)
    if vtkProcessModule.GetProcessModule().GetPartitionId() == 0:
        with open(arguments.output, "w") as report:
            json.dump({"read_wall_seconds": read_seconds, "read_cpu_seconds": cpu_seconds[0],
                       "first_wall_seconds": frames[0], "later_wall_seconds": later(frames),
                       "first_cpu_seconds": cpu_seconds[1], "spt_counts": counts,
                       "later_cpu_seconds": later(cpu_seconds[1:])}, report)


main()
