"""Measure a compute traversal of the cells against drawing them as points.

SPT's traversals of a large mesh on llvmpipe are bound by rasterizing one point per small cell
(Documentation/results.md, "A compute traversal of the small cells"; the mapper's own compute
pass is vtkSPTVolumeMapper's ComputeTraversal). This experiment does the same work per (cell,
sample) both ways, in one OpenGL context, on a race scene, with shaders of its own:

- *points*: one GL_POINTS primitive per cell, as vtkSPTTetrahedraPointsVS.glsl draws it; the
  fragment stage finds the segment, looks up its color, keeps it or not by a hashed threshold
  and takes the atomic minimum of its depth key; its optical depth terms (the exact coverage)
  are added by blending into a float target;
- *compute*: one invocation per cell visits the samples of the cell's bounding box and does the
  same; the coverage terms are added as 20.12 fixed-point integers by atomic additions (in an
  r32i image, or in a shader storage buffer), which give the same sums in any order.

It then does the color traversal's work both ways after those keys: the color of every segment
that is not in front of the survivor, summed. It checks that both ways give the same keys, bit
for bit, and the same sums to the fixed point's rounding (it fails otherwise), and prints the
best of four timings of each, with SPT's and VTK PT's frames of the scene in the same window
for scale. The shaders are simplified (one repetition, a made-up pre-integration table, every
cell drawn as a point, no strata); what they keep is each traversal's work per (cell, sample).

    SPT_DATA_DIR=... xvfb-run -a python3 Documentation/experiments/compute_traversal.py drill-1M 256

It needs the installed `spt` package and a GLX or EGL window (:func:`spt.render.make_window`).
"""

import ctypes
import sys
import time
from ctypes import POINTER, c_char_p, c_float, c_int, c_ssize_t, c_ubyte, c_uint, c_void_p

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkRenderingVolumeOpenGL2 import vtkOpenGLProjectedTetrahedraMapper

from spt import render
from spt.experiments.bench import race

# GL entry points: name -> (result, arguments).
_SIGNATURES = {
    "glCreateShader": (c_uint, [c_uint]),
    "glShaderSource": (None, [c_uint, c_int, POINTER(c_char_p), c_void_p]),
    "glCompileShader": (None, [c_uint]),
    "glGetShaderiv": (None, [c_uint, c_uint, POINTER(c_int)]),
    "glGetShaderInfoLog": (None, [c_uint, c_int, c_void_p, c_char_p]),
    "glCreateProgram": (c_uint, []),
    "glAttachShader": (None, [c_uint, c_uint]),
    "glLinkProgram": (None, [c_uint]),
    "glGetProgramiv": (None, [c_uint, c_uint, POINTER(c_int)]),
    "glGetProgramInfoLog": (None, [c_uint, c_int, c_void_p, c_char_p]),
    "glUseProgram": (None, [c_uint]),
    "glGetUniformLocation": (c_int, [c_uint, c_char_p]),
    "glUniformMatrix4fv": (None, [c_int, c_int, c_ubyte, POINTER(c_float)]),
    "glUniform2f": (None, [c_int, c_float, c_float]),
    "glUniform1i": (None, [c_int, c_int]),
    "glUniform1ui": (None, [c_int, c_uint]),
    "glUniform1f": (None, [c_int, c_float]),
    "glGenBuffers": (None, [c_int, POINTER(c_uint)]),
    "glBindBuffer": (None, [c_uint, c_uint]),
    "glBufferData": (None, [c_uint, c_ssize_t, c_void_p, c_uint]),
    "glBindBufferBase": (None, [c_uint, c_uint, c_uint]),
    "glGenTextures": (None, [c_int, POINTER(c_uint)]),
    "glBindTexture": (None, [c_uint, c_uint]),
    "glActiveTexture": (None, [c_uint]),
    "glTexImage2D": (None, [c_uint, c_int, c_int, c_int, c_int, c_int, c_uint, c_uint, c_void_p]),
    "glTexImage3D": (None, [c_uint, c_int, c_int, c_int, c_int, c_int, c_int, c_uint, c_uint,
                            c_void_p]),
    "glTexParameteri": (None, [c_uint, c_uint, c_int]),
    "glBindImageTexture": (None, [c_uint, c_uint, c_int, c_ubyte, c_int, c_uint, c_uint]),
    "glClearTexImage": (None, [c_uint, c_int, c_uint, c_uint, c_void_p]),
    "glClearBufferData": (None, [c_uint, c_uint, c_uint, c_uint, c_void_p]),
    "glGenFramebuffers": (None, [c_int, POINTER(c_uint)]),
    "glBindFramebuffer": (None, [c_uint, c_uint]),
    "glFramebufferTexture2D": (None, [c_uint, c_uint, c_uint, c_uint, c_int]),
    "glCheckFramebufferStatus": (c_uint, [c_uint]),
    "glViewport": (None, [c_int, c_int, c_int, c_int]),
    "glEnable": (None, [c_uint]),
    "glDisable": (None, [c_uint]),
    "glBlendFunc": (None, [c_uint, c_uint]),
    "glBlendEquation": (None, [c_uint]),
    "glColorMask": (None, [c_ubyte] * 4),
    "glGenVertexArrays": (None, [c_int, POINTER(c_uint)]),
    "glBindVertexArray": (None, [c_uint]),
    "glDrawArrays": (None, [c_uint, c_int, c_int]),
    "glDispatchCompute": (None, [c_uint, c_uint, c_uint]),
    "glMemoryBarrier": (None, [c_uint]),
    "glFinish": (None, []),
    "glGetTexImage": (None, [c_uint, c_int, c_uint, c_uint, c_void_p]),
    "glGetBufferSubData": (None, [c_uint, c_ssize_t, c_ssize_t, c_void_p]),
    "glPixelStorei": (None, [c_uint, c_int]),
}

# The GL enumerants used here.
VERTEX_SHADER, FRAGMENT_SHADER, COMPUTE_SHADER = 0x8B31, 0x8B30, 0x91B9
COMPILE_STATUS, LINK_STATUS = 0x8B81, 0x8B82
SHADER_STORAGE_BUFFER, STATIC_DRAW = 0x90D2, 0x88E4
TEXTURE_2D, TEXTURE_3D, TEXTURE_2D_ARRAY, TEXTURE0 = 0x0DE1, 0x806F, 0x8C1A, 0x84C0
R32UI, R32I, R32I_FORMAT, RGBA32F = 0x8236, 0x8235, 0x8D94, 0x8814
RGBA, FLOAT, UNSIGNED_INT, INT = 0x1908, 0x1406, 0x1405, 0x1404
MIN_FILTER, MAG_FILTER, WRAP_S, WRAP_T, WRAP_R = 0x2801, 0x2800, 0x2802, 0x2803, 0x8072
LINEAR, NEAREST, CLAMP_TO_EDGE = 0x2601, 0x2600, 0x812F
FRAMEBUFFER, COLOR_ATTACHMENT0, FRAMEBUFFER_COMPLETE = 0x8D40, 0x8CE0, 0x8CD5
READ_WRITE, ALL_BARRIER_BITS, PACK_ALIGNMENT = 0x88BA, 0xFFFFFFFF, 0x0D05
DEPTH_TEST, SCISSOR_TEST, BLEND, PROGRAM_POINT_SIZE, FUNC_ADD, POINTS = (
    0x0B71, 0x0C11, 0x0BE2, 0x8642, 0x8006, 0x0000)
# The coverage sums' fixed point: 12 bits of integer part (optical depths up to 2048) and 20
# bits of fraction (1e-6, far below the 8 bits of the image).
FIXED_POINT_ONE = 1 << 20


class GL:
    """The current context's GL functions, through glXGetProcAddress or eglGetProcAddress."""

    def __init__(self, egl: bool):
        if egl:
            library = ctypes.CDLL("libEGL.so.1")
            lookup = library.eglGetProcAddress
        else:
            library = ctypes.CDLL("libGL.so.1")
            lookup = library.glXGetProcAddressARB
        lookup.restype = c_void_p
        lookup.argtypes = [c_char_p]
        for name, (result, arguments) in _SIGNATURES.items():
            address = lookup(name.encode())
            if not address:
                raise RuntimeError(f"the context has no {name}")
            setattr(self, name[2:], ctypes.CFUNCTYPE(result, *arguments)(address))

    def shader(self, kind: int, source: str) -> int:
        shader = self.CreateShader(kind)
        text = c_char_p(source.encode())
        self.ShaderSource(shader, 1, ctypes.byref(text), None)
        self.CompileShader(shader)
        status = c_int()
        self.GetShaderiv(shader, COMPILE_STATUS, ctypes.byref(status))
        if not status.value:
            log = ctypes.create_string_buffer(10000)
            self.GetShaderInfoLog(shader, 10000, None, log)
            raise RuntimeError(log.value.decode())
        return shader

    def program(self, *stages) -> int:
        program = self.CreateProgram()
        for kind, source in stages:
            self.AttachShader(program, self.shader(kind, source))
        self.LinkProgram(program)
        status = c_int()
        self.GetProgramiv(program, LINK_STATUS, ctypes.byref(status))
        if not status.value:
            log = ctypes.create_string_buffer(10000)
            self.GetProgramInfoLog(program, 10000, None, log)
            raise RuntimeError(log.value.decode())
        return program

    def name(self, generate) -> int:
        value = c_uint()
        generate(1, ctypes.byref(value))
        return value.value


# What the points' and the compute traversal share: the cell's face planes and bounding square
# (as vtkSPTTetrahedraPointsVS.glsl makes them) and the work of one (cell, sample).
COMMON = """#version 450
layout(std430, binding = 0) readonly buffer Points { float points[]; };
layout(std430, binding = 1) readonly buffer Tetrahedra { uvec4 tetrahedra[]; };
layout(std430, binding = 2) readonly buffer Scalars { float scalars[]; };
uniform mat4 MCVC;
uniform mat4 VCDC;
uniform mat4 DCVC;
uniform vec2 size;
uniform sampler3D table;
uniform float thicknessToTable;
uniform int seed;
layout(r32ui) coherent uniform uimage2D keys;

struct Cell { vec4 facePlanes[4]; vec4 scalarPlane; };

vec3 vertexVC(uint id)
{
  return (MCVC * vec4(points[3u * id], points[3u * id + 1u], points[3u * id + 2u], 1.0)).xyz;
}

vec4 ndcFacePlane(vec3 k, vec3 a, vec3 b, vec3 c)
{
  vec3 normal = cross(b - a, c - a);
  normal /= -dot(normal, k - a);
  return vec4(normal, -dot(normal, a)) * DCVC;
}

uvec4 pcg4d(uvec4 v)
{
  v = v * 1664525u + 1013904223u;
  v.x += v.y * v.w; v.y += v.z * v.x; v.z += v.x * v.y; v.w += v.y * v.z;
  v ^= v >> 16u;
  v.x += v.y * v.w; v.y += v.z * v.x; v.z += v.x * v.y; v.w += v.y * v.z;
  return v;
}

// The cell's planes, its bounding square in normalized device coordinates and the depth of its
// nearest vertex; false for a flat cell or one outside the viewport.
bool setUp(uint id, out Cell cell, out vec2 low, out vec2 high, out float nearest)
{
  uvec4 ids = tetrahedra[id];
  vec3 v0 = vertexVC(ids.x);
  vec3 v1 = vertexVC(ids.y);
  vec3 v2 = vertexVC(ids.z);
  vec3 v3 = vertexVC(ids.w);
  vec4 s = vec4(scalars[ids.x], scalars[ids.y], scalars[ids.z], scalars[ids.w]);
  cell.facePlanes[0] = ndcFacePlane(v0, v1, v2, v3);
  cell.facePlanes[1] = ndcFacePlane(v1, v2, v3, v0);
  cell.facePlanes[2] = ndcFacePlane(v2, v3, v0, v1);
  cell.facePlanes[3] = ndcFacePlane(v3, v0, v1, v2);
  cell.scalarPlane = s.x * cell.facePlanes[0] + s.y * cell.facePlanes[1] +
    s.z * cell.facePlanes[2] + s.w * cell.facePlanes[3];
  vec4 c0 = VCDC * vec4(v0, 1.0);
  vec4 c1 = VCDC * vec4(v1, 1.0);
  vec4 c2 = VCDC * vec4(v2, 1.0);
  vec4 c3 = VCDC * vec4(v3, 1.0);
  vec2 p0 = c0.xy / c0.w;
  vec2 p1 = c1.xy / c1.w;
  vec2 p2 = c2.xy / c2.w;
  vec2 p3 = c3.xy / c3.w;
  low = max(min(min(p0, p1), min(p2, p3)), vec2(-1.0));
  high = min(max(max(p0, p1), max(p2, p3)), vec2(1.0));
  nearest = min(min(c0.z / c0.w, c1.z / c1.w), min(c2.z / c2.w, c3.z / c3.w));
  return dot(cross(v1 - v0, v2 - v0), v3 - v0) != 0.0 && all(lessThanEqual(low, high));
}

// The segment of the sample at window position `at` through the cell, its pre-integrated color
// and its depth key; false if the ray misses the cell.
bool shade(uint id, Cell cell, vec2 at, out vec4 color, out uint key)
{
  vec2 ndc = at / size * 2.0 - 1.0;
  float enter = -1.0;
  float leave = 1.0;
  for (int k = 0; k < 4; ++k)
  {
    float atZero = dot(cell.facePlanes[k].xyw, vec3(ndc, 1.0));
    float slope = cell.facePlanes[k].z;
    float bound = -atZero / slope;
    enter = slope < 0.0 ? max(enter, bound) : enter;
    leave = slope > 0.0 ? min(leave, bound) : leave;
    if (slope == 0.0 && atZero > 0.0)
    {
      return false;
    }
  }
  if (enter >= leave)
  {
    return false;
  }
  vec4 front = vec4(ndc, enter, 1.0);
  vec4 back = vec4(ndc, leave, 1.0);
  vec4 frontVC = DCVC * front;
  vec4 backVC = DCVC * back;
  float frontScalar = -dot(cell.scalarPlane, front) / frontVC.w;
  float backScalar = -dot(cell.scalarPlane, back) / backVC.w;
  float thickness = length(backVC.xyz / backVC.w - frontVC.xyz / frontVC.w);
  color = textureLod(table, vec3(clamp(frontScalar, 0.0, 1.0), clamp(backScalar, 0.0, 1.0),
    sqrt(min(thickness * thicknessToTable, 1.0))), 0.0);
  key = (uint((0.5 * enter + 0.5) * 16777215.0) << 8u) | (id & 0xFFu);
  return true;
}

// What one (cell, sample) adds to the sums of its traversal; false if it adds nothing.
// The keys traversal: the threshold and the key's atomic minimum, and the optical depth terms
// of the exact coverage. The colors traversal (after the keys): the color of a segment that
// is not in front of the repetition's survivor, the visibility estimator's sum at L = 1.
bool visit(uint id, Cell cell, vec2 at, out vec4 terms)
{
  vec4 color;
  uint key;
  if (!shade(id, cell, at, color, key))
  {
    return false;
  }
  ivec2 pixel = ivec2(at);
#ifdef COLORS
  terms = color;
  return key <= imageLoad(keys, pixel).r;
#else
  float threshold = float(pcg4d(uvec4(uvec2(pixel), id, uint(seed))).x >> 8u) / 16777216.0;
  if (threshold < color.a && key < imageLoad(keys, pixel).r)
  {
    imageAtomicMin(keys, pixel, key);
  }
  float tau = -log(1.0 - min(color.a, 0.99999994));
  terms = color.a > 0.0 ? vec4(color.rgb * (tau / color.a), tau) : vec4(0.0);
  return true;
#endif
}
"""

POINTS_VS = COMMON + """
flat out uint cellId;
flat out Cell cell;
void main()
{
  cellId = uint(gl_VertexID);
  vec2 low;
  vec2 high;
  float nearest;
  bool shown = setUp(cellId, cell, low, high, nearest);
  vec2 extent = (high - low) * 0.5 * size;
  gl_PointSize = max(extent.x, extent.y) + 0.05;
  gl_Position = shown ? vec4(0.5 * (low + high), clamp(nearest, -1.0, 1.0), 1.0)
                      : vec4(0.0, 0.0, 2.0, 1.0);
}
"""

POINTS_FS = COMMON + """
flat in uint cellId;
flat in Cell cell;
layout(location = 0) out vec4 coverage;
void main()
{
  vec4 terms;
  if (!visit(cellId, cell, gl_FragCoord.xy, terms))
  {
    discard;
  }
  coverage = terms;
}
"""

COMPUTE = COMMON + """
layout(local_size_x = 64) in;
uniform uint cellCount;
layout(r32i) uniform iimage2DArray coverage;
layout(std430, binding = 3) buffer CoverageSums { int sums[]; };
void main()
{
  uint id = gl_GlobalInvocationID.x;
  Cell cell;
  vec2 low;
  vec2 high;
  float nearest;
  if (id >= cellCount || !setUp(id, cell, low, high, nearest))
  {
    return;
  }
  // The samples whose centres lie in the bounding square: those a point of it covers.
  vec2 windowLow = (low * 0.5 + 0.5) * size;
  vec2 windowHigh = (high * 0.5 + 0.5) * size;
  ivec2 first = max(ivec2(ceil(windowLow - 0.5)), ivec2(0));
  ivec2 last = min(ivec2(floor(windowHigh - 0.5)), ivec2(size) - 1);
  for (int y = first.y; y <= last.y; ++y)
  {
    for (int x = first.x; x <= last.x; ++x)
    {
      vec4 terms;
      if (visit(id, cell, vec2(x, y) + 0.5, terms))
      {
#if defined(COVERAGE_IMAGE) || defined(COVERAGE_BUFFER)
        ivec4 fixedTerms = ivec4(round(terms * FIXED_POINT_ONE));
        for (int k = 0; k < 4; ++k)
        {
          if (fixedTerms[k] != 0)
          {
#ifdef COVERAGE_IMAGE
            imageAtomicAdd(coverage, ivec3(x, y, k), fixedTerms[k]);
#else
            atomicAdd(sums[4 * (y * int(size.x) + x) + k], fixedTerms[k]);
#endif
          }
        }
#endif
      }
    }
  }
}
"""


def matrix(vtk_matrix) -> np.ndarray:
    return np.array([[vtk_matrix.GetElement(i, j) for j in range(4)] for i in range(4)])


def pre_integration_table(front: int = 64, thickness: int = 32) -> np.ndarray:
    """A smooth made-up table: premultiplied RGBA by (thickness, back, front) scalar."""
    f = np.linspace(0.0, 1.0, front)[None, None, :]
    b = np.linspace(0.0, 1.0, front)[None, :, None]
    t = np.linspace(0.0, 1.0, thickness)[:, None, None]
    mean = 0.5 * (f + b)
    alpha = 1.0 - np.exp(-4.0 * t * t * (0.05 + np.exp(-(((mean - 0.6) / 0.15) ** 2))))
    rgba = np.stack([mean * alpha, (1.0 - mean) * alpha, 0.5 * alpha, alpha], axis=-1)
    return np.ascontiguousarray(rgba, dtype=np.float32)


def main(name: str, size: int) -> None:
    scene = race.race_scene(name)
    grid = scene.grid
    window, renderer = render.make_window(size, size)
    frames = {}
    for label, mapper in (("SPT L=1", render.spt_mapper(1)),
                          ("VTK PT", vtkOpenGLProjectedTetrahedraMapper())):
        frames[label] = render.render(grid, scene.property, mapper, scene.view, (size, size),
                                      window=window, frames=2).seconds
    camera = renderer.GetActiveCamera()
    model_view = matrix(camera.GetModelViewTransformMatrix())
    projection = matrix(camera.GetProjectionTransformMatrix(1.0, -1.0, 1.0))
    matrices = {"MCVC": model_view, "VCDC": projection, "DCVC": np.linalg.inv(projection)}

    cells = grid.GetNumberOfCells()
    points = vtk_to_numpy(grid.GetPoints().GetData()).astype(np.float32)
    tetrahedra = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).astype(np.uint32)
    if tetrahedra.size != 4 * cells:
        raise ValueError(f"{name} is not made of tetrahedra only")
    values = vtk_to_numpy(grid.GetPointData().GetScalars()).astype(np.float64)
    if values.ndim > 1:
        values = np.linalg.norm(values, axis=1)
    scalars = ((values - values.min()) / np.ptp(values)).astype(np.float32)
    bounds = np.array(grid.GetBounds())
    diagonal = float(np.linalg.norm(bounds[1::2] - bounds[0::2]))

    window.MakeCurrent()
    gl = GL(egl="EGL" in window.GetClassName())
    source = COMPUTE.replace("FIXED_POINT_ONE", f"{FIXED_POINT_ONE}.0")

    def compute(define: str) -> int:
        return gl.program((COMPUTE_SHADER, source.replace("#version 450", "#version 450" + define)))

    colors_fs = POINTS_FS.replace("#version 450", "#version 450\n#define COLORS")
    programs = {
        "points": gl.program((VERTEX_SHADER, POINTS_VS), (FRAGMENT_SHADER, POINTS_FS)),
        "points, colors": gl.program((VERTEX_SHADER, POINTS_VS), (FRAGMENT_SHADER, colors_fs)),
        "compute, colors": compute("\n#define COLORS\n#define COVERAGE_BUFFER"),
        "compute": compute(""),
        "compute, sums in an image": compute("\n#define COVERAGE_IMAGE"),
        "compute, sums in a buffer": compute("\n#define COVERAGE_BUFFER"),
    }

    def storage(data: np.ndarray, binding: int) -> int:
        buffer = gl.name(gl.GenBuffers)
        gl.BindBuffer(SHADER_STORAGE_BUFFER, buffer)
        gl.BufferData(SHADER_STORAGE_BUFFER, data.nbytes, data.ctypes.data, STATIC_DRAW)
        gl.BindBufferBase(SHADER_STORAGE_BUFFER, binding, buffer)
        return buffer

    storage(np.ascontiguousarray(points), 0)
    storage(np.ascontiguousarray(tetrahedra), 1)
    storage(scalars, 2)
    sums_buffer = storage(np.zeros(4 * size * size, np.int32), 3)

    def texture(target: int, filtering: int) -> int:
        name = gl.name(gl.GenTextures)
        gl.BindTexture(target, name)
        for parameter in (MIN_FILTER, MAG_FILTER):
            gl.TexParameteri(target, parameter, filtering)
        return name

    table = pre_integration_table()
    gl.ActiveTexture(TEXTURE0)
    table_texture = texture(TEXTURE_3D, LINEAR)
    gl.TexImage3D(TEXTURE_3D, 0, RGBA32F, table.shape[2], table.shape[1], table.shape[0], 0, RGBA,
                  FLOAT, table.ctypes.data)
    for wrap in (WRAP_S, WRAP_T, WRAP_R):
        gl.TexParameteri(TEXTURE_3D, wrap, CLAMP_TO_EDGE)
    keys = texture(TEXTURE_2D, NEAREST)
    gl.TexImage2D(TEXTURE_2D, 0, R32UI, size, size, 0, R32I_FORMAT, UNSIGNED_INT, None)
    coverage_image = texture(TEXTURE_2D_ARRAY, NEAREST)
    gl.TexImage3D(TEXTURE_2D_ARRAY, 0, R32I, size, size, 4, 0, R32I_FORMAT, INT, None)
    coverage_target = texture(TEXTURE_2D, NEAREST)
    gl.TexImage2D(TEXTURE_2D, 0, RGBA32F, size, size, 0, RGBA, FLOAT, None)
    framebuffer = gl.name(gl.GenFramebuffers)
    gl.BindFramebuffer(FRAMEBUFFER, framebuffer)
    gl.FramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, coverage_target, 0)
    if gl.CheckFramebufferStatus(FRAMEBUFFER) != FRAMEBUFFER_COMPLETE:
        raise RuntimeError("the coverage target is not complete")
    gl.BindVertexArray(gl.name(gl.GenVertexArrays))
    gl.ActiveTexture(TEXTURE0)
    gl.BindTexture(TEXTURE_3D, table_texture)
    gl.BindImageTexture(0, keys, 0, 0, 0, READ_WRITE, R32UI)
    gl.BindImageTexture(1, coverage_image, 0, 1, 0, READ_WRITE, R32I)

    def use(program: int) -> None:
        gl.UseProgram(program)
        for uniform, value in matrices.items():
            transposed = np.ascontiguousarray(value.T, dtype=np.float32)
            gl.UniformMatrix4fv(gl.GetUniformLocation(program, uniform.encode()), 1, 0,
                                transposed.ctypes.data_as(POINTER(c_float)))
        gl.Uniform2f(gl.GetUniformLocation(program, b"size"), float(size), float(size))
        gl.Uniform1f(gl.GetUniformLocation(program, b"thicknessToTable"), 1.0 / (0.02 * diagonal))
        for uniform, value in ((b"table", 0), (b"seed", 7), (b"keys", 0), (b"coverage", 1)):
            gl.Uniform1i(gl.GetUniformLocation(program, uniform), value)
        gl.Uniform1ui(gl.GetUniformLocation(program, b"cellCount"), cells)

    def clear() -> None:
        nothing_kept = np.array([0xFFFFFFFF], np.uint32)
        zeros = np.zeros(4, np.int32)
        gl.ClearTexImage(keys, 0, R32I_FORMAT, UNSIGNED_INT, nothing_kept.ctypes.data)
        gl.ClearTexImage(coverage_image, 0, R32I_FORMAT, INT, zeros.ctypes.data)
        gl.ClearTexImage(coverage_target, 0, RGBA, FLOAT, zeros.ctypes.data)
        gl.BindBuffer(SHADER_STORAGE_BUFFER, sums_buffer)
        gl.ClearBufferData(SHADER_STORAGE_BUFFER, R32I, R32I_FORMAT, INT, zeros.ctypes.data)
        gl.Finish()

    def draw_points(coverage: bool, program: str = "points") -> None:
        use(programs[program])
        gl.BindFramebuffer(FRAMEBUFFER, framebuffer)
        gl.Viewport(0, 0, size, size)
        gl.Disable(DEPTH_TEST)
        gl.Disable(SCISSOR_TEST)
        gl.Enable(PROGRAM_POINT_SIZE)
        gl.Enable(BLEND)
        gl.BlendFunc(1, 1)
        gl.BlendEquation(FUNC_ADD)
        gl.ColorMask(*([int(coverage)] * 4))
        gl.DrawArrays(POINTS, 0, cells)

    def dispatch(variant: str) -> None:
        use(programs[variant])
        gl.DispatchCompute((cells + 63) // 64, 1, 1)
        gl.MemoryBarrier(ALL_BARRIER_BITS)

    runs = {
        "points, keys and coverage": lambda: draw_points(True),
        "compute, keys and coverage (image)": lambda: dispatch("compute, sums in an image"),
        "compute, keys and coverage (buffer)": lambda: dispatch("compute, sums in a buffer"),
        "points, keys only": lambda: draw_points(False),
        "compute, keys only": lambda: dispatch("compute"),
    }
    # The colors traversal reads the keys that the keys traversal left.
    colors = {
        "points, colors": lambda: draw_points(True, "points, colors"),
        "compute, colors (buffer)": lambda: dispatch("compute, colors"),
    }

    def keys_then(run) -> None:
        clear()
        draw_points(False)
        gl.Finish()
        run()

    best = {label: float("inf") for label in list(runs) + list(colors)}
    for _ in range(4):
        for label, run in list(runs.items()) + list(colors.items()):
            if label in colors:
                keys_then(lambda: None)
            else:
                clear()
            start = time.perf_counter()
            run()
            gl.Finish()
            best[label] = min(best[label], time.perf_counter() - start)

    def read(texture_name: int, target: int, shape, dtype, data_format: int, data_type: int):
        out = np.empty(shape, dtype)
        gl.BindTexture(target, texture_name)
        gl.PixelStorei(PACK_ALIGNMENT, 1)
        gl.GetTexImage(target, 0, data_format, data_type, out.ctypes.data)
        return out

    clear()
    runs["points, keys and coverage"]()
    gl.Finish()
    keys_points = read(keys, TEXTURE_2D, (size, size), np.uint32, R32I_FORMAT, UNSIGNED_INT)
    coverage_points = read(coverage_target, TEXTURE_2D, (size, size, 4), np.float32, RGBA, FLOAT)
    clear()
    runs["compute, keys and coverage (image)"]()
    gl.Finish()
    keys_compute = read(keys, TEXTURE_2D, (size, size), np.uint32, R32I_FORMAT, UNSIGNED_INT)
    coverage_compute = np.moveaxis(read(coverage_image, TEXTURE_2D_ARRAY, (4, size, size),
                                        np.int32, R32I_FORMAT, INT), 0, -1) / FIXED_POINT_ONE

    storage_read = np.empty(4 * size * size, np.int32)
    keys_then(colors["points, colors"])
    gl.Finish()
    colors_points = read(coverage_target, TEXTURE_2D, (size, size, 4), np.float32, RGBA, FLOAT)
    keys_then(colors["compute, colors (buffer)"])
    gl.Finish()
    gl.BindBuffer(SHADER_STORAGE_BUFFER, sums_buffer)
    gl.GetBufferSubData(SHADER_STORAGE_BUFFER, 0, storage_read.nbytes, storage_read.ctypes.data)
    colors_compute = storage_read.reshape(size, size, 4) / FIXED_POINT_ONE

    print(f"{name}: {cells:,} cells, {size} x {size}; SPT at L = 1 {frames['SPT L=1']:.3f} s, "
          f"VTK PT {frames['VTK PT']:.3f} s")
    print(f"samples with a key: {int((keys_points != 0xFFFFFFFF).sum())}; keys that differ: "
          f"{int((keys_points != keys_compute).sum())}; largest coverage "
          f"{float(coverage_points.max()):.3g}, largest difference "
          f"{float(np.abs(coverage_points - coverage_compute).max()):.2g}")
    print(f"colors: largest sum {float(colors_points.max()):.3g}, largest difference "
          f"{float(np.abs(colors_points - colors_compute).max()):.2g}")
    for label, seconds in best.items():
        print(f"{label}: {seconds:.4f} s")
    print("compute / points: keys and coverage %.2f (image), %.2f (buffer); keys only %.2f" % (
        best["compute, keys and coverage (image)"] / best["points, keys and coverage"],
        best["compute, keys and coverage (buffer)"] / best["points, keys and coverage"],
        best["compute, keys only"] / best["points, keys only"]))
    print("compute / points: colors %.2f" % (
        best["compute, colors (buffer)"] / best["points, colors"]))
    # Both ways must do the same work: the same keys, and sums that differ by the fixed point's
    # rounding (2^-21 per term) and the float blending's, far below 1e-4 here.
    if (keys_points != keys_compute).any():
        raise SystemExit("the compute pass left other keys than the points")
    for what, difference in (("coverage", np.abs(coverage_points - coverage_compute).max()),
                             ("colors", np.abs(colors_points - colors_compute).max())):
        if not difference < 1e-4:
            raise SystemExit(
                f"the compute pass's {what} sums differ from the points' by {difference}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "drill-1M",
         int(sys.argv[2]) if len(sys.argv) > 2 else 256)
