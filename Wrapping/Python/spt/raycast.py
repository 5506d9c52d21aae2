"""An exact ray caster of the project's own, in NumPy: the second reference.

One ray through the centre of each pixel, from the near to the far clipping plane, wherever
the camera is (inside the mesh too); each tetrahedron the ray crosses gives one segment
(entry and exit by clipping the ray against the tetrahedron's four face planes, the scalar
from the cell's linear interpolant); each segment is integrated with the optical model of
:class:`vtkPreIntegrationTable` and VTK's ``vtkUnstructuredGridLinearRayIntegrator``
(attenuation ``tau(s) = opacity(s) / unit distance``, emission ``C(s) tau(s)``) by fine
quadrature; the segments of a ray are composited front to back after sorting by depth.
A volume's matrix places the mesh in the world (lengths are measured in the data's own
coordinates, as VTK's mappers measure them), and clipping planes (world coordinates, VTK's
convention: the side that a plane's normal points to is kept) cut each ray to the interval that
all of them keep, so that a segment is cut where the ray crosses a plane.

It is slow (seconds per hundred thousand tetrahedra) but has no approximation beyond the
quadrature, which makes it a check of VTK's ray caster (``Testing/test_raycast.py`` compares the
two on small meshes); :func:`spt.render.reference` can use either.
"""

from __future__ import annotations

from typing import Iterable, Optional, Sequence, Tuple

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import (VTK_TETRA, vtkDataSet, vtkPlane,
                                           vtkPlaneCollection, vtkUnstructuredGrid)
from vtkmodules.vtkCommonMath import vtkMatrix4x4
from vtkmodules.vtkFiltersGeneral import vtkDataSetTriangleFilter
from vtkmodules.vtkRenderingCore import vtkCamera, vtkVolumeProperty

#: Samples of each transfer function over its range (linearly interpolated in between).
TRANSFER_FUNCTION_SAMPLES = 8193
#: Quadrature steps per ray segment (midpoint rule; error falls as 1/steps^2).
SEGMENT_STEPS = 24
#: Ray-tetrahedron pairs handled per batch (bounds the memory to a few hundred megabytes).
PAIRS_PER_BATCH = 1 << 21


class TransferFunction:
    """The first component's color and opacity functions of a property, sampled finely."""

    def __init__(self, prop: vtkVolumeProperty):
        unit_distance = prop.GetScalarOpacityUnitDistance(0)
        if not unit_distance > 0.0:
            raise ValueError(f"ScalarOpacityUnitDistance is {unit_distance}; it must be positive")
        opacity = prop.GetScalarOpacity(0)
        color = prop.GetRGBTransferFunction(0)
        if opacity.GetSize() == 0:
            raise ValueError("the scalar opacity function has no points")
        low, high = opacity.GetRange()
        if color.GetSize() > 0:
            low, high = min(low, color.GetRange()[0]), max(high, color.GetRange()[1])
        if high <= low:
            high = low + 1.0
        n = TRANSFER_FUNCTION_SAMPLES
        self.range = (float(low), float(high))
        alpha = np.empty(n)
        opacity.GetTable(low, high, n, alpha)
        rgb = np.ones(3 * n)  # white where the property has no color function
        if color.GetSize() > 0:
            color.GetTable(low, high, n, rgb)
        self.tau = alpha / unit_distance
        self.rgb = np.ascontiguousarray(rgb.reshape(n, 3))

    def lookup(self, scalars: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
        """Attenuation and color at the given scalars (clamped to the range, as VTK does)."""
        low, high = self.range
        last = len(self.tau) - 1
        x = np.clip((scalars.ravel() - low) * (last / (high - low)), 0.0, last)
        i = np.minimum(x.astype(np.int64), last - 1)
        f = x - i
        g = 1.0 - f

        def interpolate(table: np.ndarray) -> np.ndarray:
            return (table.take(i) * g + table.take(i + 1) * f).reshape(scalars.shape)

        rgb = np.stack([interpolate(self.rgb[:, c]) for c in range(3)], axis=-1)
        return interpolate(self.tau), rgb


def _tetrahedra(grid: vtkDataSet) -> vtkUnstructuredGrid:
    types = vtk_to_numpy(grid.GetDistinctCellTypesArray()) if grid.GetNumberOfCells() else []
    if isinstance(grid, vtkUnstructuredGrid) and all(t == VTK_TETRA for t in types):
        return grid
    split = vtkDataSetTriangleFilter()
    split.SetInputData(grid)
    split.Update()
    return split.GetOutput()


def _scalars(grid: vtkDataSet) -> Tuple[np.ndarray, bool]:
    """The active scalars (magnitude of vectors) and whether they live on the cells."""
    for attributes, on_cells in ((grid.GetPointData(), False), (grid.GetCellData(), True)):
        array = attributes.GetScalars()
        if array is not None:
            values = vtk_to_numpy(array).astype(np.float64)
            if values.ndim > 1:
                values = np.linalg.norm(values, axis=1)
            return values, on_cells
    raise ValueError("the grid has no active point or cell scalars")


class _Mesh:
    """Per-tetrahedron geometry: vertices, outward face planes, scalar gradient."""

    def __init__(self, grid: vtkDataSet):
        tets = _tetrahedra(grid)
        self.points = vtk_to_numpy(tets.GetPoints().GetData()).astype(np.float64)
        cells = vtk_to_numpy(tets.GetCells().GetConnectivityArray()).reshape(-1, 4)
        scalars, on_cells = _scalars(tets)
        v = self.points[cells]                                   # (n, 4, 3)
        edges = v[:, 1:] - v[:, :1]
        det = np.linalg.det(edges)
        scale = np.abs(edges).max(axis=(1, 2)) ** 3 + 1e-300
        keep = np.abs(det) > 1e-12 * scale
        if on_cells:
            keep &= np.isfinite(scalars)
        else:
            keep &= np.isfinite(scalars[cells]).all(axis=1)
        self.cells, v, edges = cells[keep], v[keep], edges[keep]
        self.vertices = v
        faces = np.array([[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]])
        a, b, c = (v[:, faces[:, k]] for k in range(3))            # (n, 4, 3) each
        normals = np.cross(b - a, c - a)
        opposite = v - a                                          # vertex k against face k
        flip = np.einsum("nkj,nkj->nk", normals, opposite) > 0.0
        normals[flip] *= -1.0
        self.normals = normals
        self.offsets = np.einsum("nkj,nkj->nk", normals, a)
        if on_cells:
            self.gradient = np.zeros((len(v), 3))
            self.base = scalars[keep]
        else:
            s = scalars[self.cells]
            self.gradient = np.linalg.solve(edges, (s[:, 1:] - s[:, :1])[..., None])[..., 0]
            self.base = s[:, 0] - np.einsum("nj,nj->n", self.gradient, v[:, 0])


#: The most clipping planes VTK's mappers (and this project's) honour.
MAXIMUM_CLIPPING_PLANES = 6


def _matrix(matrix: Optional[vtkMatrix4x4]) -> np.ndarray:
    """A vtkMatrix4x4 as an array (the identity for None)."""
    if matrix is None:
        return np.eye(4)
    return np.array([[matrix.GetElement(i, j) for j in range(4)] for i in range(4)])


def _data_planes(planes, model: np.ndarray) -> np.ndarray:
    """Clipping planes (vtkPlane, in world coordinates) as rows (n, d) of data coordinates: a
    data point x is kept where n.x + d >= 0."""
    if planes is None:
        return np.zeros((0, 4))
    if isinstance(planes, vtkPlaneCollection):
        planes = [planes.GetItem(i) for i in range(planes.GetNumberOfItems())]
    planes = list(planes)
    if len(planes) > MAXIMUM_CLIPPING_PLANES:
        raise ValueError(f"{len(planes)} clipping planes: at most {MAXIMUM_CLIPPING_PLANES} "
                         "are supported")
    rows = []
    for plane in planes:
        if not isinstance(plane, vtkPlane):
            raise TypeError(f"a clipping plane must be a vtkPlane, not {type(plane).__name__}")
        normal, origin = np.array(plane.GetNormal()), np.array(plane.GetOrigin())
        rows.append(np.r_[normal, -normal @ origin])
    return np.array(rows).reshape(-1, 4) @ model


def _kept_interval(planes: np.ndarray, origin: np.ndarray, direction: np.ndarray
                   ) -> Tuple[np.ndarray, np.ndarray]:
    """Per ray, the parameters between which every plane keeps it (within [0, 1])."""
    low, high = np.zeros(len(origin)), np.ones(len(origin))
    for plane in planes:
        at_origin = origin @ plane[:3] + plane[3]
        slope = direction @ plane[:3]
        with np.errstate(divide="ignore", invalid="ignore"):
            t = -at_origin / slope
        low = np.where(slope > 0.0, np.maximum(low, t), low)
        high = np.where(slope < 0.0, np.minimum(high, t), high)
        high = np.where((slope == 0.0) & (at_origin < 0.0), -1.0, high)
    return low, high


def _camera_rays(camera: vtkCamera, width: int, height: int, model: np.ndarray = np.eye(4)
                 ) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Data-to-NDC matrix (through the volume's matrix ``model``) and, for every pixel
    centre, the ray's near point and direction from the near to the far clipping plane, in
    data coordinates."""
    matrix = camera.GetCompositeProjectionTransformMatrix(width / height, -1.0, 1.0)
    m = _matrix(matrix) @ model
    inverse = np.linalg.inv(m)
    jj, ii = np.meshgrid(np.arange(height), np.arange(width), indexing="ij")
    x = 2.0 * (ii.ravel() + 0.5) / width - 1.0
    y = 2.0 * (jj.ravel() + 0.5) / height - 1.0
    ends = []
    for z in (-1.0, 1.0):
        ndc = np.stack([x, y, np.full_like(x, z), np.ones_like(x)], axis=1)
        world = ndc @ inverse.T
        ends.append(world[:, :3] / world[:, 3:])
    return m, ends[0], ends[1] - ends[0]


def _projected_bounds(homogeneous: np.ndarray) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per tetrahedron (clip coordinates of its vertices), the screen bounds (NDC x and y,
    min and max) of its part beyond the near plane, and whether it has one: its vertices
    there, and where its edges cross the plane (clip z = -w, where w > 0)."""
    beyond_near = homogeneous[..., 2] + homogeneous[..., 3]      # >= 0: on the visible side
    points = [homogeneous[:, i] for i in range(4)]
    valid = [beyond_near[:, i] >= 0.0 for i in range(4)]
    for i, j in ((0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)):
        a, b = beyond_near[:, i], beyond_near[:, j]
        crosses = (a >= 0.0) != (b >= 0.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            t = np.where(crosses, a / (a - b), 0.0)
        points.append(homogeneous[:, i] + t[:, None] * (homogeneous[:, j] - homogeneous[:, i]))
        valid.append(crosses)
    points, valid = np.stack(points, axis=1), np.stack(valid, axis=1)
    w = np.where(valid, points[..., 3], 1.0)
    ndc = points[..., :2] / np.where(w > 0.0, w, 1.0)[..., None]
    low = np.where(valid[..., None], ndc, np.inf).min(axis=1)
    high = np.where(valid[..., None], ndc, -np.inf).max(axis=1)
    return low, high, valid.any(axis=1)


def _pairs(mesh: _Mesh, m: np.ndarray, width: int, height: int):
    """Batches of (tetrahedron, pixel) pairs: the pixel centres in the projected bounding box
    of each tetrahedron's part beyond the near plane (rays start there, wherever the camera
    is)."""
    n = len(mesh.vertices)
    homogeneous = np.concatenate([mesh.vertices, np.ones((n, 4, 1))], axis=2) @ m.T
    low, high, visible = _projected_bounds(homogeneous)
    px = (np.stack([low[:, 0], high[:, 0]], axis=1) + 1.0) * 0.5 * width - 0.5
    py = (np.stack([low[:, 1], high[:, 1]], axis=1) + 1.0) * 0.5 * height - 0.5
    with np.errstate(invalid="ignore"):
        i0 = np.clip(np.ceil(px[:, 0]), 0, width)
        i1 = np.clip(np.floor(px[:, 1]), -1, width - 1)
        j0 = np.clip(np.ceil(py[:, 0]), 0, height)
        j1 = np.clip(np.floor(py[:, 1]), -1, height - 1)
    i0, i1, j0, j1 = (np.where(visible, v, 0).astype(np.int64) for v in (i0, i1, j0, j1))
    nx = np.where(visible, np.maximum(i1 - i0 + 1, 0), 0)
    ny = np.where(visible, np.maximum(j1 - j0 + 1, 0), 0)
    counts = nx * ny
    cumulative = np.cumsum(counts)
    start = 0
    while start < n:
        base = cumulative[start - 1] if start else 0
        stop = int(np.searchsorted(cumulative, base + PAIRS_PER_BATCH, side="right"))
        stop = max(stop, start + 1)
        tet = np.repeat(np.arange(start, stop), counts[start:stop])
        first = cumulative[start:stop] - counts[start:stop] - base
        local = np.arange(len(tet)) - np.repeat(first, counts[start:stop])
        ix = i0[tet] + local % np.maximum(nx[tet], 1)
        iy = j0[tet] + local // np.maximum(nx[tet], 1)
        yield tet, iy * width + ix
        start = stop


def _segments(mesh: _Mesh, tet: np.ndarray, pixel: np.ndarray, origin: np.ndarray,
              direction: np.ndarray, kept: Tuple[np.ndarray, np.ndarray]):
    """Entry parameter, length and front and back scalars of each ray-tetrahedron pair that
    intersects within the part of the ray that ``kept`` (per pixel) gives."""
    o, d = origin[pixel], direction[pixel]
    normals, offsets = mesh.normals[tet], mesh.offsets[tet]
    nd = np.einsum("nkj,nj->nk", normals, d)
    distance = offsets - np.einsum("nkj,nj->nk", normals, o)     # n.o + t n.d <= h
    with np.errstate(divide="ignore", invalid="ignore"):
        t = distance / nd
    enter = np.where(nd < 0.0, t, -np.inf).max(axis=1)
    leave = np.where(nd > 0.0, t, np.inf).min(axis=1)
    parallel_outside = ((nd == 0.0) & (distance < 0.0)).any(axis=1)
    enter, leave = np.maximum(enter, kept[0][pixel]), np.minimum(leave, kept[1][pixel])
    hit = (leave > enter) & ~parallel_outside
    tet, pixel, enter, leave, o, d = tet[hit], pixel[hit], enter[hit], leave[hit], o[hit], d[hit]
    g, c = mesh.gradient[tet], mesh.base[tet]
    front = c + np.einsum("nj,nj->n", g, o + enter[:, None] * d)
    back = c + np.einsum("nj,nj->n", g, o + leave[:, None] * d)
    length = (leave - enter) * np.linalg.norm(d, axis=1)
    return pixel, enter, length, front, back


def _integrate(tf: TransferFunction, length: np.ndarray, front: np.ndarray, back: np.ndarray
               ) -> Tuple[np.ndarray, np.ndarray]:
    """Optical depth and premultiplied color of linear segments (midpoint quadrature)."""
    steps = SEGMENT_STEPS
    u = (np.arange(steps) + 0.5) / steps
    scalars = front[:, None] + (back - front)[:, None] * u
    tau, rgb = tf.lookup(scalars)
    depth = tau * (length / steps)[:, None]                          # (n, steps)
    before = np.cumsum(depth, axis=1) - depth
    weight = np.exp(-before) * -np.expm1(-depth)
    color = np.einsum("ns,nsc->nc", weight, rgb)
    return depth.sum(axis=1), color


def _composite(pixel: np.ndarray, enter: np.ndarray, depth: np.ndarray, color: np.ndarray,
               count: int) -> np.ndarray:
    """Front-to-back compositing of each pixel's segments, sorted by entry."""
    order = np.lexsort((enter, pixel))
    pixel, depth, color = pixel[order], depth[order], color[order]
    total = np.cumsum(depth)
    first = np.r_[True, pixel[1:] != pixel[:-1]]
    group_start = np.maximum.accumulate(np.where(first, np.arange(len(pixel)), 0))
    before = total - depth - (total[group_start] - depth[group_start])
    rgba = np.zeros((count, 4))
    np.add.at(rgba[:, :3], pixel, color * np.exp(-before)[:, None])
    optical = np.zeros(count)
    np.add.at(optical, pixel, depth)
    rgba[:, 3] = -np.expm1(-optical)
    return rgba


def render(grid: vtkDataSet, prop: vtkVolumeProperty, camera: vtkCamera,
           size: Tuple[int, int], matrix: Optional[vtkMatrix4x4] = None,
           clipping_planes: Optional[Iterable[vtkPlane]] = None) -> np.ndarray:
    """The exact image of ``grid`` seen by ``camera`` at ``size`` (width, height): float
    premultiplied RGBA, row 0 at the top, as :func:`spt.render.read_rgba` returns it.
    ``matrix`` is the volume's (vtkVolume.GetMatrix(), data to world), ``clipping_planes``
    the mapper's (vtkPlane objects or a vtkPlaneCollection, world coordinates, at most six)."""
    return render_volumes([(grid, prop, matrix, clipping_planes)], camera, size)


def render_volumes(volumes: Sequence[tuple], camera: vtkCamera,
                   size: Tuple[int, int]) -> np.ndarray:
    """The exact image of several volumes, each a grid with a property of its own, and
    optionally its matrix and clipping planes (as :func:`render` takes them), in one space:
    every ray's segments of all of them composited front to back, wherever they
    interpenetrate. A ray's parameter is the same in every volume's data coordinates, so the
    segments sort across volumes."""
    width, height = size
    parts = []
    for grid, prop, *placement in volumes:
        matrix, planes = (list(placement) + [None, None])[:2]
        tf = TransferFunction(prop)
        mesh = _Mesh(grid)
        model = _matrix(matrix)
        m, origin, direction = _camera_rays(camera, width, height, model)
        kept = _kept_interval(_data_planes(planes, model), origin, direction)
        for tet, pixel in _pairs(mesh, m, width, height):
            pixel, enter, length, front, back = _segments(mesh, tet, pixel, origin, direction,
                                                          kept)
            depth, color = _integrate(tf, length, front, back)
            parts.append((pixel, enter, depth, color))
    if not parts:
        return np.zeros((height, width, 4))
    pixel, enter, depth, color = (np.concatenate(p) for p in zip(*parts))
    rgba = _composite(pixel, enter, depth, color, width * height)
    return np.ascontiguousarray(rgba.reshape(height, width, 4)[::-1])
