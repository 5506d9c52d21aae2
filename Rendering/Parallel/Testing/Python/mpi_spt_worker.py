"""One rank of a plain VTK MPI program rendering the default scene with vtkSPTVolumeMapper:
every rank makes the default mesh, keeps the cells whose id modulo the number of ranks is its
rank (interleaved pieces, each spanning the whole mesh), numbers them by their ids in the whole
(GlobalIds), and renders its piece with the mapper's controller set. Rank 0 writes the image.
With ``--second-volume``, a second SPT volume in the same renderer shows the mesh once more,
moved into the first by its vtkVolume's position, each rank with its interleaved piece of it.

Run by test_spt_mpi.py under mpiexec; ``--serial`` renders the whole mesh with no controller.
"""

import argparse
import json
import pathlib

import numpy as np


#: The options that name one rank (none by default) and what that rank does differently.
RANK_OPTIONS = {
    "--other-array-on": "this rank renders an array of another name (in the second volume "
                        "with --second-volume)",
    "--other-seed-on": "this rank renders with seed 7",
    "--other-opacity-on": "this rank's opacity transfer function is half the others'",
    "--empty-rank": "this rank has no cells",
    "--opaque-on": "this rank draws an opaque sphere in the middle of the mesh",
    "--other-target-on": "this rank renders with TargetError 0.01 (the others without, unless "
                         "--target-error)",
}


def parse() -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--output", type=pathlib.Path, required=True)
    parser.add_argument("--size", type=int, default=128)
    parser.add_argument("--repetitions", type=int, default=16)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--serial", action="store_true", help="no MPI, no controller")
    for option, help_text in RANK_OPTIONS.items():
        parser.add_argument(option, type=int, default=-1, help=help_text)
    parser.add_argument("--second-volume", action="store_true",
                        help="a second SPT volume: the mesh moved by scene_support.union_offset()")
    parser.add_argument("--empty-viewport-on", default="",
                        help="this rank's renderer (or every rank's: 'all') has a viewport "
                             "with no pixels")
    parser.add_argument("--keep-cullers", action="store_true",
                        help="keep VTK's frustum culler, which may skip a rank's render")
    parser.add_argument("--depth-slabs", type=int, default=1, help="DepthSlabs")
    parser.add_argument("--clipping-plane", action="store_true",
                        help="every rank's mapper clipped by the plane of clipping_support's "
                             "case 'one oblique'")
    parser.add_argument("--frames", type=int, default=2)
    parser.add_argument("--per-pass", type=int, default=None, help="RepetitionsPerPass")
    parser.add_argument("--target-error", type=float, default=None,
                        help="TargetError; --repetitions is then the cap")
    parser.add_argument("--progressive", action="store_true",
                        help="ProgressiveRefinement on: later frames add to the first")
    parser.add_argument("--update-rate", type=float, default=0.0,
                        help="AutoAdjustRepetitions on, with this desired update rate (frames "
                             "per second); each rank's budget is its own measured time")
    return parser.parse_args()


def controller_or_none(serial: bool):
    if serial:
        return None
    from mpi4py import MPI  # noqa: F401  (initializes MPI for VTK's controller)
    from vtkmodules.vtkParallelCore import vtkMultiProcessController
    from vtkmodules.vtkParallelMPI import vtkMPIController

    controller = vtkMPIController()
    controller.Initialize()
    vtkMultiProcessController.SetGlobalController(controller)
    return controller


def opaque_sphere(bounds):
    """An opaque orange sphere in the middle of ``bounds``, unlit (one flat color): it hides
    and cuts the volume, and shows through where the volume in front of it is translucent."""
    from vtkmodules.vtkFiltersSources import vtkSphereSource
    from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper

    sphere = vtkSphereSource()
    sphere.SetCenter([(bounds[2 * a] + bounds[2 * a + 1]) / 2.0 for a in range(3)])
    sphere.SetRadius(0.25 * min(bounds[2 * a + 1] - bounds[2 * a] for a in range(3)))
    sphere.SetThetaResolution(48)
    sphere.SetPhiResolution(48)
    mapper = vtkPolyDataMapper()
    mapper.SetInputConnection(sphere.GetOutputPort())
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetColor(0.9, 0.55, 0.2)
    actor.GetProperty().SetAmbient(1.0)
    actor.GetProperty().SetDiffuse(0.0)
    actor.GetProperty().SetSpecular(0.0)
    return actor


def halved_opacity(volume_property):
    """A copy of ``volume_property`` whose scalar opacity is half as high everywhere."""
    from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
    from vtkmodules.vtkRenderingCore import vtkVolumeProperty

    copy = vtkVolumeProperty()
    copy.DeepCopy(volume_property)
    opacity = vtkPiecewiseFunction()
    opacity.DeepCopy(volume_property.GetScalarOpacity())
    for i in range(opacity.GetSize()):
        node = [0.0] * 4
        opacity.GetNodeValue(i, node)
        node[1] *= 0.5
        opacity.SetNodeValue(i, node)
    copy.SetScalarOpacity(opacity)
    return copy


def add_volumes(arguments, renderer, controller, rank, ranks, scene):
    """This rank's SPT volumes of the scene (two with --second-volume) in ``renderer``, each
    with its piece of the mesh; returns their mappers and pieces."""
    import scene_support
    from clipping_support import CASES
    from spt import meshes, render

    grid = scene.grid

    def piece_of(grid, renamed):
        if controller is None:
            return grid
        piece = meshes.interleaved_piece(grid, rank, ranks, empty=rank == arguments.empty_rank)
        if renamed and rank == arguments.other_array_on:
            piece.GetPointData().GetScalars().SetName("another name")
        return piece

    seed = 7 if rank == arguments.other_seed_on else arguments.seed
    volume_property = (halved_opacity(scene.property) if rank == arguments.other_opacity_on
                       else scene.property)
    mappers, pieces = [], []
    for second in ((False, True) if arguments.second_volume else (False,)):
        target_error = 0.01 if rank == arguments.other_target_on else arguments.target_error
        mapper = render.spt_mapper(arguments.repetitions, seed=seed, target_error=target_error,
                                   per_pass=arguments.per_pass)
        mapper.SetProgressiveRefinement(arguments.progressive)
        mapper.SetDepthSlabs(arguments.depth_slabs)
        if arguments.update_rate > 0.0:
            mapper.SetAutoAdjustRepetitions(True)
            # Ranks draw every pixel; so does the serial render the tests compare them with.
            mapper.SetAutoAdjustSampleDistances(False)
        if controller is not None:
            mapper.SetController(controller)
        if arguments.clipping_plane:
            for plane in CASES["one oblique"].vtk_planes():
                mapper.AddClippingPlane(plane)
        piece = piece_of(grid, renamed=second == arguments.second_volume)
        volume = render.add_volume(renderer, piece, volume_property, mapper)
        if second:
            volume.SetPosition(*scene_support.union_offset(grid))
        mappers.append(mapper)
        pieces.append(piece)
    return mappers, pieces


def render_frames(arguments, window, mappers):
    """The frames' images, repetition counts and the first mapper's error estimates."""
    from spt import render

    images, counts, estimates = [], [], []
    for _ in range(arguments.frames):
        window.Render()
        images.append(render.read_rgba(window))
        counts.append([m.GetLastRepetitionCount() for m in mappers]
                      if arguments.second_volume else mappers[0].GetLastRepetitionCount())
        estimates.append(mappers[0].GetEstimatedError())
    return images, counts, estimates


def main() -> None:
    arguments = parse()
    import scene_support
    from spt import render, scenes

    controller = controller_or_none(arguments.serial)
    rank = controller.GetLocalProcessId() if controller else 0
    ranks = controller.GetNumberOfProcesses() if controller else 1
    scene = scenes.scene("default")
    grid = scene.grid
    window, renderer = render.make_window(arguments.size, arguments.size)
    if not arguments.keep_cullers:
        # Every rank renders every frame, whatever its piece: a culler could skip one.
        renderer.GetCullers().RemoveAllItems()
    if arguments.empty_viewport_on in ("all", str(rank)):
        renderer.SetViewport(0.0, 0.0, 0.0, 0.0)
    mappers, pieces = add_volumes(arguments, renderer, controller, rank, ranks, scene)
    if rank == arguments.opaque_on:
        renderer.AddActor(opaque_sphere(grid.GetBounds()))
    bounds = (scene_support.union("default") if arguments.second_volume else grid).GetBounds()
    render.place_camera(renderer, bounds, scene.view)
    if arguments.update_rate > 0.0:
        window.SetDesiredUpdateRate(arguments.update_rate)
    images, counts, estimates = render_frames(arguments, window, mappers)
    if rank == 0:
        np.save(arguments.output, np.stack(images))
        report = {"ranks": ranks, "cells": pieces[0].GetNumberOfCells(),
                  "bytes": mappers[0].GetFrameStatistics().GetParallelBytes(),
                  "repetitions": counts, "estimated_errors": estimates,
                  "fewest": mappers[0].GetFrameStatistics().GetFewestRepetitionCount()}
        arguments.output.with_suffix(".json").write_text(json.dumps(report))
    window.Finalize()


if __name__ == "__main__":
    main()
