"""The GLSL of the compute traversal experiment (compute_traversal.py): the mapper's own
functions, read from the source tree as the mapper assembles them, and the experiment's
simplified work per (cell, sample) for the points' fragment stage and the compute stage."""

import pathlib

REPOSITORY = pathlib.Path(__file__).resolve().parents[2]


def shader_file(path: str) -> str:
    """A GLSL file of the source tree, by its path from the repository's root."""
    return (REPOSITORY / path).read_text()


def glsl_definition(source: str, start: str) -> str:
    """The definition in ``source`` that begins with ``start`` (the first line of a function
    or a struct), up to its closing brace, with a struct's semicolon."""
    begin = source.index(start)
    depth = 0
    for end in range(source.index("{", begin), len(source)):
        depth += {"{": 1, "}": -1}.get(source[end], 0)
        if depth == 0:
            break
    end += 2 if source.startswith("};", end) else 1
    return source[begin:end] + "\n"


def mapper_functions(stage_declarations: str) -> str:
    """The mapper's GLSL that both traversals' sample work uses, after the declarations of the
    stage's cell and sample (``samplePosition``, ``facePlaneNDC``, ``scalarPlaneNDC``): the
    hash, a cell's face planes and point (for the compute traversal), and a sample's segment."""
    fragment = shader_file("Rendering/SPT/shaders/vtkSPTTetrahedraFS.glsl")
    return "\n".join([
        stage_declarations, UNIFORMS,
        shader_file("Rendering/Core/shaders/vtkHashRandom.glsl"),
        shader_file("Rendering/SPT/shaders/vtkSPTFacePlane.glsl"),
        shader_file("Rendering/SPT/shaders/vtkSPTPointCell.glsl"),
        glsl_definition(fragment, "struct Segment"),
        glsl_definition(fragment, "bool planeSegment(out Segment segment)"),
        SAMPLE_WORK])


# What the points' vertex stage (vtkSPTTetrahedraPointsVS.glsl) declares too, and what the
# sample work needs besides.
UNIFORMS = """
uniform mat4 MCVCMatrix;
uniform mat4 VCDCMatrix;
uniform mat4 DCVCMatrix;
uniform vec2 passSizeInPixels;
uniform usamplerBuffer tetrahedra;
uniform samplerBuffer points;
uniform samplerBuffer scalars;
uniform sampler3D table;
uniform float thicknessToTable;
uniform int seed;
layout(r32ui) coherent uniform uimage2D keys;
"""

SAMPLE_WORK = """
// The segment of the sample through the cell, its pre-integrated color and its depth key;
// false if the ray misses the cell.
bool shade(uint id, out vec4 color, out uint key)
{
  Segment segment;
  if (!planeSegment(segment))
  {
    return false;
  }
  float thickness = length(segment.backVC - segment.frontVC);
  color = textureLod(table, vec3(clamp(segment.frontScalar, 0.0, 1.0),
    clamp(segment.backScalar, 0.0, 1.0), sqrt(min(thickness * thicknessToTable, 1.0))), 0.0);
  key = (uint(segment.frontDepth * 16777215.0) << 8u) | (id & 0xFFu);
  return true;
}

// What one (cell, sample) adds to the sums of its traversal; false if it adds nothing.
// The keys traversal: the threshold and the key's atomic minimum, and the optical depth terms
// of the exact coverage. The colors traversal (after the keys): the color of a segment that
// is not in front of the repetition's survivor, the visibility estimator's sum at L = 1.
bool visit(uint id, out vec4 terms)
{
  vec4 color;
  uint key;
  if (!shade(id, color, key))
  {
    return false;
  }
  ivec2 pixel = ivec2(samplePosition);
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

POINTS_FS = """
#define samplePosition gl_FragCoord.xy
flat in int tetrahedronId;
flat in vec4 facePlaneNDC[4];
flat in vec4 scalarPlaneNDC;
//SAMPLE
layout(location = 0) out vec4 coverage;
void main()
{
  vec4 terms;
  if (!visit(uint(tetrahedronId), terms))
  {
    discard;
  }
  coverage = terms;
}
"""

COMPUTE = """
vec2 samplePosition;
vec4 facePlaneNDC[4];
vec4 scalarPlaneNDC;
//SAMPLE
layout(local_size_x = 64) in;
uniform uint cellCount;
layout(r32i) uniform iimage2DArray coverage;
layout(std430, binding = 3) buffer CoverageSums { int sums[]; };

void addTerms(ivec2 pixel, vec4 terms)
{
#if defined(COVERAGE_IMAGE) || defined(COVERAGE_BUFFER)
  ivec4 fixedTerms = ivec4(round(terms * FIXED_POINT_ONE));
  for (int k = 0; k < 4; ++k)
  {
    if (fixedTerms[k] != 0)
    {
#ifdef COVERAGE_IMAGE
      imageAtomicAdd(coverage, ivec3(pixel, k), fixedTerms[k]);
#else
      atomicAdd(sums[4 * (pixel.y * int(passSizeInPixels.x) + pixel.x) + k], fixedTerms[k]);
#endif
    }
  }
#endif
}

void main()
{
  uint id = gl_GlobalInvocationID.x;
  vec2 low;
  vec2 high;
  float nearest;
  if (id >= cellCount || !pointCell(int(id), facePlaneNDC, scalarPlaneNDC, low, high, nearest))
  {
    return;
  }
  // The samples whose centres lie in the bounding square: those a point of it covers.
  vec2 windowLow = (low * 0.5 + 0.5) * passSizeInPixels;
  vec2 windowHigh = (high * 0.5 + 0.5) * passSizeInPixels;
  ivec2 first = max(ivec2(ceil(windowLow - 0.5)), ivec2(0));
  ivec2 last = min(ivec2(floor(windowHigh - 0.5)), ivec2(passSizeInPixels) - 1);
  for (int y = first.y; y <= last.y; ++y)
  {
    for (int x = first.x; x <= last.x; ++x)
    {
      samplePosition = vec2(x, y) + 0.5;
      vec4 terms;
      if (visit(id, terms))
      {
        addTerms(ivec2(x, y), terms);
      }
    }
  }
}
"""


def points_vertex_source() -> str:
    """The mapper's vertex stage of the cells drawn as points, assembled as the mapper does."""
    source = shader_file("Rendering/SPT/shaders/vtkSPTTetrahedraPointsVS.glsl")
    for tag, text in (("//VTK::System::Dec", "#version 450"), ("//Volume::Defines::Dec", ""),
                      ("//SPT::FacePlane::Impl",
                       shader_file("Rendering/SPT/shaders/vtkSPTFacePlane.glsl")),
                      ("//SPT::PointCell::Impl",
                       shader_file("Rendering/SPT/shaders/vtkSPTPointCell.glsl"))):
        source = source.replace(tag, text)
    return source


def sample_stage_source(main: str, *defines: str) -> str:
    """A fragment or compute stage: ``main`` with the mapper's functions and the sample work at
    its //SAMPLE, after the version and ``defines``."""
    declarations, body = main.split("//SAMPLE")
    header = "\n".join(["#version 450"] + [f"#define {define}" for define in defines])
    return header + "\n" + mapper_functions(declarations) + body
