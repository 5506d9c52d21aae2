"""Measure a compute traversal of the cells against drawing them as points.

SPT's traversals of a large mesh on llvmpipe are bound by rasterizing one point per small cell
(Documentation/design.md, "The small cells in a compute pass"; the mapper's own compute pass
is vtkSPTVolumeMapper's ComputeTraversal). This experiment does the same work per (cell,
sample) both ways, in one OpenGL context, on a race scene:

- *points*: one GL_POINTS primitive per cell, drawn by the mapper's own vertex stage
  (vtkSPTTetrahedraPointsVS.glsl); the fragment stage finds the segment, looks up its color,
  keeps it or not by a hashed threshold and takes the atomic minimum of its depth key; its
  optical depth terms (the exact coverage) are added by blending into a float target;
- *compute*: one invocation per cell visits the samples of the cell's bounding box and does the
  same; the coverage terms are added as 20.12 fixed-point integers by atomic additions (in an
  r32i image, or in a shader storage buffer), which give the same sums in any order.

It then does the color traversal's work both ways after those keys: the color of every segment
that is not in front of the survivor, summed. It checks that both ways give the same keys, bit
for bit, and the same sums to the fixed point's rounding (it fails otherwise), and prints the
best of four timings of each, with SPT's and VTK PT's frames of the scene in the same window
for scale. The cells' face planes, the sample's segment and the hash are the mapper's own GLSL
functions, read from Rendering/SPT/shaders and Rendering/Core/shaders; the work per sample is
simplified (one repetition, a made-up pre-integration table, every cell drawn as a point, no
strata): what it keeps is each traversal's work per (cell, sample). The GLSL is assembled in
compute_traversal_shaders.py, and gl_context.py calls OpenGL.

    SPT_DATA_DIR=... xvfb-run -a python3 Documentation/experiments/compute_traversal.py drill-1M 256

It needs the installed `spt` package, this source tree (for the shaders) and a GLX or EGL window
(:func:`spt.render.make_window`).
"""

import dataclasses
import sys
import time
from ctypes import POINTER, c_float
from typing import Callable, Dict, Tuple

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkRenderingVolumeOpenGL2 import vtkOpenGLProjectedTetrahedraMapper

from spt import render
from spt.experiments.bench import race
from spt.scenes import Scene

from compute_traversal_shaders import (
    COMPUTE, POINTS_FS, points_vertex_source, sample_stage_source)
from gl_context import (
    ALL_BARRIER_BITS, BLEND, CLAMP_TO_EDGE, COLOR_ATTACHMENT0, COMPUTE_SHADER, DEPTH_TEST, FLOAT,
    FRAGMENT_SHADER, FRAMEBUFFER, FRAMEBUFFER_COMPLETE, FUNC_ADD, GL, INT, LINEAR, MAG_FILTER,
    MIN_FILTER, NEAREST, PACK_ALIGNMENT, POINTS, PROGRAM_POINT_SIZE, R32F, R32I, R32I_FORMAT,
    R32UI, READ_WRITE, RGB32F, RGBA, RGBA32F, RGBA32UI, SCISSOR_TEST, SHADER_STORAGE_BUFFER,
    STATIC_DRAW, TEXTURE0, TEXTURE_2D, TEXTURE_2D_ARRAY, TEXTURE_3D, TEXTURE_BUFFER, UNSIGNED_INT,
    VERTEX_SHADER, WRAP_R, WRAP_S, WRAP_T)

# The coverage sums' fixed point: 12 bits of integer part (optical depths up to 2048) and 20
# bits of fraction (1e-6, far below the 8 bits of the image).
FIXED_POINT_ONE = 1 << 20
# The texture units of the pre-integration table and of the mesh's buffer textures.
TABLE_UNIT, TETRAHEDRA_UNIT, POINTS_UNIT, SCALARS_UNIT = 0, 1, 2, 3
# The image units of the keys and of the coverage sums, and the sums buffer's binding.
KEYS_IMAGE, COVERAGE_IMAGE, SUMS_BINDING = 0, 1, 3


def build_programs(gl: GL) -> Dict[str, int]:
    """The programs of both traversals, by name."""
    vertex = points_vertex_source()
    fixed_one = f"FIXED_POINT_ONE {FIXED_POINT_ONE}.0"

    def compute(*defines: str) -> int:
        return gl.program((COMPUTE_SHADER, sample_stage_source(COMPUTE, fixed_one, *defines)))

    return {
        "points": gl.program((VERTEX_SHADER, vertex),
                             (FRAGMENT_SHADER, sample_stage_source(POINTS_FS))),
        "points, colors": gl.program((VERTEX_SHADER, vertex),
                                     (FRAGMENT_SHADER, sample_stage_source(POINTS_FS, "COLORS"))),
        "compute, colors": compute("COLORS", "COVERAGE_BUFFER"),
        "compute": compute(),
        "compute, sums in an image": compute("COVERAGE_IMAGE"),
        "compute, sums in a buffer": compute("COVERAGE_BUFFER"),
    }


@dataclasses.dataclass
class Mesh:
    """A scene's tetrahedra as the traversals read them."""

    cells: int
    points: np.ndarray      # float32, x y z per point
    tetrahedra: np.ndarray  # uint32, four point ids per cell
    scalars: np.ndarray     # float32 in [0, 1], per point
    diagonal: float         # of the bounds


def mesh_of(scene: Scene) -> Mesh:
    grid = scene.grid
    cells = grid.GetNumberOfCells()
    tetrahedra = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).astype(np.uint32)
    if tetrahedra.size != 4 * cells:
        raise ValueError(f"{scene.name} is not made of tetrahedra only")
    values = vtk_to_numpy(grid.GetPointData().GetScalars()).astype(np.float64)
    if values.ndim > 1:
        values = np.linalg.norm(values, axis=1)
    scalars = ((values - values.min()) / np.ptp(values)).astype(np.float32)
    bounds = np.array(grid.GetBounds())
    points = vtk_to_numpy(grid.GetPoints().GetData()).astype(np.float32)
    return Mesh(cells, np.ascontiguousarray(points), np.ascontiguousarray(tetrahedra), scalars,
                float(np.linalg.norm(bounds[1::2] - bounds[0::2])))


def matrix(vtk_matrix) -> np.ndarray:
    return np.array([[vtk_matrix.GetElement(i, j) for j in range(4)] for i in range(4)])


def camera_matrices(renderer) -> Dict[str, np.ndarray]:
    """The uniforms of the camera of ``renderer``."""
    camera = renderer.GetActiveCamera()
    projection = matrix(camera.GetProjectionTransformMatrix(1.0, -1.0, 1.0))
    return {"MCVCMatrix": matrix(camera.GetModelViewTransformMatrix()),
            "VCDCMatrix": projection, "DCVCMatrix": np.linalg.inv(projection)}


def pre_integration_table(front: int = 64, thickness: int = 32) -> np.ndarray:
    """A smooth made-up table: premultiplied RGBA by (thickness, back, front) scalar."""
    f = np.linspace(0.0, 1.0, front)[None, None, :]
    b = np.linspace(0.0, 1.0, front)[None, :, None]
    t = np.linspace(0.0, 1.0, thickness)[:, None, None]
    mean = 0.5 * (f + b)
    alpha = 1.0 - np.exp(-4.0 * t * t * (0.05 + np.exp(-(((mean - 0.6) / 0.15) ** 2))))
    rgba = np.stack([mean * alpha, (1.0 - mean) * alpha, 0.5 * alpha, alpha], axis=-1)
    return np.ascontiguousarray(rgba, dtype=np.float32)


class Traversals:
    """Both traversals in the current context: their programs, the mesh's buffers, the keys,
    the coverage and color sums (a float target, an r32i image array, a storage buffer)."""

    def __init__(self, gl: GL, mesh: Mesh, matrices: Dict[str, np.ndarray], size: int):
        self.gl, self.mesh, self.matrices, self.size = gl, mesh, matrices, size
        self.programs = build_programs(gl)
        self._buffer_texture(mesh.tetrahedra, RGBA32UI, TETRAHEDRA_UNIT)
        self._buffer_texture(mesh.points, RGB32F, POINTS_UNIT)
        self._buffer_texture(mesh.scalars, R32F, SCALARS_UNIT)
        self.sums_buffer = self._storage(np.zeros(4 * size * size, np.int32), SUMS_BINDING)
        self._make_targets()

    def _buffer_texture(self, data: np.ndarray, internal_format: int, unit: int) -> None:
        gl = self.gl
        buffer = gl.name(gl.GenBuffers)
        gl.BindBuffer(TEXTURE_BUFFER, buffer)
        gl.BufferData(TEXTURE_BUFFER, data.nbytes, data.ctypes.data, STATIC_DRAW)
        gl.ActiveTexture(TEXTURE0 + unit)
        gl.BindTexture(TEXTURE_BUFFER, gl.name(gl.GenTextures))
        gl.TexBuffer(TEXTURE_BUFFER, internal_format, buffer)

    def _storage(self, data: np.ndarray, binding: int) -> int:
        gl = self.gl
        buffer = gl.name(gl.GenBuffers)
        gl.BindBuffer(SHADER_STORAGE_BUFFER, buffer)
        gl.BufferData(SHADER_STORAGE_BUFFER, data.nbytes, data.ctypes.data, STATIC_DRAW)
        gl.BindBufferBase(SHADER_STORAGE_BUFFER, binding, buffer)
        return buffer

    def _texture(self, target: int, filtering: int) -> int:
        name = self.gl.name(self.gl.GenTextures)
        self.gl.BindTexture(target, name)
        for parameter in (MIN_FILTER, MAG_FILTER):
            self.gl.TexParameteri(target, parameter, filtering)
        return name

    def _make_targets(self) -> None:
        gl, size = self.gl, self.size
        table = pre_integration_table()
        gl.ActiveTexture(TEXTURE0 + TABLE_UNIT)
        table_texture = self._texture(TEXTURE_3D, LINEAR)
        gl.TexImage3D(TEXTURE_3D, 0, RGBA32F, table.shape[2], table.shape[1], table.shape[0], 0,
                      RGBA, FLOAT, table.ctypes.data)
        for wrap in (WRAP_S, WRAP_T, WRAP_R):
            gl.TexParameteri(TEXTURE_3D, wrap, CLAMP_TO_EDGE)
        self.keys = self._texture(TEXTURE_2D, NEAREST)
        gl.TexImage2D(TEXTURE_2D, 0, R32UI, size, size, 0, R32I_FORMAT, UNSIGNED_INT, None)
        self.coverage_image = self._texture(TEXTURE_2D_ARRAY, NEAREST)
        gl.TexImage3D(TEXTURE_2D_ARRAY, 0, R32I, size, size, 4, 0, R32I_FORMAT, INT, None)
        self.coverage_target = self._texture(TEXTURE_2D, NEAREST)
        gl.TexImage2D(TEXTURE_2D, 0, RGBA32F, size, size, 0, RGBA, FLOAT, None)
        self.framebuffer = gl.name(gl.GenFramebuffers)
        gl.BindFramebuffer(FRAMEBUFFER, self.framebuffer)
        gl.FramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, self.coverage_target,
                                0)
        if gl.CheckFramebufferStatus(FRAMEBUFFER) != FRAMEBUFFER_COMPLETE:
            raise RuntimeError("the coverage target is not complete")
        gl.BindVertexArray(gl.name(gl.GenVertexArrays))
        gl.BindTexture(TEXTURE_3D, table_texture)
        gl.BindImageTexture(KEYS_IMAGE, self.keys, 0, 0, 0, READ_WRITE, R32UI)
        gl.BindImageTexture(COVERAGE_IMAGE, self.coverage_image, 0, 1, 0, READ_WRITE, R32I)

    def use(self, program: int) -> None:
        gl = self.gl
        gl.UseProgram(program)
        for uniform, value in self.matrices.items():
            transposed = np.ascontiguousarray(value.T, dtype=np.float32)
            gl.UniformMatrix4fv(gl.GetUniformLocation(program, uniform.encode()), 1, 0,
                                transposed.ctypes.data_as(POINTER(c_float)))
        gl.Uniform2f(gl.GetUniformLocation(program, b"passSizeInPixels"), float(self.size),
                     float(self.size))
        gl.Uniform1f(gl.GetUniformLocation(program, b"thicknessToTable"),
                     1.0 / (0.02 * self.mesh.diagonal))
        for uniform, value in ((b"table", TABLE_UNIT), (b"tetrahedra", TETRAHEDRA_UNIT),
                               (b"points", POINTS_UNIT), (b"scalars", SCALARS_UNIT),
                               (b"seed", 7), (b"keys", KEYS_IMAGE),
                               (b"coverage", COVERAGE_IMAGE)):
            gl.Uniform1i(gl.GetUniformLocation(program, uniform), value)
        gl.Uniform1ui(gl.GetUniformLocation(program, b"cellCount"), self.mesh.cells)

    def clear(self) -> None:
        gl = self.gl
        nothing_kept = np.array([0xFFFFFFFF], np.uint32)
        zeros = np.zeros(4, np.int32)
        gl.ClearTexImage(self.keys, 0, R32I_FORMAT, UNSIGNED_INT, nothing_kept.ctypes.data)
        gl.ClearTexImage(self.coverage_image, 0, R32I_FORMAT, INT, zeros.ctypes.data)
        gl.ClearTexImage(self.coverage_target, 0, RGBA, FLOAT, zeros.ctypes.data)
        gl.BindBuffer(SHADER_STORAGE_BUFFER, self.sums_buffer)
        gl.ClearBufferData(SHADER_STORAGE_BUFFER, R32I, R32I_FORMAT, INT, zeros.ctypes.data)
        gl.Finish()

    def draw_points(self, coverage: bool, program: str = "points") -> None:
        gl = self.gl
        self.use(self.programs[program])
        gl.BindFramebuffer(FRAMEBUFFER, self.framebuffer)
        gl.Viewport(0, 0, self.size, self.size)
        gl.Disable(DEPTH_TEST)
        gl.Disable(SCISSOR_TEST)
        gl.Enable(PROGRAM_POINT_SIZE)
        gl.Enable(BLEND)
        gl.BlendFunc(1, 1)
        gl.BlendEquation(FUNC_ADD)
        gl.ColorMask(*([int(coverage)] * 4))
        gl.DrawArrays(POINTS, 0, self.mesh.cells)

    def dispatch(self, variant: str) -> None:
        self.use(self.programs[variant])
        self.gl.DispatchCompute((self.mesh.cells + 63) // 64, 1, 1)
        self.gl.MemoryBarrier(ALL_BARRIER_BITS)

    def keys_then(self, run: Callable[[], None]) -> None:
        """The keys traversal (points), then ``run``: the colors traversal reads its keys."""
        self.clear()
        self.draw_points(False)
        self.gl.Finish()
        run()

    def read_texture(self, name: int, target: int, shape, dtype, data_format: int,
                     data_type: int) -> np.ndarray:
        out = np.empty(shape, dtype)
        self.gl.BindTexture(target, name)
        self.gl.PixelStorei(PACK_ALIGNMENT, 1)
        self.gl.GetTexImage(target, 0, data_format, data_type, out.ctypes.data)
        return out

    def read_keys(self) -> np.ndarray:
        return self.read_texture(self.keys, TEXTURE_2D, (self.size, self.size), np.uint32,
                                 R32I_FORMAT, UNSIGNED_INT)

    def read_target(self) -> np.ndarray:
        return self.read_texture(self.coverage_target, TEXTURE_2D, (self.size, self.size, 4),
                                 np.float32, RGBA, FLOAT)

    def read_coverage_image(self) -> np.ndarray:
        sums = self.read_texture(self.coverage_image, TEXTURE_2D_ARRAY, (4, self.size, self.size),
                                 np.int32, R32I_FORMAT, INT)
        return np.moveaxis(sums, 0, -1) / FIXED_POINT_ONE

    def read_sums_buffer(self) -> np.ndarray:
        sums = np.empty(4 * self.size * self.size, np.int32)
        self.gl.BindBuffer(SHADER_STORAGE_BUFFER, self.sums_buffer)
        self.gl.GetBufferSubData(SHADER_STORAGE_BUFFER, 0, sums.nbytes, sums.ctypes.data)
        return sums.reshape(self.size, self.size, 4) / FIXED_POINT_ONE


def keys_runs(traversals: Traversals) -> Dict[str, Callable[[], None]]:
    """The keys traversal's runs, each after a clear."""
    return {
        "points, keys and coverage": lambda: traversals.draw_points(True),
        "compute, keys and coverage (image)":
            lambda: traversals.dispatch("compute, sums in an image"),
        "compute, keys and coverage (buffer)":
            lambda: traversals.dispatch("compute, sums in a buffer"),
        "points, keys only": lambda: traversals.draw_points(False),
        "compute, keys only": lambda: traversals.dispatch("compute"),
    }


def colors_runs(traversals: Traversals) -> Dict[str, Callable[[], None]]:
    """The colors traversal's runs, each after the keys that the keys traversal left."""
    return {
        "points, colors": lambda: traversals.draw_points(True, "points, colors"),
        "compute, colors (buffer)": lambda: traversals.dispatch("compute, colors"),
    }


def best_times(traversals: Traversals, repeats: int = 4) -> Dict[str, float]:
    """The best of ``repeats`` timings of every run, in seconds."""
    keys, colors = keys_runs(traversals), colors_runs(traversals)
    best = {label: float("inf") for label in list(keys) + list(colors)}
    for _ in range(repeats):
        for label, run in list(keys.items()) + list(colors.items()):
            if label in colors:
                traversals.keys_then(lambda: None)
            else:
                traversals.clear()
            start = time.perf_counter()
            run()
            traversals.gl.Finish()
            best[label] = min(best[label], time.perf_counter() - start)
    return best


def sums_both_ways(traversals: Traversals) -> Dict[str, Tuple[np.ndarray, np.ndarray]]:
    """The keys, the coverage sums and the color sums, (points, compute) each."""
    keys, colors = keys_runs(traversals), colors_runs(traversals)
    traversals.clear()
    keys["points, keys and coverage"]()
    traversals.gl.Finish()
    keys_points, coverage_points = traversals.read_keys(), traversals.read_target()
    traversals.clear()
    keys["compute, keys and coverage (image)"]()
    traversals.gl.Finish()
    keys_compute, coverage_compute = traversals.read_keys(), traversals.read_coverage_image()
    traversals.keys_then(colors["points, colors"])
    traversals.gl.Finish()
    colors_points = traversals.read_target()
    traversals.keys_then(colors["compute, colors (buffer)"])
    traversals.gl.Finish()
    colors_compute = traversals.read_sums_buffer()
    return {"keys": (keys_points, keys_compute), "coverage": (coverage_points, coverage_compute),
            "colors": (colors_points, colors_compute)}


def reference_frames(scene: Scene, window, size: int) -> Dict[str, float]:
    """SPT's and VTK PT's frame times of the scene in ``window``, for scale."""
    frames = {}
    for label, mapper in (("SPT L=1", render.spt_mapper(1)),
                          ("VTK PT", vtkOpenGLProjectedTetrahedraMapper())):
        frames[label] = render.render(scene.grid, scene.property, mapper, scene.view,
                                      (size, size), window=window, frames=2).seconds
    return frames


def largest_difference(pair: Tuple[np.ndarray, np.ndarray]) -> float:
    return float(np.abs(pair[0] - pair[1]).max())


def report(name: str, size: int, cells: int, frames: Dict[str, float],
           sums: Dict[str, Tuple[np.ndarray, np.ndarray]], best: Dict[str, float]) -> None:
    keys_points, keys_compute = sums["keys"]
    print(f"{name}: {cells:,} cells, {size} x {size}; SPT at L = 1 {frames['SPT L=1']:.3f} s, "
          f"VTK PT {frames['VTK PT']:.3f} s")
    print(f"samples with a key: {int((keys_points != 0xFFFFFFFF).sum())}; keys that differ: "
          f"{int((keys_points != keys_compute).sum())}; largest coverage "
          f"{float(sums['coverage'][0].max()):.3g}, largest difference "
          f"{largest_difference(sums['coverage']):.2g}")
    print(f"colors: largest sum {float(sums['colors'][0].max()):.3g}, largest difference "
          f"{largest_difference(sums['colors']):.2g}")
    for label, seconds in best.items():
        print(f"{label}: {seconds:.4f} s")
    print("compute / points: keys and coverage %.2f (image), %.2f (buffer); keys only %.2f" % (
        best["compute, keys and coverage (image)"] / best["points, keys and coverage"],
        best["compute, keys and coverage (buffer)"] / best["points, keys and coverage"],
        best["compute, keys only"] / best["points, keys only"]))
    print("compute / points: colors %.2f" % (
        best["compute, colors (buffer)"] / best["points, colors"]))


def check(sums: Dict[str, Tuple[np.ndarray, np.ndarray]]) -> None:
    """Both ways must do the same work: the same keys, and sums that differ by the fixed
    point's rounding (2^-21 per term) and the float blending's, far below 1e-4 here."""
    keys_points, keys_compute = sums["keys"]
    if (keys_points != keys_compute).any():
        raise SystemExit("the compute pass left other keys than the points")
    for what in ("coverage", "colors"):
        difference = largest_difference(sums[what])
        if not difference < 1e-4:
            raise SystemExit(
                f"the compute pass's {what} sums differ from the points' by {difference}")


def main(name: str, size: int) -> None:
    scene = race.race_scene(name)
    window, renderer = render.make_window(size, size)
    frames = reference_frames(scene, window, size)
    mesh = mesh_of(scene)
    window.MakeCurrent()
    gl = GL(egl="EGL" in window.GetClassName())
    traversals = Traversals(gl, mesh, camera_matrices(renderer), size)
    best = best_times(traversals)
    sums = sums_both_ways(traversals)
    report(name, size, mesh.cells, frames, sums, best)
    check(sums)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "drill-1M",
         int(sys.argv[2]) if len(sys.argv) > 2 else 256)
