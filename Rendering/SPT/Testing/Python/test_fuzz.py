"""Random meshes (random points, random and invalid connectivity, random cell types, random
arrays with NaN and Inf, random selections and transfer functions) rendered with each mapper,
many fixed seeds: no crash, no hang, and every render either draws, or reports a clear error
or warning, or had nothing to show (render_seed() says what that means), with the input
unchanged.

The renders run in a subprocess, this file run as a program, so that a crash fails the test
with the seed it happened at instead of killing pytest:

    python3 test_fuzz.py MAPPER FIRST_SEED COUNT

Before each render it prints `begin SEED`, after it `end SEED OUTCOME` (OUTCOME: drew, error,
warning or empty) and flushes, so that the parent knows where a crash or a hang happened. A
failed check (a non-finite image, a changed input, nothing drawn without a word) prints
`fail SEED reason` and the process exits with status 1. Reproduce one seed with
`python3 Rendering/SPT/Testing/Python/test_fuzz.py MAPPER SEED 1` under xvfb-run, with the
package and Testing/Python on PYTHONPATH.
"""

from __future__ import annotations

import pathlib
import subprocess
import sys

import numpy as np
import pytest
import vtk
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy

from spt import render

from robustness_support import assert_unchanged, snapshot, volume_property, watch

WORKER = pathlib.Path(__file__).resolve()
SEEDS = 400
TIMEOUT = 600  # seconds for all seeds of one mapper; measured: about 10 on two shared cores
SIZE = (40, 40)
CELL_SIZES = {vtk.VTK_TETRA: 4, vtk.VTK_HEXAHEDRON: 8, vtk.VTK_WEDGE: 6, vtk.VTK_PYRAMID: 5,
              vtk.VTK_VOXEL: 8, vtk.VTK_TRIANGLE: 3, vtk.VTK_QUADRATIC_TETRA: 10,
              vtk.VTK_QUADRATIC_HEXAHEDRON: 20, vtk.VTK_VERTEX: 1}


def random_points(rng: np.random.Generator) -> np.ndarray:
    count = int(rng.integers(0, 40))
    extreme = rng.random() < 0.2
    exponent = rng.uniform(-30, 30) if extreme else rng.uniform(-2, 2)
    points = rng.normal(size=(count, 3)) * 10.0 ** exponent
    if count and rng.random() < 0.1:
        points += 10.0 ** rng.uniform(-30, 30)  # far from the origin
    if count and rng.random() < 0.15:
        points[rng.integers(0, count)] = rng.choice([np.nan, np.inf, -np.inf])
    if count > 1 and rng.random() < 0.1:
        points[1:] = points[0]  # every point the same
    return points


def random_cells(rng: np.random.Generator, grid: vtk.vtkUnstructuredGrid, points: int) -> None:
    types = list(CELL_SIZES)
    for _ in range(int(rng.integers(0, 30))):
        cell_type = types[int(rng.integers(0, len(types)))]
        size = CELL_SIZES[cell_type]
        if rng.random() < 0.01:
            size = int(rng.integers(0, 12))  # a wrong number of points for the type
        high = max(points, 1) + (3 if rng.random() < 0.01 else 0)  # sometimes out of range
        ids = rng.integers(-1 if rng.random() < 0.01 else 0, high, size=size)
        grid.InsertNextCell(cell_type, len(ids), [int(i) for i in ids])


def random_array(rng: np.random.Generator, count: int, name: str):
    components = int(rng.choice([1, 1, 1, 2, 3, 9]))
    extreme = rng.random() < 0.2
    exponent = rng.uniform(-30, 30) if extreme else rng.uniform(-1, 1)
    values = rng.normal(size=(count, components)) * 10.0 ** exponent
    if rng.random() < 0.1:
        values[:] = values[0] if count else 0.0  # a constant field
    if count and rng.random() < 0.3:
        bad = rng.integers(0, count, size=int(rng.integers(1, count + 1)))
        values[bad] = rng.choice([np.nan, np.inf, -np.inf])
    dtype = rng.choice([np.float64, np.float32, np.int32, np.uint8])
    if np.dtype(dtype).kind != "f":
        values = np.nan_to_num(values, posinf=0.0, neginf=0.0).clip(-1e6, 1e6)
    values = values.astype(dtype)
    array = numpy_to_vtk(values if components > 1 else values.ravel(), deep=True)
    array.SetName(name)
    return array


def random_grid(rng: np.random.Generator) -> vtk.vtkUnstructuredGrid:
    """Random points, random and invalid connectivity, random arrays."""
    grid = vtk.vtkUnstructuredGrid()
    coordinates = random_points(rng)
    if rng.random() < 0.95:
        points = vtk.vtkPoints()
        points.SetData(numpy_to_vtk(coordinates.reshape(-1, 3), deep=True))
        grid.SetPoints(points)
    random_cells(rng, grid, len(coordinates))
    for attributes, count in ((grid.GetPointData(), grid.GetNumberOfPoints()),
                              (grid.GetCellData(), grid.GetNumberOfCells())):
        for name in ("a", "b"):
            if rng.random() < 0.5:
                # Sometimes a tuple short or long: arrays that do not match the grid.
                wrong = int(rng.choice([-1, 1])) if rng.random() < 0.05 else 0
                attributes.AddArray(random_array(rng, max(count + wrong, 0), name))
        if attributes.GetNumberOfArrays() and rng.random() < 0.7:
            attributes.SetActiveScalars(attributes.GetArrayName(0))
    return grid


def random_property(rng: np.random.Generator) -> vtk.vtkVolumeProperty:
    colors, opacities = [], []
    for _ in range(int(rng.choice([0, 1, 2, 3, 3, 3]))):
        x = float(rng.normal() * 10.0 ** rng.uniform(-1, 1))
        colors.append((x, *rng.random(3)))
        opacities.append((x, float(rng.choice([0.0, 1.0, rng.random()]))))
    return volume_property(colors, opacities, float(10.0 ** rng.uniform(-3, 1)))


def random_mapper(kind: str, rng: np.random.Generator):
    if kind == "pbvr":
        mapper = render.pbvr_mapper(int(rng.integers(1, 4)), seed=int(rng.integers(0, 1000)))
        mapper.SetMaximumParticleMemory(16)  # random optical depths: a clear error, not hours
    else:
        mapper = (render.spt_mapper(int(rng.integers(1, 4)), seed=int(rng.integers(0, 1000)))
                  if kind == "spt" else render.havs_mapper(int(rng.integers(2, 7))))
        mapper.SetPreIntegrationScalarResolution(16)
        mapper.SetPreIntegrationThicknessResolution(8)
    if rng.random() < 0.3:
        mapper.SetScalarModeToUsePointFieldData() if rng.random() < 0.5 else \
            mapper.SetScalarModeToUseCellFieldData()
        mapper.SelectScalarArray(str(rng.choice(["a", "b", "c"])))
    if rng.random() < 0.2:
        mapper.SetVectorModeToComponent()
        mapper.SetVectorComponent(int(rng.integers(0, 4)))
    return mapper


def camera_can_frame(grid: vtk.vtkDataSet) -> bool:
    """Whether VTK's ResetCamera can frame the grid: finite bounds of a size its clipping
    range handles (it fails far from 1, see robustness_support.check_extreme_scale)."""
    bounds = np.array(grid.GetBounds())
    if not np.isfinite(bounds).all():
        return False
    size = float(np.max(bounds[1::2] - bounds[0::2]))
    return 1e-10 < size < 1e10 and float(np.max(np.abs(bounds))) < 1e10


def opaque_property(grid: vtk.vtkDataSet) -> vtk.vtkVolumeProperty:
    """Opacity 1 at every scalar, reaching full opacity within a millionth of the data's size."""
    bounds = np.array(grid.GetBounds())
    return volume_property([], [(0.0, 1.0)], 1e-6 * float(np.max(bounds[1::2] - bounds[0::2])))


def render_seed(kind: str, seed: int, window, renderer) -> str:
    """Render the random scene of `seed`; returns the outcome, raises AssertionError on a
    failed check."""
    rng = np.random.default_rng([seed, {"spt": 1, "havs": 2, "pbvr": 3}[kind]])
    grid = random_grid(rng)
    prop = random_property(rng)
    mapper = random_mapper(kind, rng)
    messages = watch(mapper)
    before = snapshot(grid)
    volume = render.add_volume(renderer, grid, prop, mapper)
    renderer.SetActiveCamera(vtk.vtkCamera())  # nothing carried over from the last seed
    renderer.ResetCamera()
    window.Render()
    image = render.read_rgba(window)
    outcome = "drew" if image[..., 3].max() > 0.0 else "empty"
    if outcome == "empty" and not messages.errors and not messages.warnings and \
            mapper.GetNumberOfTetrahedra() > 0 and camera_can_frame(grid):
        # Nothing drawn without a word: the transfer function must be why. Opaque, the same
        # tetrahedra must show, or the mapper say why not (PBVR: too many particles), unless
        # they are all flat (on fewer than four distinct points).
        volume.SetProperty(opaque_property(grid))
        window.Render()
        points = vtk_to_numpy(grid.GetPoints().GetData())
        assert render.read_rgba(window)[..., 3].max() > 0.0 or messages.errors or \
            len(np.unique(points, axis=0)) < 4, "nothing drawn, nothing said, even when opaque"
        messages.errors.clear()
    renderer.RemoveVolume(volume)
    mapper.ReleaseGraphicsResources(window)
    assert_unchanged(grid, before)
    assert np.isfinite(image).all(), "the image is not finite"
    if messages.errors:
        assert all(len(text) > 40 for text in messages.errors), messages.errors
        return "error"
    return "warning" if messages.warnings and outcome == "empty" else outcome


def main(argv) -> int:
    kind, first, count = argv[1], int(argv[2]), int(argv[3])
    window, renderer = render.make_window(*SIZE)
    status = 0
    for seed in range(first, first + count):
        print(f"begin {seed}", flush=True)
        try:
            outcome = render_seed(kind, seed, window, renderer)
        except AssertionError as failure:
            print(f"fail {seed} {failure}".replace("\n", " "), flush=True)
            status = 1
            continue
        print(f"end {seed} {outcome}", flush=True)
    window.Finalize()
    return status


def outcomes(stdout: str):
    """{seed: outcome} of the seeds that finished, the seeds that failed a check (with why),
    and the last seed begun."""
    done, failed, last = {}, {}, None
    for line in stdout.splitlines():
        word, _, rest = line.partition(" ")
        seed, _, detail = rest.partition(" ")
        if word == "begin":
            last = int(seed)
        elif word == "end":
            done[int(seed)] = detail
        elif word == "fail":
            failed[int(seed)] = detail
    return done, failed, last


@pytest.mark.parametrize("kind", ["spt", "havs", "pbvr"])
def test_random_meshes(kind):
    try:
        # This file run as a program (its folder, with the helpers, comes first on its path).
        result = subprocess.run([sys.executable, str(WORKER), kind, "0", str(SEEDS)],
                                capture_output=True, text=True, timeout=TIMEOUT, check=False)
    except subprocess.TimeoutExpired as timeout:
        _, _, last = outcomes(timeout.stdout.decode() if timeout.stdout else "")
        pytest.fail(f"{kind}: no answer within {TIMEOUT} s, at seed {last}")
    done, failed, last = outcomes(result.stdout)
    if result.returncode not in (0, 1) or (last is not None and last not in done and
                                           last not in failed):
        tail = "\n".join(result.stderr.splitlines()[-5:])
        pytest.fail(f"{kind}: the worker died (status {result.returncode}) at seed {last}:\n{tail}")
    assert not failed, f"{kind}: checks failed at seeds {failed}"
    assert len(done) == SEEDS
    # The inputs were random enough to reach every outcome, drawing among them.
    counts = {outcome: list(done.values()).count(outcome) for outcome in set(done.values())}
    assert counts.get("drew", 0) >= 10 and counts.get("error", 0) >= 10, counts


if __name__ == "__main__":
    sys.exit(main(sys.argv))
