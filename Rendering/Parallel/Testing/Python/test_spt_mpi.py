"""vtkSPTVolumeMapper in a plain VTK MPI program (vtkMPIController, no ParaView): each rank
renders an interleaved piece of the default mesh (cells by id modulo the number of ranks, each
piece spanning the whole mesh) with no redistribution; the ranks combine their depth keys by a
global minimum and their sums by a global sum, and rank 0 resolves.

The random numbers follow the cells' global ids, so with the same seed the 2-rank image is the
1-rank image, and that is the image of one process with no controller (the default mesh is all
tetrahedra, numbered as its cells). The images are compared at 8 bits: at most one level apart
(the reductions add the same float terms in another order, which may move a sum by an ulp and a
pixel across a rounding boundary; measured: identical).

Ranks that disagree (another scalar array, another seed, another transfer function) give one
error naming the rank and draw nothing, without a hang (each run has a timeout). The ranks
integrate the pre-integration table in shares and gather it.

With an error target (TargetError), rank 0 estimates the noise of the whole image from the
halves' global sums after each step, and every rank follows it: the ranks draw the repetitions
one process draws, and the 2-rank image, repetition count and estimate are the 1-rank ones.
Progressive refinement adds to the whole image, and the time budget is agreed by the ranks.

Two SPT volumes in one renderer (the mesh, and a copy moved into it by its vtkVolume's
position) share one set of buffers across the ranks too: the 2-rank image is that of one
process, and close to the exact reference of the union.
"""

import json
import os
import pathlib
import shutil
import subprocess
import sys

import numpy as np
import pytest

import scene_support
from spt import metrics

WORKER = pathlib.Path(__file__).resolve().parent / "mpi_spt_worker.py"
SIZE = 128
REPETITIONS = 16
TIMEOUT = 300  # seconds; a hang fails the test instead of blocking it
#: One 8-bit level.
LEVEL = 1.0 / 255.0
#: The RMSE (over the footprint) of a 16-repetition SPT image of the default scene from the
#: exact reference is about 0.0024; an image missing a piece is off by more than 0.02.
REFERENCE_RMSE = 0.008
#: The error target of ParaView's plugin, and its cap on the repetitions. With 4 repetitions
#: per traversal, the first step draws 2 + 2 and several steps follow, each drawing only the
#: tiles still above the target.
TARGET = 0.005
TARGET_CAP = 256
TARGET_OPTIONS = ("--target-error", str(TARGET), "--per-pass", "4")


def mpiexec():
    path = shutil.which("mpiexec")
    if not path:
        pytest.skip("mpiexec (OpenMPI) is not installed")
    probe = ("from mpi4py import MPI\n"
             "from vtkmodules.vtkParallelMPI import vtkMPIController\n")
    if subprocess.run([sys.executable, "-c", probe], capture_output=True,
                      check=False).returncode != 0:
        pytest.skip("mpi4py or VTK's vtkParallelMPI is not importable")
    command = [path, "--oversubscribe"]
    if os.geteuid() == 0:
        command.append("--allow-run-as-root")
    for variable in ("PYTHONPATH", "DISPLAY", "SPT_DATA_DIR"):
        if variable in os.environ:
            command += ["-x", variable]
    return command


def run(output: pathlib.Path, ranks: int, *options: str, repetitions: int = REPETITIONS,
        errors: int = 0):
    """Render with ``ranks`` ranks (0: no MPI, no controller), which must report ``errors``
    errors in all; the frames rank 0 read back, its report, and the stderr of every rank."""
    command = [sys.executable, str(WORKER), "--output", str(output), "--size", str(SIZE),
               "--repetitions", str(repetitions), *options]
    if ranks > 0:
        command = mpiexec() + ["-n", str(ranks)] + command
    else:
        command.append("--serial")
    result = subprocess.run(command, capture_output=True, text=True, timeout=TIMEOUT,
                            check=False)
    assert result.returncode == 0, result.stdout[-4000:] + result.stderr[-4000:]
    assert result.stderr.count("ERR") == errors, result.stderr
    report = json.loads(output.with_suffix(".json").read_text())
    return np.load(output), report, result.stderr


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """run() with no error expected, each set of ranks, options and repetitions once per
    module."""
    directory = tmp_path_factory.mktemp("spt_mpi")
    done = {}

    def run_once(ranks: int, *options: str, repetitions: int = REPETITIONS):
        key = (ranks, options, repetitions)
        if key not in done:
            done[key] = run(directory / f"run{len(done)}.npy", ranks, *options,
                            repetitions=repetitions)
        return done[key]
    return run_once


def largest_difference(a: np.ndarray, b: np.ndarray) -> float:
    """The largest difference of two images at 8 bits, in levels."""
    return float(np.abs(metrics.to_uint8(a).astype(int) - metrics.to_uint8(b).astype(int)).max())


def run_serial_and_two_ranks(runs, *options: str, repetitions=REPETITIONS):
    """Render with no controller and with 2 ranks: the 2-rank frames are the serial ones (one
    8-bit level), with no error on any rank; the two runs (images, report, stderr)."""
    serial, two = (runs(ranks, *options, repetitions=repetitions) for ranks in (0, 2))
    assert len(serial[0]) == len(two[0])
    for frame in range(len(two[0])):
        assert largest_difference(serial[0][frame], two[0][frame]) <= 1.0
    return serial, two


def check_bytes(report, expected: int) -> None:
    """The bytes a rank moved are ``expected``, plus a small record."""
    assert expected <= report["bytes"] <= expected + 4096


def test_two_ranks_equal_one_rank(runs):
    one, report_one, _ = runs(1)
    two, report_two, _ = runs(2)
    assert report_one["ranks"] == 1 and report_two["ranks"] == 2
    assert report_two["cells"] == 24000  # rank 0's piece: every other cell
    assert largest_difference(one[0], two[0]) <= 1.0


def test_one_rank_equals_no_controller(runs):
    assert largest_difference(runs(0)[0][0], runs(1)[0][0]) <= 1.0


def test_later_frames_equal_the_first(runs):
    two, _, _ = runs(2)
    assert largest_difference(two[0], two[1]) == 0.0


#: Runs of two ranks that draw the default mesh: their options, their repetitions, and
#: whether they show it twice (--second-volume), composited where the volumes overlap.
VOLUME_RUNS = {"one volume": ((), REPETITIONS, False),
               "error target": (TARGET_OPTIONS, TARGET_CAP, False),
               "two volumes": (("--second-volume",), REPETITIONS, True)}


@pytest.mark.parametrize("case", VOLUME_RUNS)
def test_image_is_the_volume(runs, case):
    """Not black, and as close to the exact reference (of the union, for two volumes) as one
    process's image is to its own (an image missing a volume or a piece is off by more than
    0.02)."""
    options, repetitions, union = VOLUME_RUNS[case]
    two, _, _ = runs(2, *options, repetitions=repetitions)
    reference = (scene_support.union_reference if union else scene_support.reference)(
        "default", SIZE)
    assert two[0][..., 3].mean() > 0.5 * reference[..., 3].mean()
    assert metrics.rmse(two[0], reference) < REFERENCE_RMSE


def test_bytes_moved(runs):
    """Per frame, each rank reduces the keys (4 bytes per sample and repetition), the sums
    and coverage (2 x 16 bytes per sample), and a small record."""
    check_bytes(runs(2)[1], SIZE * SIZE * (4 * REPETITIONS + 32))


#: Depth slabs: the ranks add up each slab's sums before the color traversal.
SLABS = 8


def test_depth_slabs_on_two_ranks_equal_one_process(runs):
    """The slabs' sums are fixed point, the same in any order: the 2-rank image is the one
    of one process. The slabs change the image (its noise), and it stays the volume."""
    _, (two, report, _) = run_serial_and_two_ranks(runs, "--depth-slabs", str(SLABS))
    assert largest_difference(two[0], two[1]) == 0.0
    assert largest_difference(two[0], runs(2)[0][0]) >= 2.0
    reference = scene_support.reference("default", SIZE)
    assert metrics.rmse(two[0], reference) < REFERENCE_RMSE
    # Per sample: each slab's keys, the sums and coverage, and each slab's four sums.
    check_bytes(report, SIZE * SIZE * (4 * REPETITIONS * SLABS + 32 + 16 * SLABS))


def test_clipping_planes_on_two_ranks_equal_one_process(runs):
    """Each rank cuts its piece's segments by the mappers' clipping plane: the combined image
    is one process's image of the clipped volume, not the unclipped one."""
    (serial, _, _), (two, _, _) = run_serial_and_two_ranks(runs, "--clipping-plane")
    assert serial[0][..., 3].max() > 0.2, "the image is empty"
    unclipped, _, _ = runs(0)
    assert metrics.rmse(two[0], unclipped[0]) > 0.05, "the plane changes nothing"


def test_a_count_that_is_not_a_power_of_two(runs):
    """The keys of 12 repetitions lie in a buffer of 16 layers (the shaders are compiled for
    a power of two): the ranks exchange the 12 layers in use, and combine them as one process
    draws them."""
    (serial, _, _), (_, report, _) = run_serial_and_two_ranks(runs, repetitions=12)
    assert serial[0][..., 3].max() > 0.2, "the image is empty"
    check_bytes(report, SIZE * SIZE * (4 * 12 + 32))


def test_ranks_share_the_table(runs):
    """Three ranks integrate the pre-integration table's 128 x 128 scalar pairs in shares of
    5,462 (the last rank's padded) and gather them: the first frame moves each rank's share
    (64 lengths of RGBA floats per pair) besides the frame's keys and sums, and the image is
    one process's."""
    serial, _, _ = runs(0)
    three, report, _ = runs(3, "--frames", "1")
    assert serial[0][..., 3].max() > 0.2, "the image is empty"
    assert largest_difference(serial[0], three[0]) <= 1.0
    table = 5462 * 64 * 4 * 4
    check_bytes(report, SIZE * SIZE * (4 * REPETITIONS + 32) + table)


def test_an_empty_piece_takes_part(runs):
    """Rank 1 has no cells: rank 0's half of the mesh is drawn, with no error."""
    images, _, _ = runs(2, "--empty-rank", "1")
    alpha = images[0][..., 3].mean()
    reference = scene_support.reference("default", SIZE)
    assert 0.2 * reference[..., 3].mean() < alpha < 0.9 * reference[..., 3].mean()


def test_opaque_geometry_on_another_rank_hides_the_volume(runs):
    """An opaque sphere drawn by rank 1 only cuts and hides rank 0's piece too (the scene
    depth is a global minimum), and shows through the translucent volume in front of it:
    rank 0 resolves the volume over every rank's geometry, so the 2-rank image is the 1-rank
    image with the sphere, in all four channels."""
    one, _, _ = runs(1, "--opaque-on", "0")
    two, _, _ = runs(2, "--opaque-on", "1")
    assert largest_difference(one[0], two[0]) <= 1.0
    without, _, _ = runs(2)
    assert largest_difference(without[0], two[0]) > 32.0


OTHER_ARRAY = ("Rank 1 renders the point array 'another name' of 1 component(s), but rank 0 "
               "renders the point array 'field'")


@pytest.mark.parametrize("options, repetitions, message", [
    (("--other-array-on", "1"), REPETITIONS, OTHER_ARRAY),
    (("--other-seed-on", "1"), REPETITIONS, "Rank 1 has Seed 7 but rank 0 has 0"),
    (("--other-opacity-on", "1"), REPETITIONS, "Rank 1's transfer function differs from rank 0's"),
    (("--other-target-on", "1"), REPETITIONS, "Rank 1 has TargetError 0.01 but rank 0 has 0"),
    (("--empty-viewport-on", "1"), REPETITIONS, "Rank 1 has image width 0 but rank 0 has 128"),
    (("--other-array-on", "1", "--target-error", str(TARGET)), TARGET_CAP, OTHER_ARRAY),
    # A later volume's settings are agreed on after the first's.
    (("--second-volume", "--other-array-on", "1"), REPETITIONS,
     "SPT volume 2 of the renderer: " + OTHER_ARRAY),
])
def test_ranks_that_differ_give_one_error(tmp_path, options, repetitions, message):
    images, _, errors = run(tmp_path / "differ.npy", 2, *options, repetitions=repetitions,
                            errors=1)
    assert errors.count(message) == 1, errors
    assert "nothing is drawn on any rank" in errors
    assert images[..., 3].max() == 0.0


def target_run(runs, ranks: int):
    return runs(ranks, *TARGET_OPTIONS, repetitions=TARGET_CAP)


@pytest.mark.parametrize("ranks", [1, 2])
def test_target_error_as_one_process(runs, ranks):
    """The same repetitions, estimate and image as one process with no controller, and the
    target met well before the cap (a render that ignored the target would draw 256); the
    ranks drew the later steps into the same tiles as one process, fewer than all."""
    serial, serial_report, _ = target_run(runs, 0)
    images, report, _ = target_run(runs, ranks)
    assert report["repetitions"] == serial_report["repetitions"]
    assert report["fewest"] == serial_report["fewest"] < report["repetitions"][0]
    assert report["repetitions"][0] < TARGET_CAP
    assert report["estimated_errors"] == pytest.approx(serial_report["estimated_errors"],
                                                       rel=1e-5)
    assert 0.0 < report["estimated_errors"][0] <= TARGET
    assert largest_difference(serial[0], images[0]) <= 1.0
    assert largest_difference(images[0], images[1]) == 0.0


def test_target_error_bytes(runs):
    """The keys of every repetition, the sums, the second half's sums and the coverage once
    (after the first step), then the sums and the second half's after each later step: at
    least one step, at most one per two repetitions."""
    _, report, _ = target_run(runs, 2)
    samples = SIZE * SIZE
    repetitions = report["repetitions"][0]
    least = samples * (4 * repetitions + 48)
    most = least + samples * 32 * (repetitions // 2 - 1) + 4096
    assert least <= report["bytes"] <= most


def test_progressive_refinement_across_ranks(runs):
    """Each frame adds RepetitionLevel repetitions to the whole image until the target is met;
    the 2-rank frames are the frames of one process."""
    options = ("--target-error", "0.002", "--progressive", "--frames", "4")
    (_, serial_report, _), (_, report, _) = run_serial_and_two_ranks(
        runs, *options, repetitions=4)
    assert report["repetitions"] == serial_report["repetitions"] == [4, 8, 12, 16]
    assert report["estimated_errors"] == pytest.approx(serial_report["estimated_errors"],
                                                       rel=1e-5)


def test_time_budget_across_ranks(runs):
    """With AutoAdjustRepetitions and a budget of 1 ms (far less than a software-rendered
    frame of this scene takes), the first frame draws the cap (nothing measured yet), the
    second one repetition of the visibility estimator (a pair of traversals, not timed yet)
    and the third the cheapest frame, one repetition in one traversal, on every rank alike."""
    options = ("--update-rate", "1000", "--frames", "3")
    (_, serial_report, _), (_, report, _) = run_serial_and_two_ranks(
        runs, *options, repetitions=64)
    assert report["repetitions"] == serial_report["repetitions"] == [64, 1, 1]


def test_target_error_with_an_empty_piece(runs):
    """Rank 1 has no cells: rank 0's half is drawn to the target, with no error and no hang."""
    images, report, _ = runs(2, "--empty-rank", "1", "--target-error", str(TARGET),
                             repetitions=TARGET_CAP)
    assert 0.0 < report["estimated_errors"][0] <= TARGET
    assert images[0][..., 3].max() > 0.0


def test_two_volumes_on_two_ranks_equal_one_process(runs):
    (_, serial_report, _), (two, report, _) = run_serial_and_two_ranks(runs, "--second-volume")
    assert report["repetitions"][0] == serial_report["repetitions"][0] == [REPETITIONS] * 2
    assert largest_difference(two[0], two[1]) == 0.0


def test_an_empty_viewport_on_every_rank_draws_nothing_without_error(runs):
    images, _, errors = runs(2, "--empty-viewport-on", "all")
    assert "Warning" not in errors, errors
    assert images.max() == 0.0


def test_a_renderer_that_culls_gets_a_warning(runs):
    """VTK's frustum culler would skip the render of a rank whose piece lies outside the view,
    and the others would wait for it: each rank says so once (the pieces here are interleaved,
    so every rank still renders)."""
    _, _, errors = runs(2, "--keep-cullers")
    assert errors.count("Remove the renderer's cullers") == 2, errors
    assert "Remove the renderer's cullers" not in runs(2)[2]
