"""Data sets for the SPT volume mapper: real meshes, an embedded default mesh and
transfer-function presets.

Every loader returns a ``vtkUnstructuredGrid`` whose point data holds exactly one array, the
scalar to render, set as the active point scalars. By default meshes are converted to tetrahedra
with ``vtkDataSetTriangleFilter`` (TetrahedraOnly on), which is what the SPT mapper consumes.

The real data sets are not part of the repository. They are read from the directory that the
environment variable ``SPT_DATA_DIR`` names (the command line's ``--data-dir`` sets it), and
from nowhere else: no folder is guessed (see :func:`data_dir`).
"""

from __future__ import annotations

import itertools
import math
import os
import pathlib
from typing import Callable, Dict, Optional, Sequence, Tuple

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import (
    vtkDataObject,
    vtkDataObjectTreeIterator,
    vtkDataSet,
    vtkDataSetAttributes,
    vtkPiecewiseFunction,
    vtkStructuredGrid,
    vtkUnstructuredGrid,
)
from vtkmodules.vtkFiltersCore import vtkAppendFilter, vtkThreshold
from vtkmodules.vtkFiltersGeneral import vtkDataSetTriangleFilter
from vtkmodules.vtkIOExodus import vtkExodusIIReader
from vtkmodules.vtkIOLegacy import (
    vtkStructuredGridReader,
    vtkStructuredPointsReader,
    vtkUnstructuredGridReader,
)
from vtkmodules.vtkIOParallel import vtkMultiBlockPLOT3DReader
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
from vtkmodules.vtkRenderingCore import (
    vtkColorTransferFunction,
    vtkVolumeProperty,
)

#: Environment variable naming the directory that holds the real data sets.
DATA_DIR_ENV = "SPT_DATA_DIR"

#: Name of the scalar array of :func:`make_default_mesh`.
DEFAULT_FIELD_NAME = "field"

#: name -> (description, point scalar array). Treat as read-only.
DATASETS: Dict[str, Tuple[str, str]] = {
    "spx": ("SPX, Super Phoenix reactor coolant (spx.vtk)", "scalars"),
    "bluntfin": ("NASA Blunt Fin, PLOT3D 40x32x32 (bluntfin*.bin)", "Density"),
    "post": ("NASA Liquid Oxygen Post, PLOT3D 38x76x38 with IBLANK (post*.bin)",
             "VelocityMagnitude"),
    "torus": ("torus tet mesh, many inverted tets (torus.vtk)", "scalars"),
    "tetramesh": ("tiny tet mesh, 160 tets (tetraMesh.vtk)", "scalars"),
    "postvtk": ("tet mesh of a post, VTK test data (post.vtk)", "Pressure"),
    "office": ("office air flow, structured grid 21x20x20 (office.binary.vtk)", "scalars"),
    "fire": ("room fire CFD, hexahedra (fire_ug.vtu)", "t"),
    "hexa": ("AMR-like hexahedral mesh (hexa.vtk)", "scalars"),
    "disk": ("ParaView disk example, Exodus II (disk_out_ref.ex2)", "Temp"),
    "ironprot": ("iron protein 68^3 image thresholded to 80..255, as in VTK's projected "
                 "tetrahedra test (ironProt.vtk)", "scalars"),
    "ironprot_full": ("iron protein 68^3 image in full, 1.5 M tets (ironProt.vtk)", "scalars"),
}

# Marks a helper cell array that flags cells to drop (blanked in PLOT3D).
_HIDDEN_ARRAY = "spt_hidden"


# Locating the data --------------------------------------------------------

def data_dir() -> pathlib.Path:
    """The directory holding the real data sets: ``$SPT_DATA_DIR``, and only that (the working
    directory and its parents are not searched, so the same command finds the same data sets
    wherever it runs). FileNotFoundError if it is unset, empty or not a directory."""
    env = os.environ.get(DATA_DIR_ENV)
    if not env:
        raise FileNotFoundError(
            f"no data directory: set the environment variable {DATA_DIR_ENV} (or the command "
            "line's --data-dir) to the folder holding the data sets")
    path = pathlib.Path(env).expanduser()
    if not path.is_dir():
        raise FileNotFoundError(f"{DATA_DIR_ENV}={env!r} is not a directory")
    return path.resolve()


def _data_file(filename: str) -> str:
    """Full path of a data file, checking that it exists."""
    path = data_dir() / filename
    if not path.is_file():
        raise FileNotFoundError(f"data file {path} is missing")
    return str(path)


# Readers: each returns a vtkDataSet with the wanted point array present ---

class UnreadableDataError(RuntimeError):
    """VTK's reader could not read a data file that is present."""


def _read(reader, filename: str) -> vtkDataSet:
    """The output of one of VTK's file readers (a legacy reader reads all scalars);
    UnreadableDataError, naming the file, when the reader fails or reads no cells (a truncated
    file, or a Git LFS pointer in its place)."""
    path = _data_file(filename)
    reader.SetFileName(path)
    if hasattr(reader, "ReadAllScalarsOn"):
        reader.ReadAllScalarsOn()
    reader.Update()
    output = reader.GetOutput()
    if not (reader.GetErrorCode() or output is None or output.GetNumberOfCells() == 0):
        return output
    if isinstance(reader, vtkXMLUnstructuredGridReader):
        # Seen on Debian 12: VTK 9.2's XML parser hands expat its input in pieces around the
        # appended data, which expat rejects as "not well-formed" since its security updates:
        # reading worked with 2.5.0-1+deb12u1 and fails with 2.5.0-1+deb12u5.
        raise UnreadableDataError(
            f"VTK's XML reader could not read {path}. With VTK 9.2 this happens for files "
            "with appended data under the security updates of the system's expat (Debian 12: "
            "2.5.0-1+deb12u5 fails, 2.5.0-1+deb12u1 worked); convert the file with a newer "
            "VTK or ParaView.")
    raise UnreadableDataError(
        f"VTK's legacy reader read no cells from {path}: the file is damaged, truncated, "
        "or not the data set itself (a Git LFS pointer, for one)")


def _read_exodus(filename: str, array: str) -> vtkDataSet:
    """Read an Exodus II file and merge its element blocks into one grid."""
    reader = vtkExodusIIReader()
    reader.SetFileName(_data_file(filename))
    reader.UpdateInformation()
    reader.SetPointResultArrayStatus(array, 1)
    reader.SetGenerateObjectIdCellArray(0)
    reader.SetGenerateGlobalElementIdArray(0)
    reader.SetGenerateGlobalNodeIdArray(0)
    reader.Update()
    append = vtkAppendFilter()
    append.MergePointsOn()
    iterator = vtkDataObjectTreeIterator()
    iterator.SetDataSet(reader.GetOutput())
    iterator.InitTraversal()
    while not iterator.IsDoneWithTraversal():
        append.AddInputData(iterator.GetCurrentDataObject())
        iterator.GoToNextItem()
    append.Update()
    return append.GetOutput()


def _read_plot3d(stem: str, function: Optional[int], iblanking: bool) -> vtkDataSet:
    """Block 0 of a single-grid big-endian binary PLOT3D pair, with the cell array of
    :func:`flag_hidden_cells`. ``function`` is a PLOT3D derived-scalar number (153:
    VelocityMagnitude); None keeps the reader's default (100, Density)."""
    reader = vtkMultiBlockPLOT3DReader()
    reader.SetXYZFileName(_data_file(stem + "xyz.bin"))
    reader.SetQFileName(_data_file(stem + "q.bin"))
    reader.AutoDetectFormatOff()
    reader.BinaryFileOn()
    reader.MultiGridOff()
    reader.SetByteOrderToBigEndian()
    reader.SetIBlanking(1 if iblanking else 0)
    if function is not None:
        reader.SetScalarFunctionNumber(function)
    reader.Update()
    grid = reader.GetOutput().GetBlock(0)
    if grid is None or grid.GetNumberOfCells() == 0:
        raise UnreadableDataError(f"VTK's PLOT3D reader read no grid from "
                                  f"{reader.GetXYZFileName()} and its q file")
    flag_hidden_cells(grid)
    return grid


def _threshold(dataset: vtkDataSet, association: int, array: str, low: float,
               high: float) -> vtkDataSet:
    """The cells of ``dataset`` whose values of ``array`` all lie in low..high."""
    thresh = vtkThreshold()
    thresh.SetInputData(dataset)
    thresh.SetInputArrayToProcess(0, 0, 0, association, array)
    thresh.SetLowerThreshold(low)
    thresh.SetUpperThreshold(high)
    thresh.SetThresholdFunction(vtkThreshold.THRESHOLD_BETWEEN)
    thresh.Update()
    return thresh.GetOutput()


def _read_iron_protein(threshold: bool) -> vtkDataSet:
    """ironProt.vtk; with ``threshold`` keep voxels with all values in 80..255, like VTK's own
    projected-tetrahedra test."""
    image = _read(vtkStructuredPointsReader(), "ironProt.vtk")
    if not threshold:
        return image
    return _threshold(image, vtkDataObject.FIELD_ASSOCIATION_POINTS, "scalars", 80.0, 255.0)


# name -> function reading the (not yet converted) data set.
_READERS: Dict[str, Callable[[], vtkDataSet]] = {
    "spx": lambda: _read(vtkUnstructuredGridReader(), "spx.vtk"),
    "bluntfin": lambda: _read_plot3d("bluntfin", None, False),
    "post": lambda: _read_plot3d("post", 153, True),
    "torus": lambda: _read(vtkUnstructuredGridReader(), "torus.vtk"),
    "tetramesh": lambda: _read(vtkUnstructuredGridReader(), "tetraMesh.vtk"),
    "postvtk": lambda: _read(vtkUnstructuredGridReader(), "post.vtk"),
    "office": lambda: _read(vtkStructuredGridReader(), "office.binary.vtk"),
    "fire": lambda: _read(vtkXMLUnstructuredGridReader(), "fire_ug.vtu"),
    "hexa": lambda: _read(vtkUnstructuredGridReader(), "hexa.vtk"),
    "disk": lambda: _read_exodus("disk_out_ref.ex2", "Temp"),
    "ironprot": lambda: _read_iron_protein(threshold=True),
    "ironprot_full": lambda: _read_iron_protein(threshold=False),
}


# Conversion to a clean (tetrahedral) unstructured grid --------------------

def flag_hidden_cells(grid: vtkStructuredGrid) -> None:
    """Add a uint8 cell array ``spt_hidden`` (1 = blanked) to ``grid``: a cell is hidden when
    the ghost array marks it HIDDENCELL, or when any of its corners has IBLANK 0. Negative
    IBLANK values (overset interface points) are kept, as VTK's reader does."""
    hidden = np.zeros(grid.GetNumberOfCells(), dtype=np.uint8)
    ghosts = grid.GetCellData().GetArray(vtkDataSetAttributes.GhostArrayName())
    if ghosts is not None:
        bits = vtk_to_numpy(ghosts) & vtkDataSetAttributes.HIDDENCELL
        hidden |= (bits != 0).astype(np.uint8)
    iblank = grid.GetPointData().GetArray("IBlank")
    if iblank is not None:
        dims = [0, 0, 0]
        grid.GetDimensions(dims)
        blank = vtk_to_numpy(iblank).reshape(dims[2], dims[1], dims[0]) == 0
        corners = np.zeros((dims[2] - 1, dims[1] - 1, dims[0] - 1), dtype=bool)
        for dk, dj, di in itertools.product((0, 1), repeat=3):
            corners |= blank[dk:dk + dims[2] - 1, dj:dj + dims[1] - 1, di:di + dims[0] - 1]
        hidden |= corners.ravel().astype(np.uint8)
    array = numpy_to_vtk(hidden, deep=True)
    array.SetName(_HIDDEN_ARRAY)
    grid.GetCellData().AddArray(array)


def _strip_arrays(dataset: vtkDataSet, array_name: str) -> vtkDataSet:
    """Shallow copy of ``dataset`` keeping only point array ``array_name`` (set as active
    scalars) and the ``spt_hidden`` cell array, if any."""
    scalars = dataset.GetPointData().GetArray(array_name)
    if scalars is None:
        raise UnreadableDataError(f"the data set has no point array {array_name!r}")
    stripped = dataset.NewInstance()
    stripped.CopyStructure(dataset)
    stripped.GetPointData().AddArray(scalars)
    stripped.GetPointData().SetActiveScalars(array_name)
    hidden = dataset.GetCellData().GetArray(_HIDDEN_ARRAY)
    if hidden is not None:
        stripped.GetCellData().AddArray(hidden)
    return stripped


def to_unstructured(dataset: vtkDataSet, array_name: str,
                    tetrahedralize: bool) -> vtkUnstructuredGrid:
    """Convert a data set to an unstructured grid (tetrahedra when ``tetrahedralize``) whose
    only array is point scalar ``array_name``, without the cells flagged as hidden."""
    dataset = _strip_arrays(dataset, array_name)
    if tetrahedralize:
        converter = vtkDataSetTriangleFilter()
        converter.TetrahedraOnlyOn()
    else:
        converter = vtkAppendFilter()
    converter.SetInputData(dataset)
    converter.Update()
    grid = converter.GetOutput()
    hidden = grid.GetCellData().GetArray(_HIDDEN_ARRAY)
    if hidden is not None and hidden.GetRange(0)[1] > 0:
        grid = _threshold(grid, vtkDataObject.FIELD_ASSOCIATION_CELLS, _HIDDEN_ARRAY, 0.0, 0.0)
    result = vtkUnstructuredGrid()
    result.CopyStructure(grid)
    result.GetPointData().ShallowCopy(grid.GetPointData())
    result.GetPointData().SetActiveScalars(array_name)
    return result


def load(name: str, tetrahedralize: bool = True) -> vtkUnstructuredGrid:
    """A real data set by name (case-insensitive; see :data:`DATASETS`, or "default"): an
    unstructured grid whose only point array is its scalar, set active, without PLOT3D's
    blanked cells; split into tetrahedra if ``tetrahedralize``, else of its own cells."""
    key = name.lower()
    if key == "default":
        return make_default_mesh()
    if key not in _READERS:
        known = ", ".join(["default", *sorted(DATASETS)])
        raise KeyError(f"unknown data set {name!r}; known: {known}")
    dataset = _READERS[key]()
    return to_unstructured(dataset, DATASETS[key][1], tetrahedralize)


# The embedded default mesh: a solid tube swept along a helix --------------

# Geometry of the default mesh (model units).
_HELIX_RADIUS = 1.0
_HELIX_PITCH = 1.0       # rise per turn; tube diameter 0.6 leaves a 0.4 gap
_HELIX_TURNS = 2.0
_TUBE_RADIUS = 0.3
_SEGMENTS_ALONG = 150    # per unit resolution
_SEGMENTS_ACROSS = 8     # per unit resolution, each of u and v


def helix_center(theta: np.ndarray) -> np.ndarray:
    """Points of the default mesh's centre line at helix angles ``theta`` (radians,
    0 .. 2*pi*turns), shape (..., 3)."""
    c = _HELIX_PITCH / (2.0 * math.pi)
    z0 = 0.5 * _HELIX_PITCH * _HELIX_TURNS
    theta = np.asarray(theta, dtype=float)
    return np.stack([_HELIX_RADIUS * np.cos(theta),
                     _HELIX_RADIUS * np.sin(theta),
                     c * theta - z0], axis=-1)


def _helix_points(n_along: int, n_across: int) -> np.ndarray:
    """Point coordinates of the tube, shape (n_along, n_across, n_across, 3) in VTK structured
    order (u fastest, then v, then along). The cross-section is the elliptical grid mapping of
    [-1, 1]^2 onto the unit disk, spanned by the helix's normal (towards its axis) and binormal:
    (normal, binormal, tangent) is right-handed, so the grid's cells are positive."""
    theta = np.linspace(0.0, 2.0 * math.pi * _HELIX_TURNS, n_along)
    s = np.linspace(-1.0, 1.0, n_across)
    v, u = np.meshgrid(s, s, indexing="ij")
    x = u * np.sqrt(1.0 - 0.5 * v * v)
    y = v * np.sqrt(1.0 - 0.5 * u * u)
    r, c = _HELIX_RADIUS, _HELIX_PITCH / (2.0 * math.pi)
    cos, sin = np.cos(theta), np.sin(theta)
    normal = np.stack([-cos, -sin, np.zeros_like(theta)], -1)
    binormal = np.stack([c * sin, -c * cos, np.full_like(theta, r)], -1) / math.hypot(r, c)
    offset = (x[None, :, :, None] * normal[:, None, None, :]
              + y[None, :, :, None] * binormal[:, None, None, :])
    return helix_center(theta)[:, None, None, :] + _TUBE_RADIUS * offset


def default_field(points: np.ndarray) -> np.ndarray:
    """Smooth analytic scalar of the default mesh, roughly in 0..1: Gaussian blobs centred on
    the helix centre line plus a gentle sinusoid, a function of position only (so of no mesh
    resolution)."""
    points = np.asarray(points, dtype=float)
    blob_angles = 2.0 * math.pi * _HELIX_TURNS * np.array([0.1, 0.3, 0.5, 0.7, 0.9])
    amplitudes = np.array([1.0, 0.6, 0.9, 0.5, 0.8])
    sigma = 0.22
    field = np.zeros(points.shape[:-1])
    for center, amplitude in zip(helix_center(blob_angles), amplitudes):
        dist2 = np.sum((points - center) ** 2, axis=-1)
        field += amplitude * np.exp(-dist2 / (2.0 * sigma * sigma))
    wave = 0.5 + 0.5 * np.sin(2.0 * points[..., 0] + 3.0 * points[..., 2])
    return 0.75 * field + 0.25 * wave


def make_default_mesh(resolution: int = 1) -> vtkUnstructuredGrid:
    """The project's embedded default data set: a solid tube of radius 0.3 swept along a
    2-turn helix (radius 1, pitch 1), a non-convex tetrahedral mesh that view rays cross
    several times with empty gaps between the turns. Its cross-section is a disk parameterised
    by the elliptical grid mapping of a square, so there is no singular axis. The grid has
    150*r x 8*r x 8*r hexahedra (r = ``resolution``), each split into 5 tetrahedra:
    48,000 * r**3 tets. The point scalar ``"field"`` (active) is :func:`default_field`."""
    if resolution < 1:
        raise ValueError("resolution must be >= 1")
    n_along = _SEGMENTS_ALONG * resolution + 1
    n_across = _SEGMENTS_ACROSS * resolution + 1
    coords = _helix_points(n_along, n_across).reshape(-1, 3)
    points = vtkPoints()
    points.SetData(numpy_to_vtk(coords.astype(np.float32), deep=True))
    structured = vtkStructuredGrid()
    structured.SetDimensions(n_across, n_across, n_along)
    structured.SetPoints(points)
    field = numpy_to_vtk(default_field(coords).astype(np.float32), deep=True)
    field.SetName(DEFAULT_FIELD_NAME)
    structured.GetPointData().AddArray(field)
    return to_unstructured(structured, DEFAULT_FIELD_NAME, tetrahedralize=True)


# Transfer functions -------------------------------------------------------

def property_from_points(grid: vtkDataSet, colors: Sequence[Tuple[float, float, float, float]],
                         opacities: Sequence[Tuple[float, float]],
                         unit_fraction: float) -> vtkVolumeProperty:
    """Volume property from (t, r, g, b) and (t, opacity) control points, t in 0..1 of the
    active scalar range; unit distance is ``unit_fraction`` of the bounding diagonal."""
    scalars = grid.GetPointData().GetScalars()
    if scalars is None:
        raise ValueError("grid has no active point scalars")
    low, high = scalars.GetRange(0)
    if high <= low:  # a constant field: widened
        low, high = low - 0.5, high + 0.5
    color = vtkColorTransferFunction()
    for t, red, green, blue in colors:
        color.AddRGBPoint(low + t * (high - low), red, green, blue)
    opacity = vtkPiecewiseFunction()
    for t, value in opacities:
        opacity.AddPoint(low + t * (high - low), min(max(value, 0.0), 1.0))
    prop = vtkVolumeProperty()
    prop.SetColor(color)
    prop.SetScalarOpacity(opacity)
    diagonal = grid.GetLength()  # of the bounding box; 1 where that is degenerate
    prop.SetScalarOpacityUnitDistance(unit_fraction * (diagonal if diagonal > 0.0 else 1.0))
    prop.ShadeOff()
    prop.SetInterpolationTypeToLinear()
    return prop


def default_transfer_function(grid: vtkDataSet) -> vtkVolumeProperty:
    """A clearly visible, colourful volume property for the default mesh: blue through teal
    and yellow to red, opacity rising to 0.7, unit distance 1/20 of the bounding diagonal."""
    colors = [(0.0, 0.15, 0.35, 0.85), (0.3, 0.10, 0.75, 0.80),
              (0.6, 0.98, 0.85, 0.25), (1.0, 0.95, 0.20, 0.10)]
    opacities = [(0.0, 0.02), (0.15, 0.08), (0.5, 0.3), (1.0, 0.7)]
    return property_from_points(grid, colors, opacities, 1.0 / 20.0)


# Paraview-like "cool to warm" diverging colour map.
_COOL_TO_WARM = [(0.0, 0.230, 0.299, 0.754), (0.5, 0.865, 0.865, 0.865),
                 (1.0, 0.706, 0.016, 0.150)]


def transfer_function(grid: vtkDataSet, preset: str = "default",
                      opacity_scale: float = 1.0,
                      steep_center: float = 0.65) -> vtkVolumeProperty:
    """Cool-to-warm volume property over the active scalar range, unit distance the bounding
    diagonal / 40, opacities clamped to 1. ``"default"``: opacity linear from 0 to
    0.8 * opacity_scale. ``"steep"``: opacity 0 up to 5 % of the range below ``steep_center``
    (a fraction of the range), rising to 0.9 * opacity_scale at it and back to 0 at 5 % above
    it (a thin, sharp feature that stresses pre-integration)."""
    if preset == "default":
        opacities = [(0.0, 0.0), (1.0, 0.8 * opacity_scale)]
    elif preset == "steep":
        if not 0.05 <= steep_center <= 0.95:
            raise ValueError(f"steep_center {steep_center} is outside 0.05..0.95")
        peak = 0.9 * opacity_scale
        opacities = [(0.0, 0.0), (steep_center - 0.05, 0.0), (steep_center, peak),
                     (steep_center + 0.05, 0.0), (1.0, 0.0)]
    else:
        raise ValueError(f"unknown preset {preset!r} (default, steep)")
    return property_from_points(grid, _COOL_TO_WARM, opacities, 1.0 / 40.0)
