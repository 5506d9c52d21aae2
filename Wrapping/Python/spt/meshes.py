"""Generated test meshes at any size: a drill bit and a bumpy ring, meshed with TetGen.

    from spt import meshes
    grid = meshes.generate("drill", 1_000_000)   # about 10^6 tetrahedra, cached on disk

Both shapes are closed surfaces swept from rings (closed loops of points), so they are
triangulated at any resolution without self-intersections:

* ``"drill"``: the paper's large data set is a drill; this one is a drill bit along +z: a
  cylindrical shank with a flat end, a body with two helical flutes (1.5 turns; the flutes are
  0.45 of the radius deep, so the shape is strongly non-convex) and a conical point of 118
  degrees that the flutes run into.
* ``"torus"``: a ring (radii 1 and 0.3) whose centre line rises and falls twice around it, with
  a bump on its outer side.

:func:`surface` gives the triangulated surface, :func:`generate` the tetrahedral mesh
(:class:`spt.vtkTetGenMesher`) with the point scalar ``"field"`` (active): smooth, with several
maxima inside the shape placed by ``seed``. The surface's resolution follows the cell count, so
large meshes have smooth surfaces, not coarse ones filled with small tetrahedra. Meshes are
cached in ``SPT_CACHE_DIR`` (default ``~/.cache/spt/meshes``) as NumPy ``.npz`` files.
"""

from __future__ import annotations

import math
import os
import pathlib
import tempfile
import warnings
import zipfile
from dataclasses import dataclass
from typing import BinaryIO, Callable, List, Optional, Tuple

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import (
    VTK_TETRA,
    vtkCellArray,
    vtkPolyData,
    vtkUnstructuredGrid,
)

SHAPES = ("drill", "torus")
FIELD_NAME = "field"
MIN_CELLS = 10_000
MAX_CELLS = 30_000_000
# Part of every cache file's name: raise it whenever the shapes, the field or the meshing
# change, so that no stale mesh is ever loaded.
FORMAT_VERSION = 1
# Of the meshed count over the asked one, generate() accepts this much before it meshes again
# with a corrected volume bound.
RETRY_TOLERANCE = 0.15

# Surface edge length over the edge length of a regular tetrahedron of the mean tetrahedron
# volume, and TetGen's -a bound over that mean volume.
SURFACE_EDGE_FACTOR = 1.5
MEAN_VOLUME_FACTOR = 2.4
# With these, TetGen (RadiusEdgeRatio 1.414) gives N * (INTERIOR + BOUNDARY[shape] / N^(1/3))
# tetrahedra for a nominal N = volume / mean volume: the interior term, and a layer of smaller
# tetrahedra along the surface that counts more in small meshes (fitted to TetGen's counts
# from 10^4 to 10^6; see _nominal_cells).
INTERIOR_RATIO = 0.65
BOUNDARY_RATIO = {"drill": 50.6, "torus": 66.2}

# The drill (units: the shank's radius is 0.4; the bit is 4.27 long).
SHANK_RADIUS, SHANK_LENGTH = 0.4, 1.5
BODY_RADIUS, BODY_END = 0.45, 4.0
TRANSITION_LENGTH = 0.3
FLUTE_DEPTH, FLUTE_SHARPNESS, FLUTE_TURNS = 0.45, 3.0, 1.5
TIP_LENGTH = BODY_RADIUS / math.tan(math.radians(59.0))
# The ring (units: centre-line radius 1).
RING_RADIUS, TUBE_RADIUS = 1.0, 0.3
RING_WAVE, BUMP_HEIGHT, BUMP_WIDTH = 0.15, 0.4, 0.5


# Surfaces from rings ------------------------------------------------------------------------

@dataclass
class Ring:
    """A closed loop of points with their angle around the loop (increasing, in [0, 2 pi))."""

    points: np.ndarray  # (n, 3)
    angles: np.ndarray  # (n,)


def _zip_rings(first: Ring, second: Ring, first_offset: int,
               second_offset: int) -> np.ndarray:
    """Triangles between two rings, merged by angle (n1 + n2 triangles, oriented alike for
    every pair, first ring "below" the second). A ring of one point gives a fan."""
    n1, n2 = len(first.angles), len(second.angles)
    a1 = np.append(first.angles, first.angles[0] + 2.0 * math.pi)
    # Start the second ring at its point nearest in angle to the first ring's first point, and
    # unwrap its angles to increase from there.
    start = int(np.argmin(np.abs(np.angle(np.exp(1j * (second.angles - a1[0]))))))
    order = (start + np.arange(n2 + 1)) % n2
    a2 = np.unwrap(second.angles[order])
    a2 += 2.0 * math.pi * np.round((a1[0] - a2[0]) / (2.0 * math.pi))
    a2[-1] = a2[0] + 2.0 * math.pi  # also for a ring of one point
    # Each step advances along one of the rings, the one whose next angle comes first, and
    # adds the triangle (lower, next lower, upper) or (lower, next upper, upper).
    keys = np.concatenate([a1[1:], a2[1:]])
    advance_first = np.concatenate([np.ones(n1, bool), np.zeros(n2, bool)])[
        np.argsort(keys, kind="stable")]
    i = np.concatenate([[0], np.cumsum(advance_first)])[:-1]
    j = np.concatenate([[0], np.cumsum(~advance_first)])[:-1]
    lower = first_offset + i % n1
    upper = second_offset + order[j % n2]
    next_lower = first_offset + (i + 1) % n1
    next_upper = second_offset + order[(j + 1) % n2]
    triangles = np.stack(
        [lower, np.where(advance_first, next_lower, next_upper), upper], axis=1)
    # Advancing along a ring of one point adds nothing.
    keep = ~((advance_first & (n1 == 1)) | (~advance_first & (n2 == 1)))
    return triangles[keep].astype(np.int64)


def _sweep(rings: List[Ring], closed: bool) -> Tuple[np.ndarray, np.ndarray]:
    """Points and outward-facing triangles of a sweep through ``rings`` (ends of one point
    each unless ``closed``, a loop)."""
    offsets = np.cumsum([0] + [len(ring.angles) for ring in rings])
    pairs = list(zip(range(len(rings) - 1), range(1, len(rings))))
    if closed:
        pairs.append((len(rings) - 1, 0))
    triangles = np.concatenate([
        _zip_rings(rings[a], rings[b], offsets[a], offsets[b]) for a, b in pairs])
    points = np.concatenate([ring.points for ring in rings])
    if signed_volume(points, triangles) < 0.0:
        triangles = triangles[:, ::-1].copy()
    return points, triangles


def signed_volume(points: np.ndarray, triangles: np.ndarray) -> float:
    """The volume a closed triangulated surface encloses, positive when its triangles face out."""
    a, b, c = (points[triangles[:, k]] for k in range(3))
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


def _resample_by_arc_length(profile: Callable[[np.ndarray], np.ndarray],
                            count: int) -> Tuple[np.ndarray, float]:
    """``count`` angles evenly spaced along the closed polar curve r = profile(theta), and the
    curve's length."""
    theta = np.linspace(0.0, 2.0 * math.pi, 2049)
    radius = profile(theta)
    xy = np.stack([radius * np.cos(theta), radius * np.sin(theta)], axis=1)
    length = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(xy, axis=0), axis=1))])
    targets = length[-1] * np.arange(count) / count
    return np.interp(targets, length, theta), float(length[-1])


def _polar_ring(profile: Callable[[np.ndarray], np.ndarray], z: float,
                spacing: float) -> Ring:
    """The closed curve r = profile(theta) at height z, with points ``spacing`` apart."""
    _, length = _resample_by_arc_length(profile, 64)
    count = max(3, int(round(length / spacing)))
    if length < 1e-12:
        return Ring(np.array([[0.0, 0.0, z]]), np.zeros(1))
    angles, _ = _resample_by_arc_length(profile, count)
    radius = profile(angles)
    points = np.stack([radius * np.cos(angles), radius * np.sin(angles), np.full(count, z)], 1)
    return Ring(points, angles)


def _meridian_samples(corners: np.ndarray, spacing: float) -> np.ndarray:
    """Points along the polyline ``corners`` (rows (z, rho)) about ``spacing`` apart, with
    every corner among them."""
    samples = [corners[:1]]
    for start, end in zip(corners[:-1], corners[1:]):
        steps = max(1, int(round(np.linalg.norm(end - start) / spacing)))
        t = np.arange(1, steps + 1)[:, None] / steps
        samples.append(start + t * (end - start))
    return np.concatenate(samples)


# The shapes ---------------------------------------------------------------------------------

def _smoothstep(t: np.ndarray) -> np.ndarray:
    t = np.clip(t, 0.0, 1.0)
    return t * t * (3.0 - 2.0 * t)


def _drill_twist(z):
    """The flutes' angle at height z (a number or an array)."""
    length = BODY_END + TIP_LENGTH - SHANK_LENGTH
    return 2.0 * math.pi * FLUTE_TURNS * np.maximum(0.0, z - SHANK_LENGTH) / length


def _drill_profile(z: float, radius: float) -> Callable[[np.ndarray], np.ndarray]:
    """Cross-section at height z scaled to ``radius``: two flutes, twisted with z."""
    depth = FLUTE_DEPTH * float(_smoothstep((z - SHANK_LENGTH) / TRANSITION_LENGTH))
    twist = _drill_twist(z)

    def profile(theta: np.ndarray) -> np.ndarray:
        flute = (0.5 - 0.5 * np.cos(2.0 * (theta - twist))) ** FLUTE_SHARPNESS
        return radius * (1.0 - depth * flute)
    return profile


def _drill_rings(spacing: float) -> Tuple[List[Ring], bool]:
    # The meridian (z, radius of the cross-section) from the centre of the shank's flat end,
    # out to its rim, up the shank and the body, to the point.
    corners = np.array([
        [0.0, 0.0], [0.0, SHANK_RADIUS], [SHANK_LENGTH, SHANK_RADIUS],
        [SHANK_LENGTH + TRANSITION_LENGTH, BODY_RADIUS], [BODY_END, BODY_RADIUS],
        [BODY_END + TIP_LENGTH, 0.0]])
    rings = []
    for z, radius in _meridian_samples(corners, spacing):
        rings.append(_polar_ring(_drill_profile(z, radius), z, spacing))
    return rings, False


def _torus_centre(u: np.ndarray) -> np.ndarray:
    return np.stack([RING_RADIUS * np.cos(u), RING_RADIUS * np.sin(u),
                     RING_WAVE * np.sin(2.0 * u)], axis=-1)


def _torus_tube_radius(u: float, v: np.ndarray) -> np.ndarray:
    """Tube radius at angle u around the ring and v around the tube (v = 0 outwards)."""
    along = math.exp(-(math.remainder(u - 0.5 * math.pi, 2.0 * math.pi) / BUMP_WIDTH) ** 2)
    across = (0.5 + 0.5 * np.cos(v)) ** 2
    return TUBE_RADIUS * (1.0 + BUMP_HEIGHT * along * across)


def _torus_rings(spacing: float) -> Tuple[List[Ring], bool]:
    count = max(8, int(round(2.0 * math.pi * RING_RADIUS / spacing)))
    rings = []
    for u in 2.0 * math.pi * np.arange(count) / count:
        centre = _torus_centre(np.array(u))
        outward = np.array([math.cos(u), math.sin(u), 0.0])
        up = np.array([0.0, 0.0, 1.0])
        ring = _polar_ring(lambda v, u=u: _torus_tube_radius(u, v), 0.0, spacing)
        radial, vertical = ring.points[:, 0], ring.points[:, 1]
        points = centre + radial[:, None] * outward + vertical[:, None] * up
        rings.append(Ring(points, ring.angles))
    return rings, True


_RINGS = {"drill": _drill_rings, "torus": _torus_rings}
# The radius of the widest circumference, which a surface's resolution divides.
_WIDEST = {"drill": BODY_RADIUS, "torus": TUBE_RADIUS * (1.0 + BUMP_HEIGHT)}
# Enclosed volumes, for the resolution a cell count needs (from a fine surface; within 0.1 %).
_VOLUMES = {"drill": 2.0160, "torus": 1.8785}


def _check_shape(shape: str) -> None:
    if shape not in SHAPES:
        raise ValueError(f"unknown shape {shape!r}; choose from {', '.join(SHAPES)}")


def _check_whole(name: str, value) -> None:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise ValueError(f"{name} must be a whole number, not {value!r}")


def surface_arrays(shape: str, resolution: int) -> Tuple[np.ndarray, np.ndarray]:
    """Points (n, 3) and outward triangles (m, 3) of the shape's surface; ``resolution`` is the
    number of points around the shape's widest circumference (at least 8)."""
    _check_shape(shape)
    _check_whole("resolution", resolution)
    if not 8 <= resolution <= 100_000:
        raise ValueError(f"resolution {resolution} is outside 8..100000")
    rings, closed = _RINGS[shape](2.0 * math.pi * _WIDEST[shape] / resolution)
    return _sweep(rings, closed)


def surface(shape: str, resolution: int = 64) -> vtkPolyData:
    """The shape's closed, triangulated, outward-facing surface; ``resolution`` is the number
    of points around its widest circumference."""
    points, triangles = surface_arrays(shape, resolution)
    polydata = vtkPolyData()
    polydata.SetPoints(_vtk_points(points))
    polydata.SetPolys(cell_array(triangles))
    return polydata


def _nominal_cells(shape: str, cells: int) -> float:
    """The nominal N of the count model that gives ``cells`` tetrahedra (by bisection: the
    model's count grows with N)."""
    def count(nominal: float) -> float:
        return nominal * (INTERIOR_RATIO + BOUNDARY_RATIO[shape] / nominal ** (1.0 / 3.0))
    low, high = 1.0, 10.0 * cells / INTERIOR_RATIO
    for _ in range(100):
        middle = math.sqrt(low * high)
        low, high = (middle, high) if count(middle) < cells else (low, middle)
    return low


def mesh_parameters(shape: str, cells: int) -> Tuple[int, float]:
    """The surface resolution and TetGen's volume bound for about ``cells`` tetrahedra."""
    _check_shape(shape)
    mean_volume = _VOLUMES[shape] / _nominal_cells(shape, cells)
    regular_edge = (6.0 * math.sqrt(2.0) * mean_volume) ** (1.0 / 3.0)
    resolution = 2.0 * math.pi * _WIDEST[shape] / (SURFACE_EDGE_FACTOR * regular_edge)
    return max(8, int(round(resolution))), MEAN_VOLUME_FACTOR * mean_volume


# The field ----------------------------------------------------------------------------------

def _blob_centres(shape: str, seed: int) -> Tuple[np.ndarray, np.ndarray]:
    """Centres and widths of the field's maxima, inside the shape (on its axis or centre
    line), placed by ``seed``."""
    rng = np.random.default_rng(seed)
    if shape == "drill":
        z = np.sort(rng.uniform(0.4, BODY_END, 4))
        centres = np.stack([np.zeros(4), np.zeros(4), z], axis=1)
        return centres, rng.uniform(0.25, 0.5, 4)
    u = rng.uniform(0.0, 2.0 * math.pi, 3)
    return _torus_centre(u), rng.uniform(0.2, 0.4, 3)


def field(shape: str, points: np.ndarray, seed: int = 0) -> np.ndarray:
    """The analytic field at ``points`` (n, 3), in [0, 1]: Gaussian maxima inside the shape,
    placed by ``seed``, over a wave that follows the shape (the flutes' helix of the drill, the
    angle around the ring's tube), so that every range of values forms nested shells."""
    _check_shape(shape)
    points = np.asarray(points, dtype=np.float64)
    centres, widths = _blob_centres(shape, seed)
    blobs = np.zeros(len(points))
    for centre, width in zip(centres, widths):
        blobs += np.exp(-np.sum((points - centre) ** 2, axis=1) / (2.0 * width ** 2))
    x, y, z = points[:, 0], points[:, 1], points[:, 2]
    if shape == "drill":
        wave = np.cos(2.0 * (np.arctan2(y, x) - _drill_twist(z))) * np.hypot(x, y) / BODY_RADIUS
    else:
        radial = np.hypot(x, y) - RING_RADIUS
        wave = np.sin(3.0 * np.arctan2(y, x)) * np.cos(np.arctan2(z, radial))
    values = 0.7 * blobs / max(blobs.max(initial=0.0), 1e-12) + 0.3 * (0.5 + 0.5 * wave)
    return values.astype(np.float32)


# Meshing and the cache ----------------------------------------------------------------------

def _check_arguments(shape: str, cells: int, seed: int) -> None:
    _check_shape(shape)
    _check_whole("cells", cells)
    _check_whole("seed", seed)
    if not MIN_CELLS <= cells <= MAX_CELLS:
        raise ValueError(f"cells {cells} is outside {MIN_CELLS}..{MAX_CELLS}")
    if seed < 0:
        raise ValueError(f"seed must be >= 0, not {seed}")


def cache_dir() -> pathlib.Path:
    """Where generated meshes are kept: ``SPT_CACHE_DIR`` or ``~/.cache/spt/meshes``."""
    configured = os.environ.get("SPT_CACHE_DIR")
    if configured:
        return pathlib.Path(configured)
    return pathlib.Path.home() / ".cache" / "spt" / "meshes"


def cache_path(shape: str, cells: int, seed: int = 0) -> pathlib.Path:
    """The cache file of one mesh (its name holds every input and the format version)."""
    _check_arguments(shape, cells, seed)
    return cache_dir() / f"{shape}-{cells}-seed{seed}-v{FORMAT_VERSION}.npz"


@dataclass
class MeshArrays:
    """A tetrahedral mesh as arrays: points (n, 3) float64, tetrahedra (m, 4) int32 (positively
    oriented), field (n,) float32."""

    points: np.ndarray
    tetrahedra: np.ndarray
    field: np.ndarray


def tetrahedralize(shape: str, cells: int) -> Tuple[np.ndarray, np.ndarray]:
    """Points and tetrahedra of the shape meshed by TetGen to about ``cells`` tetrahedra; if the
    first count is off by more than RETRY_TOLERANCE, meshed once more with a corrected bound."""
    from . import HAVE_MESHING, MeshingUnavailable
    if not HAVE_MESHING:
        raise MeshingUnavailable(f"Meshing the {shape} of about {cells} tetrahedra")
    from . import vtkTetGenMesher

    resolution, bound = mesh_parameters(shape, cells)
    polydata = surface(shape, resolution)
    for attempt in range(2):
        mesher = vtkTetGenMesher()
        mesher.SetInputData(polydata)
        mesher.SetMaximumVolume(bound)
        mesher.Update()
        grid = mesher.GetOutput()
        count = grid.GetNumberOfCells()
        if count == 0:
            raise RuntimeError(f"TetGen failed on the {shape} surface (see the error above)")
        if abs(count / cells - 1.0) <= RETRY_TOLERANCE or attempt == 1:
            break
        bound *= count / cells
    points = vtk_to_numpy(grid.GetPoints().GetData()).astype(np.float64)
    tetrahedra = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).reshape(-1, 4)
    return points, tetrahedra.astype(np.int32)


def save_atomically(path: pathlib.Path, write: Callable[[BinaryIO], None]) -> None:
    """Write a cache file with ``write`` into a temporary file in the same directory, renamed
    over ``path``: a reader sees the whole file or none, and an interrupted run leaves none."""
    path.parent.mkdir(parents=True, exist_ok=True)
    handle, temporary = tempfile.mkstemp(prefix=path.stem, suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(handle, "wb") as stream:
            write(stream)
        os.replace(temporary, path)
    except BaseException:
        pathlib.Path(temporary).unlink(missing_ok=True)
        raise


def load_cached(path: pathlib.Path) -> Optional[MeshArrays]:
    """The cached mesh, or None when the file is missing, unreadable or of another format."""
    try:
        with np.load(path, allow_pickle=False) as data:
            if int(data["format_version"]) != FORMAT_VERSION:
                return None
            mesh = MeshArrays(data["points"], data["tetrahedra"], data["field"])
    except (OSError, KeyError, ValueError, zipfile.BadZipFile):
        return None
    points_ok = mesh.points.ndim == 2 and mesh.points.shape[1] == 3
    tets_ok = (mesh.tetrahedra.ndim == 2 and mesh.tetrahedra.shape[1] == 4
               and mesh.tetrahedra.size > 0 and 0 <= mesh.tetrahedra.min()
               and mesh.tetrahedra.max() < len(mesh.points))
    if not (points_ok and tets_ok and mesh.field.shape == (len(mesh.points),)):
        return None
    return mesh


def generate_arrays(shape: str, cells: int, seed: int = 0, cache: bool = True) -> MeshArrays:
    """:func:`generate`'s mesh as NumPy arrays."""
    path = cache_path(shape, cells, seed)
    if cache:
        mesh = load_cached(path)
        if mesh is not None:
            return mesh
    points, tetrahedra = tetrahedralize(shape, cells)
    mesh = MeshArrays(points, tetrahedra, field(shape, points, seed))
    if cache:
        try:
            save_atomically(path, lambda stream: np.savez(
                stream, points=mesh.points, tetrahedra=mesh.tetrahedra, field=mesh.field,
                format_version=np.array(FORMAT_VERSION)))
        except OSError as error:
            # The cache only spares the next run the meshing; this mesh is still good.
            warnings.warn(f"the mesh could not be cached at {path}: {error}", stacklevel=2)
    return mesh


def to_grid(mesh: MeshArrays) -> vtkUnstructuredGrid:
    """A vtkUnstructuredGrid of VTK_TETRA cells with the active point scalars "field"."""
    grid = vtkUnstructuredGrid()
    grid.SetPoints(_vtk_points(mesh.points))
    grid.SetCells(VTK_TETRA, cell_array(mesh.tetrahedra))
    values = numpy_to_vtk(np.ascontiguousarray(mesh.field, dtype=np.float32), deep=True)
    values.SetName(FIELD_NAME)
    grid.GetPointData().SetScalars(values)
    return grid


def generate(shape: str, cells: int, seed: int = 0, cache: bool = True) -> vtkUnstructuredGrid:
    """A tetrahedral mesh of ``shape`` ("drill" or "torus") with about ``cells`` tetrahedra
    (within 25 %; 10,000 to 30,000,000) and the active point scalars "field".

    ``seed`` places the field's maxima (the mesh itself depends only on shape and cells). With
    ``cache``, the mesh is read from, or written to, :func:`cache_path`. TetGen takes about
    30 microseconds of CPU and 200 to 260 bytes per tetrahedron: 35 s for 10^6, 7 to 15
    minutes and 3 GB for 1.3 * 10^7 (see Documentation/design.md).
    """
    return to_grid(generate_arrays(shape, cells, seed, cache))


def write_legacy(grid: vtkUnstructuredGrid, path: pathlib.Path) -> None:
    """Write ``grid`` as a binary VTK legacy file (``.vtk``)."""
    from vtkmodules.vtkIOLegacy import vtkUnstructuredGridWriter

    path = pathlib.Path(path)
    if path.suffix != ".vtk":
        raise ValueError(f"the output {path} must end in .vtk (VTK legacy format)")
    if not path.parent.is_dir():
        raise ValueError(f"the output's folder {path.parent} does not exist")
    writer = vtkUnstructuredGridWriter()
    writer.SetFileName(str(path))
    writer.SetFileTypeToBinary()
    writer.SetInputData(grid)
    if writer.Write() != 1:
        raise OSError(f"could not write {path}")


def _vtk_points(points: np.ndarray) -> vtkPoints:
    result = vtkPoints()
    result.SetData(numpy_to_vtk(np.ascontiguousarray(points, dtype=np.float64), deep=True))
    return result


def cell_array(cells: np.ndarray) -> vtkCellArray:
    """A vtkCellArray of cells of equal size from an (m, k) array of point ids."""
    count, size = cells.shape
    offsets = numpy_to_vtkIdTypeArray(np.arange(0, (count + 1) * size, size, dtype=np.int64),
                                      deep=True)
    connectivity = numpy_to_vtkIdTypeArray(np.ascontiguousarray(cells, dtype=np.int64).ravel(),
                                           deep=True)
    result = vtkCellArray()
    result.SetData(offsets, connectivity)
    return result


def interleaved_piece(grid: vtkUnstructuredGrid, rank: int, ranks: int,
                      empty: bool = False) -> vtkUnstructuredGrid:
    """The piece of ``grid`` that rank ``rank`` of ``ranks`` draws when the cells are dealt
    out in turn: the cells whose id is ``rank`` modulo ``ranks`` (none if ``empty``), with
    their ids in the whole as global ids. ``grid`` is not modified."""
    from vtkmodules.vtkCommonCore import VTK_ID_TYPE, vtkIdList
    from vtkmodules.vtkFiltersCore import vtkExtractCells

    whole = vtkUnstructuredGrid()
    whole.ShallowCopy(grid)
    ids = numpy_to_vtk(np.arange(grid.GetNumberOfCells()), deep=True, array_type=VTK_ID_TYPE)
    ids.SetName("GlobalIds")
    whole.GetCellData().SetGlobalIds(ids)
    keep = vtkIdList()
    for cell in range(rank, 0 if empty else grid.GetNumberOfCells(), ranks):
        keep.InsertNextId(cell)
    extract = vtkExtractCells()
    extract.SetInputData(whole)
    extract.SetCellList(keep)
    extract.Update()
    return extract.GetOutput()
