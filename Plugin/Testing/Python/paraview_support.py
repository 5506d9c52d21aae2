"""Helpers of the ParaView plugin tests: where things are, running ParaView's executables, data
files ParaView can read, and images.

The tests run ParaView's own executables (pvpython, pvbatch, pvserver, paraview) on the plugin
and the spt package of this build tree: ctest passes SPT_PARAVIEW_PLUGIN (the built SPT.so) and
PYTHONPATH; a test is skipped when they or the executables are missing.
"""

from __future__ import annotations

import json
import os
import pathlib
import shutil
import socket
import struct
import subprocess
import time
from typing import Dict, List, Optional, Sequence

import numpy as np
import pytest

SCRIPTS = pathlib.Path(__file__).resolve().parent / "paraview"
SUBPROCESS_TIMEOUT = 900  # seconds; llvmpipe on two shared cores is slow

SPT, HAVS, PBVR = "Volume (SPT)", "Volume (HAVS-like)", "Volume (PBVR)"
#: The mapper of each representation type (SPT's is the parallel subclass, on one rank too).
MAPPERS = {SPT: "vtkPSPTVolumeMapper", HAVS: "vtkHAVSVolumeMapper", PBVR: "vtkPBVRVolumeMapper"}


def executable(name: str) -> str:
    path = shutil.which(name)
    if not path:
        pytest.skip(f"{name} (ParaView 5.11) is not installed")
    return path


def plugin_path() -> pathlib.Path:
    """The SPT.so of this build tree."""
    value = os.environ.get("SPT_PARAVIEW_PLUGIN")
    if not value:
        pytest.skip("SPT_PARAVIEW_PLUGIN is not set: the plugin was not built "
                    "(SPT_BUILD_PARAVIEW_PLUGIN=OFF) or the test runs outside ctest")
    path = pathlib.Path(value)
    assert path.is_file(), f"SPT_PARAVIEW_PLUGIN={path} does not exist"
    return path


def environment(**overrides: str) -> Dict[str, str]:
    """This process's environment (PYTHONPATH with the build tree's spt, DISPLAY) plus
    ``overrides``."""
    return {**os.environ, **overrides}


def run(command: Sequence[str], env: Optional[Dict[str, str]] = None,
        cwd: Optional[os.PathLike] = None) -> subprocess.CompletedProcess:
    """Run a ParaView executable; fail the test with its output if it fails, or if VTK's
    OpenGL state checks reported an error (ParaView's build has them on)."""
    result = subprocess.run([str(c) for c in command], env=env or environment(), cwd=cwd,
                            capture_output=True, text=True, timeout=SUBPROCESS_TIMEOUT,
                            check=False)
    assert result.returncode == 0, (
        f"{' '.join(map(str, command))} failed ({result.returncode}):\n"
        f"{result.stdout[-4000:]}\n{result.stderr[-4000:]}")
    assert "OpenGL errors detected" not in result.stderr, (
        f"{' '.join(map(str, command))} left OpenGL errors:\n{result.stderr[-4000:]}")
    return result


def scene(data: os.PathLike, output: pathlib.Path, *options) -> list:
    """render_volume.py's arguments for one scene: ``data`` rendered into ``output``, with its
    reports beside it (read_report()), then ``options``."""
    return ["--data", data, "--output", output, "--report", output.with_suffix(""), *options]


def render_command(*scenes: Sequence, program: str = "pvpython") -> List:
    """``program`` running render_volume.py on the scenes (each a scene()), one after the
    other in one process."""
    command = [executable(program), SCRIPTS / "render_volume.py"]
    for index, arguments in enumerate(scenes):
        command += (["--then"] if index else []) + list(arguments)
    return command


def read_report(output: pathlib.Path) -> dict:
    """Rank 0's report on the scene rendered into ``output``."""
    return json.loads(output.with_suffix(".rank0.json").read_text())


def mpirun(ranks: int, command: Sequence[str], preload: Optional[str] = None) -> List[str]:
    """mpirun arguments for ``ranks`` local ranks running ``command`` (root needs consent)."""
    arguments = [executable("mpirun"), "-np", str(ranks), "--oversubscribe"]
    if os.geteuid() == 0:
        arguments.append("--allow-run-as-root")
    if preload:
        arguments += ["-x", f"LD_PRELOAD={preload}"]
    return arguments + [str(c) for c in command]


def artifacts() -> Optional[pathlib.Path]:
    """Where ctest keeps images and measures to look at (SPT_TEST_ARTIFACTS), if set."""
    directory = os.environ.get("SPT_TEST_ARTIFACTS")
    if not directory:
        return None
    path = pathlib.Path(directory)
    path.mkdir(parents=True, exist_ok=True)
    return path


def keep(path: os.PathLike, name: str) -> None:
    directory = artifacts()
    if directory:
        shutil.copy(path, directory / name)


def keep_text(text: str, name: str) -> None:
    directory = artifacts()
    if directory:
        (directory / name).write_text(text)


def wait_for(process: subprocess.Popen, text: str, seconds: float) -> None:
    """Read a process's output until a line contains ``text`` (a server ready to connect)."""
    deadline = time.monotonic() + seconds
    lines = []
    while time.monotonic() < deadline:
        line = process.stdout.readline()
        if not line:
            break
        lines.append(line)
        if text in line:
            return
    raise AssertionError(f"{process.args[0]} never said {text!r}:\n{''.join(lines)}")


def render_on_pvserver(server: Sequence, scenes: Sequence[Sequence], env: Dict[str, str],
                       seconds: float) -> None:
    """Start a pvserver (``server``: its command, given a free port here), run a pvpython client
    that renders the scenes (each a scene()) on it once it accepts connections, and check the
    server ends with its client."""
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        port = probe.getsockname()[1]
    process = subprocess.Popen([*map(str, server), f"--server-port={port}"], env=env,
                               stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        wait_for(process, "Accepting connection", seconds)
        run(render_command(*[[*scene, "--connect", f"localhost:{port}"] for scene in scenes]),
            env=env)
        assert process.wait(timeout=seconds) == 0
    finally:
        if process.poll() is None:
            process.kill()
            process.wait()


# --------------------------------------------------------------------------------------------
# Data: legacy VTK files, which VTK 9.2 reads without expat (see test_paraview_mpi.py)
# --------------------------------------------------------------------------------------------

def write_mesh(path: pathlib.Path, grid=None) -> pathlib.Path:
    """The project's default mesh (48,000 tetrahedra, point scalars "field") as a binary
    legacy .vtk file."""
    from vtkmodules.vtkIOLegacy import vtkUnstructuredGridWriter
    from spt import data

    writer = vtkUnstructuredGridWriter()
    writer.SetFileName(str(path))
    writer.SetInputData(grid if grid is not None else data.make_default_mesh())
    writer.SetFileTypeToBinary()
    assert writer.Write() == 1
    return path


def cell_centers(grid) -> np.ndarray:
    """(cells, 3) array of the cells' centers."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkFiltersCore import vtkCellCenters

    centers = vtkCellCenters()
    centers.SetInputData(grid)
    centers.Update()
    return vtk_to_numpy(centers.GetOutput().GetPoints().GetData())


def write_pieces(directory: pathlib.Path, cells_of_piece) -> pathlib.Path:
    """The default mesh split into pieces by ``cells_of_piece(grid) -> [cell ids of each
    piece]``, as pieces.N.vtk and a pieces.pvtk that ParaView's legacy reader hands out one
    piece per rank. Each cell keeps its id in the whole as its global id (cell data
    GlobalIds), which SPT's random numbers follow."""
    from vtkmodules.util.numpy_support import numpy_to_vtk
    from vtkmodules.vtkCommonCore import VTK_ID_TYPE, vtkIdList
    from vtkmodules.vtkFiltersCore import vtkExtractCells
    from spt import data

    grid = data.make_default_mesh()
    global_ids = numpy_to_vtk(np.arange(grid.GetNumberOfCells()), deep=True,
                              array_type=VTK_ID_TYPE)
    global_ids.SetName("GlobalIds")
    grid.GetCellData().SetGlobalIds(global_ids)
    pieces = cells_of_piece(grid)
    entries = []
    for index, ids in enumerate(pieces):
        id_list = vtkIdList()
        for cell in ids:
            id_list.InsertNextId(int(cell))
        extract = vtkExtractCells()
        extract.SetInputData(grid)
        extract.SetCellList(id_list)
        extract.Update()
        piece = write_mesh(directory / f"pieces.{index}.vtk", extract.GetOutput())
        entries.append(f'  <Piece fileName="{piece.name}" />')
    index_file = directory / "pieces.pvtk"
    index_file.write_text(
        '<File version="pvtk-1.0" dataType="vtkUnstructuredGrid" '
        f'numberOfPieces="{len(pieces)}" >\n' + "\n".join(entries) + "\n</File>\n")
    return index_file


# --------------------------------------------------------------------------------------------
# Images
# --------------------------------------------------------------------------------------------

def read_png(path: os.PathLike) -> np.ndarray:
    """An RGB(A) PNG as float in [0, 1], row 0 at the top."""
    from vtkmodules.vtkIOImage import vtkPNGReader
    from spt import metrics

    reader = vtkPNGReader()
    reader.SetFileName(str(path))
    reader.Update()
    return metrics.from_vtk_image(reader.GetOutput(), as_float_rgba=True)


def read_xwd(path: os.PathLike) -> np.ndarray:
    """An X window dump (what Xvfb -fbdir keeps of its screen) as uint8 RGB, row 0 at the
    top. Handles the 24-bit TrueColor ZPixmap dumps of Xvfb (32 bits per pixel)."""
    raw = pathlib.Path(path).read_bytes()
    (header_size, _version, pixmap_format, _depth, width, height, _xoffset, byte_order,
     _unit, _bit_order, _pad, bits_per_pixel, bytes_per_line, _visual, red_mask, green_mask,
     blue_mask, _bits_per_rgb, _entries, colors) = struct.unpack(">20I", raw[:80])
    assert pixmap_format == 2 and bits_per_pixel == 32, "only 32-bit ZPixmap dumps"
    offset = header_size + 12 * colors
    rows = np.frombuffer(raw, dtype=np.uint8, count=bytes_per_line * height, offset=offset)
    words = rows.reshape(height, bytes_per_line)[:, :4 * width].copy().view(
        "<u4" if byte_order == 0 else ">u4").reshape(height, width)

    def channel(mask: int) -> np.ndarray:
        shift = (mask & -mask).bit_length() - 1
        return ((words & mask) >> shift).astype(np.uint8)

    return np.dstack([channel(red_mask), channel(green_mask), channel(blue_mask)])


def footprint(image: np.ndarray, background=(0.0, 0.0, 0.0), threshold: float = 2.5 / 255.0
              ) -> np.ndarray:
    """Pixels that differ from the background color."""
    return np.abs(image[..., :3] - np.asarray(background)).max(axis=-1) > threshold


def check_volume_image(image: np.ndarray, background=(0.0, 0.0, 0.0),
                       threshold: float = 2.5 / 255.0) -> None:
    """A volume over the background, not an empty view: part of the view differs from the
    background (by more than ``threshold``), with varied colors."""
    covered = footprint(image, background, threshold)
    assert 0.05 < covered.mean() < 0.8, f"{covered.mean():.3f} of the view is covered"
    colors = image[covered][:, :3]
    assert colors.mean() > 0.1
    assert colors.std(axis=0).max() > 0.05, "a flat color, not a volume"


def box_filter(image: np.ndarray, radius: int) -> np.ndarray:
    """Mean over (2 radius + 1)^2 pixels (wrapping at the border, which is background)."""
    total = np.zeros_like(image)
    for dy in range(-radius, radius + 1):
        for dx in range(-radius, radius + 1):
            total += np.roll(np.roll(image, dy, axis=0), dx, axis=1)
    return total / (2 * radius + 1) ** 2
