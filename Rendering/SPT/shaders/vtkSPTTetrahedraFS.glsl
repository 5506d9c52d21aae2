//VTK::System::Dec
//SPT::Extensions::Dec
//VTK::Output::Dec
//Volume::Defines::Dec

// SPT fragment stage (Sakamoto, Kawamura, Kuwano and Koyamada 2009): each fragment is one ray
// segment through one tetrahedron. This file finds the segment and its pre-integrated color
// and opacity, and draws the keep-or-discard thresholds; the main() of the pass, appended at
// the end, decides what the fragment writes (vtkSPTPass*FS.glsl).

#ifdef SPT_COMPUTE
// The compute traversal sets these for each cell and sample (vtkSPTTetrahedraCS.glsl).
vec2 samplePosition; // window coordinates of the sample's centre in the pass
int tetrahedronId;
vec4 facePlaneNDC[4];
vec4 scalarPlaneNDC;
#else
#define samplePosition gl_FragCoord.xy
flat in int tetrahedronId;
flat in vec4 facePlaneNDC[4]; // the cell's face planes and scalar plane (vtkSPTFacePlane.glsl)
flat in vec4 scalarPlaneNDC;
#endif
#ifdef SPT_CLIPPED_CELLS
flat in int clippedCell; // 1: the exit face of a cell that the near plane cuts
#endif

uniform sampler3D preIntegrationTable; // (front scalar, back scalar, sqrt(thickness)) -> RGBA
uniform vec3 tableTexelScale;          // maps [0, 1] onto the centers of the first and last texels
uniform vec3 tableTexelOffset;
uniform float thicknessToTable;        // 1 / largest thickness in the table, model units
uniform mat3 VCMCLinear;               // view -> model, for lengths: the unit distance of the
                                       // opacity is a length in the data's own coordinates

uniform sampler2D sceneDepthTexture;   // depth of the opaque scene, one texel per pixel
                                       // (SPT_SCENE_DEPTH: opaque geometry was drawn)
uniform int subpixelLevel;
uniform vec2 pixelScale;               // viewport pixels per image pixel: 1 but in interactive renders
uniform vec2 passSizeInPixels;
uniform mat4 DCVCMatrix;               // clip -> view
uniform mat4 VCDCMatrix;               // view -> clip
uniform mat4 MCVCMatrix;               // model -> view

// The mesh, for the cells that a clipping plane cuts: four point ids per tetrahedron, the points
// (model coordinates) and their scalars (or one scalar per tetrahedron).
uniform usamplerBuffer tetrahedra;
uniform samplerBuffer points;
uniform samplerBuffer scalars;

#ifdef SPT_CLIPPING_PLANES
uniform vec4 clippingPlanes[6]; // the mapper's clipping planes (view coordinates): a point is
uniform int clippingPlaneCount; // kept where dot(plane, (x, 1)) >= 0 for each of them
#endif

uniform int cellIdOffset; // where this volume's cell ids start among the frame's volumes
#ifdef SPT_GLOBAL_IDS
uniform usamplerBuffer randomIds; // per tetrahedron: the id from the input's global cell id
#else
uniform usamplerBuffer meshIndices; // per tetrahedron drawn: its index in the mesh
#endif
uniform int repetition; // first repetition of this pass; bit patterns of unsigned values:
uniform int seed;       // VTK sets int uniforms only
uniform int stratumCount;  // stratified sampling: the repetitions from stratumOrigin on form
uniform int stratumOrigin; // blocks of stratumCount; 0 for independent sampling
uniform int stratumMask;   // 2^k - 1 >= stratumCount - 1, and about k / 2, for permute()
uniform int stratumShift;
uniform int repetitionsInGroup; // of the SPT_REPETITIONS_PER_PASS, how many this pass draws

//Volume::Random::Impl

// One ray segment through one tetrahedron, in view coordinates, with the scalars at its ends
// and the window depth of its front, which orders the segments of a sample.
struct Segment
{
  vec3 frontVC;
  vec3 backVC;
  float frontScalar;
  float backScalar;
  float frontDepth;
};

// The scalar at a point of this fragment's cell (the cell's own with scalars per cell).
float scalarAt(uint pointId)
{
#ifdef SPT_CELL_SCALARS
  return texelFetch(scalars, tetrahedronId).r;
#else
  return texelFetch(scalars, int(pointId)).r;
#endif
}

// The segment of this fragment's ray through its tetrahedron, clipped in normalized device
// coordinates, where the ray is a line along z: each face plane bounds z from one side. False
// when the ray misses the cell (a point's square is larger than the cell's projection, and a
// sample on the outline's edge may fall just outside the cell).
bool planeSegment(out Segment segment)
{
  vec2 ndc = samplePosition / passSizeInPixels * 2.0 - 1.0;
  float enter = -1.0;
  float leave = 1.0;
  for (int k = 0; k < 4; ++k)
  {
    float atZero = dot(facePlaneNDC[k].xyw, vec3(ndc, 1.0));
    float slope = facePlaneNDC[k].z;
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
  vec4 frontVC = DCVCMatrix * front;
  vec4 backVC = DCVCMatrix * back;
  segment.frontVC = frontVC.xyz / frontVC.w;
  segment.backVC = backVC.xyz / backVC.w;
  segment.frontScalar = -dot(scalarPlaneNDC, front) / frontVC.w;
  segment.backScalar = -dot(scalarPlaneNDC, back) / backVC.w;
  segment.frontDepth = 0.5 * enter + 0.5;
  return true;
}

#ifdef SPT_CLIPPED_CELLS
// The sample's ray in view coordinates, from the near plane (t = 0) to the far plane (t = 1).
void sampleRay(out vec3 origin, out vec3 direction)
{
  vec2 ndc = samplePosition / passSizeInPixels * 2.0 - 1.0;
  vec4 nearVC = DCVCMatrix * vec4(ndc, -1.0, 1.0);
  vec4 farVC = DCVCMatrix * vec4(ndc, 1.0, 1.0);
  origin = nearVC.xyz / nearVC.w;
  direction = farVC.xyz / farVC.w - origin;
}

// The parameters where the ray enters and leaves the cell of these outward face planes: it
// enters at the last of the entry faces' planes and leaves at the first of the exit faces'.
void clipRayByPlanes(vec4 facePlane[4], vec3 origin, vec3 direction, out float enter,
  out float leave)
{
  enter = 0.0;
  leave = 1.0;
  for (int k = 0; k < 4; ++k)
  {
    float approach = dot(facePlane[k].xyz, direction);
    float t = -dot(facePlane[k], vec4(origin, 1.0)) / approach;
    if (approach < 0.0)
    {
      enter = max(enter, t);
    }
    else if (approach > 0.0)
    {
      leave = min(leave, t);
    }
  }
}

// The segment of the ray from `enter` to `leave`, the scalars at its ends interpolated with
// the cell's barycentric weights (minus the face planes' values).
void rayCellSegment(vec4 facePlane[4], vec4 vertexScalar, vec3 origin, vec3 direction,
  float enter, float leave, out Segment segment)
{
  segment.frontVC = origin + enter * direction;
  segment.backVC = origin + leave * direction;
  vec4 front = vec4(segment.frontVC, 1.0);
  vec4 back = vec4(segment.backVC, 1.0);
  vec4 frontWeights = -vec4(dot(facePlane[0], front), dot(facePlane[1], front),
    dot(facePlane[2], front), dot(facePlane[3], front));
  vec4 backWeights = -vec4(dot(facePlane[0], back), dot(facePlane[1], back),
    dot(facePlane[2], back), dot(facePlane[3], back));
  segment.frontScalar = dot(vertexScalar, frontWeights);
  segment.backScalar = dot(vertexScalar, backWeights);
  vec4 frontDC = VCDCMatrix * front;
  segment.frontDepth = clamp(0.5 * frontDC.z / frontDC.w + 0.5, 0.0, 1.0);
}

// The outward face planes of a tetrahedron (view coordinates): facePlane[k] is the plane of the
// face opposite vertex k, scaled so that the vertex is at -1. False for a flat tetrahedron,
// which holds no volume.
bool cellFacePlanes(vec3 vertexVC[4], out vec4 facePlane[4])
{
  for (int k = 0; k < 4; ++k)
  {
    vec3 a = vertexVC[(k + 1) % 4];
    vec3 normal = cross(vertexVC[(k + 2) % 4] - a, vertexVC[(k + 3) % 4] - a);
    float towardsOpposite = dot(normal, vertexVC[k] - a);
    if (towardsOpposite == 0.0)
    {
      return false;
    }
    normal /= -towardsOpposite;
    facePlane[k] = vec4(normal, -dot(normal, a));
  }
  return true;
}

// The segment of a cell that a clipping plane cuts, between the near plane and the cell's
// exit. False when the ray misses the cell.
bool cellSegment(out Segment segment)
{
  vec3 origin;
  vec3 direction;
  sampleRay(origin, direction);
  uvec4 ids = texelFetch(tetrahedra, tetrahedronId);
  vec3 vertexVC[4];
  vec4 vertexScalar;
  for (int i = 0; i < 4; ++i)
  {
    vertexVC[i] = (MCVCMatrix * vec4(texelFetch(points, int(ids[i])).xyz, 1.0)).xyz;
    vertexScalar[i] = scalarAt(ids[i]);
  }
  vec4 facePlane[4];
  float enter;
  float leave;
  if (!cellFacePlanes(vertexVC, facePlane))
  {
    return false;
  }
  clipRayByPlanes(facePlane, origin, direction, enter, leave);
  if (enter >= leave)
  {
    return false;
  }
  rayCellSegment(facePlane, vertexScalar, origin, direction, enter, leave, segment);
  return true;
}
#endif

#ifdef SPT_CLIPPING_PLANES
// Cuts the segment to the part that every clipping plane keeps. The scalar is linear along
// the segment, so the cut ends get the exact scalar, and the table the shortened thickness:
// the cut segment's own color. False when nothing is left.
bool clipSegment(inout Segment segment)
{
  vec4 front = vec4(segment.frontVC, 1.0);
  vec4 back = vec4(segment.backVC, 1.0);
  float enter = 0.0;
  float leave = 1.0;
  for (int k = 0; k < clippingPlaneCount; ++k)
  {
    float atFront = dot(clippingPlanes[k], front);
    float atBack = dot(clippingPlanes[k], back);
    if (atFront < 0.0 && atBack < 0.0)
    {
      return false;
    }
    if (atFront < 0.0)
    {
      enter = max(enter, atFront / (atFront - atBack));
    }
    else if (atBack < 0.0)
    {
      leave = min(leave, atFront / (atFront - atBack));
    }
  }
  if (enter >= leave)
  {
    return false;
  }
  if (enter > 0.0 || leave < 1.0)
  {
    float frontScalar = segment.frontScalar;
    segment.frontVC = mix(front.xyz, back.xyz, enter);
    segment.backVC = mix(front.xyz, back.xyz, leave);
    segment.frontScalar = mix(frontScalar, segment.backScalar, enter);
    segment.backScalar = mix(frontScalar, segment.backScalar, leave);
    vec4 frontDC = VCDCMatrix * vec4(segment.frontVC, 1.0);
    segment.frontDepth = enter > 0.0
      ? clamp(0.5 * frontDC.z / frontDC.w + 0.5, 0.0, 1.0) : segment.frontDepth;
  }
  return true;
}
#endif

// This fragment's segment, cut by the clipping planes and where opaque geometry hides the rest
// of it. False when nothing of it is visible.
bool visibleSegment(out Segment segment)
{
#ifdef SPT_CLIPPED_CELLS
  if (clippedCell != 0)
  {
    if (!cellSegment(segment))
    {
      return false;
    }
  }
  else
#endif
  if (!planeSegment(segment))
  {
    return false;
  }
#ifdef SPT_CLIPPING_PLANES
  if (!clipSegment(segment))
  {
    return false;
  }
#endif

#ifdef SPT_SCENE_DEPTH
  // Opaque geometry hides what lies behind it and cuts a segment that it passes through.
  ivec2 scenePixel = ivec2(samplePosition) / subpixelLevel;
  if (pixelScale != vec2(1.0))
  {
    // An image with fewer pixels than the viewport: the viewport pixel at this one's center.
    scenePixel = min(ivec2((vec2(scenePixel) + 0.5) * pixelScale),
      textureSize(sceneDepthTexture, 0) - 1);
  }
  float sceneDepth = texelFetch(sceneDepthTexture, scenePixel, 0).r;
  if (segment.frontDepth >= sceneDepth)
  {
    return false;
  }
  if (sceneDepth < 1.0 && segment.frontVC.z > segment.backVC.z)
  {
    vec4 sceneDC = vec4(samplePosition / passSizeInPixels * 2.0 - 1.0, sceneDepth * 2.0 - 1.0, 1.0);
    vec4 sceneVC = DCVCMatrix * sceneDC;
    float sceneZ = sceneVC.z / sceneVC.w;
    if (sceneZ > segment.backVC.z)
    {
      float t = clamp((segment.frontVC.z - sceneZ) / (segment.frontVC.z - segment.backVC.z), 0.0, 1.0);
      segment.backVC = mix(segment.frontVC, segment.backVC, t);
      segment.backScalar = mix(segment.frontScalar, segment.backScalar, t);
    }
  }
#endif
  return true;
}

// The segment's pre-integrated color and opacity: premultiplied RGBA.
vec4 preIntegrated(Segment segment)
{
  float thickness = length(VCMCLinear * (segment.backVC - segment.frontVC));
  vec3 coordinate = vec3(clamp(segment.frontScalar, 0.0, 1.0), clamp(segment.backScalar, 0.0, 1.0),
    sqrt(min(thickness * thicknessToTable, 1.0)));
  return texture(preIntegrationTable, coordinate * tableTexelScale + tableTexelOffset);
}

// The segment's optical depth tau = -ln(1 - alpha) and its tau-weighted color, the terms of
// the exact coverage (see vtkEnsembleResolveFS.glsl).
vec4 opticalDepthTerms(vec4 color)
{
  float tau = -log(1.0 - min(color.a, 0.99999994));
  return color.a > 0.0 ? vec4(color.rgb * (tau / color.a), tau) : vec4(0.0);
}

// The id of this fragment's cell among the frame's volumes, which its random numbers follow.
uint cellId()
{
#ifdef SPT_GLOBAL_IDS
  return texelFetch(randomIds, tetrahedronId).r + uint(cellIdOffset);
#else
  return texelFetch(meshIndices, tetrahedronId).r + uint(cellIdOffset);
#endif
}

// The depth key of a segment for the atomic minimum: the depth in 24 bits (as a depth buffer
// holds it), then 8 bits of the tetrahedron's id, so that two fragments at one depth do not
// both win.
uint depthKey(Segment segment)
{
  return (uint(segment.frontDepth * 16777215.0) << 8u) | (cellId() & 0xFFu);
}

#ifdef SPT_DEPTH_SLABS
//SPT::Slabs::Impl

#endif

// The segment's depth slab (0 without slabs), and the first of its key layers.
int firstLayerOfSlab(Segment segment, out int slab)
{
#ifdef SPT_DEPTH_SLABS
  slab = slabOfDepth(segment.frontDepth);
#else
  slab = 0;
#endif
  return slab * SPT_REPETITIONS_PER_PASS;
}

// A float uniform in [0, 1) from the upper 24 of 32 random bits (exactly representable).
float unitFloat(uint bits)
{
  return float(bits >> 8u) * (1.0 / 16777216.0);
}

// A pseudo-random permutation of [0, n), keyed: a bijection of the enclosing power-of-two range
// (xor, odd multiplication and xorshift are invertible modulo 2^k), walked until it lands in
// range (the idea of Kensler's "Correlated Multi-Jittered Sampling", Pixar 2013).
uint permute(uint index, uint n, uint key)
{
  uint mask = uint(stratumMask);
  uint shift = uint(stratumShift);
  do
  {
    index ^= key;
    index *= 0xe170893du;
    index ^= (index & mask) >> shift;
    index ^= key >> 16u;
    index *= 0x0929eb3fu;
    index ^= (index & mask) >> shift;
    index += key;
    index &= mask;
  } while (index >= n);
  return index;
}

// The inverse of permute(): the index that permute() sends to `place`. Each step of the
// bijection undone in reverse order (the multipliers' inverses modulo 2^32; a xorshift by at
// least half the bits is its own inverse), walked back until it lands in range.
uint unpermute(uint place, uint n, uint key)
{
  uint mask = uint(stratumMask);
  uint shift = uint(stratumShift);
  uint index = place;
  do
  {
    index = (index - key) & mask;
    index ^= index >> shift;
    index = (index * 0xf95384bfu) & mask;
    index ^= (key >> 16u) & mask;
    index ^= index >> shift;
    index = (index * 0x3e779615u) & mask;
    index ^= key & mask;
  } while (index >= n);
  return index;
}

// The keep-or-discard threshold of this fragment for repetition r: uniform in [0, 1), from a
// hash of the pixel, the tetrahedron, r and the seed. Stratified: within each block of
// stratumCount repetitions, every (pixel, tetrahedron) visits each of the stratumCount strata
// once, in its own random order, so its kept count is alpha * stratumCount to within one.
//
// A fragment asks for its repetitions mostly in increasing order, so the hashes are reused:
// one 4D hash gives the random bits of four consecutive repetitions, and the order of the
// strata is hashed once per block. threshold(r) stays a function of r alone, so one
// repetition per pass and many per pass draw the same image.
uint hashGroup = 0xFFFFFFFFu;
uvec4 hashBits;
uint orderBlock = 0xFFFFFFFFu;
uint orderKey;

// The random bits of repetition r.
uint thresholdBits(uint r)
{
  if ((r >> 2u) != hashGroup)
  {
    hashGroup = r >> 2u;
    uvec3 cell = uvec3(uvec2(samplePosition), cellId());
    hashBits = pcg4d(uvec4(cell, hashGroup ^ (uint(seed) * 0x9E3779B9u)));
  }
  return hashBits[r & 3u];
}

// The key of the order of the strata in a block (counted from stratumOrigin).
uint strataOrderKey(uint block)
{
  if (block != orderBlock)
  {
    orderBlock = block;
    uvec3 cell = uvec3(uvec2(samplePosition), cellId());
    orderKey = pcg4d(uvec4(cell, (uint(stratumOrigin) + block) ^ (uint(seed) * 0x85EBCA6Bu))).x;
  }
  return orderKey;
}

// The threshold of a repetition in the given stratum of n, jittered by its random bits.
float stratumThreshold(uint stratum, uint bits, uint n)
{
  return (float(stratum) + unitFloat(bits)) / float(n);
}

// The keep-or-discard threshold of repetition r (see the caches above): independent, or
// jittered in the stratum that this fragment's order of the block gives r.
float threshold(uint r)
{
  uint bits = thresholdBits(r);
  if (stratumCount <= 0)
  {
    return unitFloat(bits);
  }
  uint n = uint(stratumCount);
  uint local = r - uint(stratumOrigin);
  uint block = local / n;
  uint stratum = permute(local - block * n, n, strataOrderKey(block));
  return stratumThreshold(stratum, bits, n);
}

// Whether the repetitions of a group that keep a fragment of this opacity are cheaper to find
// stratum by stratum (keptRepetition()) than by testing every repetition: with stratified
// thresholds, only the strata below alpha can keep it, about alpha * stratumCount per block
// the group touches.
bool fewStrataKeep(float alpha, int first, int passRepetitions)
{
  if (stratumCount <= 0)
  {
    return false;
  }
  int n = stratumCount;
  int local = first - stratumOrigin;
  int blocks = (local + passRepetitions - 1) / n - local / n + 1;
  return 2.0 * alpha * float(n * blocks) < float(passRepetitions);
}

// Whether a stratum may keep a fragment of this opacity. Strata are visited from 0 up; none
// from the first whose threshold cannot be below alpha.
bool strataBelow(uint stratum, float alpha)
{
  uint n = uint(stratumCount);
  return stratum < n && stratumThreshold(stratum, 0u, n) < alpha;
}

// The repetition that visits a stratum of a block in this fragment's order, and whether it
// keeps a fragment of this opacity: exactly threshold(r) < alpha, found from the stratum.
bool keptRepetition(uint block, uint stratum, float alpha, out uint r)
{
  uint n = uint(stratumCount);
  r = uint(stratumOrigin) + block * n + unpermute(stratum, n, strataOrderKey(block));
  return stratumThreshold(stratum, thresholdBits(r), n) < alpha;
}

//SPT::Pass::Impl
