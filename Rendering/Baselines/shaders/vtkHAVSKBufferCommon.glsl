// The image-space half of HAVS (Callahan, Ikits, Comba and Silva 2005): a k-buffer of
// KBUFFER_SIZE - 1 entries per pixel, each a (scalar, distance) pair of a fragment not yet
// composited, next to the color composited so far. Inserting a fragment into a full buffer
// composites the ray segment between the two nearest of the KBUFFER_SIZE candidates (the
// entries and the fragment) front to back, through the pre-integration table, and drops the
// nearer one. The flush pass composites what is left, in depth order.
//
// The buffer lives in KBUFFER_TARGETS RGBA32F textures: target 0 is the premultiplied color,
// the others hold two entries each (scalar, distance, scalar, distance). A fragment reads and
// writes them as inout color attachments (HAVS_FRAMEBUFFER_FETCH) or as images (HAVS_IMAGE),
// inside a pixel_interlock_ordered critical section where HAVS_INTERLOCK is defined: see
// vtkHAVSKBuffer.h for how each mode keeps a pixel's fragments in primitive order.
//
// An entry's scalar s in [0, 1] is stored as a code that also says where the ray crosses the
// mesh's boundary: s inside, s + 2 where it leaves the mesh, s + 4 where it enters it. A
// segment from a fragment where the ray leaves the mesh to one where it enters it again lies
// in a gap outside the mesh and contributes nothing. (Asking for both ends keeps the segments
// behind internal faces that look like boundary faces, as the two triangulations of a quad
// shared by two hexahedra split differently: the ray leaves one cell and enters the next at
// the same distance, in either order.)

const float EMPTY_DISTANCE = 1.0e30;  // distance of an empty entry
const float EXIT_CODE = 2.0;          // added to the scalar where the ray leaves the mesh
const float ENTRY_CODE = 4.0;         // added to the scalar where the ray enters the mesh
const float OPAQUE_ALPHA = 0.998046875; // 1 - 1/512: nothing behind changes an 8-bit pixel

uniform sampler3D preIntegrationTable; // (front scalar, back scalar, sqrt(thickness)) -> RGBA
uniform vec3 tableTexelScale;          // maps [0, 1] onto the centers of the first and last texels
uniform vec3 tableTexelOffset;
uniform float thicknessToTable;        // 1 / largest thickness in the table, model units
uniform mat3 VCMCLinear;               // view -> model, for lengths in the data's coordinates
uniform mat4 DCVCMatrix;               // clip -> view, for the ray through a pixel
uniform int parallelProjection;

#ifdef HAVS_FRAMEBUFFER_FETCH
#define KBUFFER_TARGET(n) layout(location = n) inout vec4
#define KBUFFER_READ(target) (target)
#define KBUFFER_WRITE(target, value) target = (value)
#else
#define KBUFFER_TARGET(n) layout(rgba32f) coherent uniform image2D
#define KBUFFER_READ(target) imageLoad(target, ivec2(gl_FragCoord.xy))
#define KBUFFER_WRITE(target, value) imageStore(target, ivec2(gl_FragCoord.xy), value)
#endif
KBUFFER_TARGET(0) kbufferTarget0;
KBUFFER_TARGET(1) kbufferTarget1;
#if KBUFFER_TARGETS > 2
KBUFFER_TARGET(2) kbufferTarget2;
#endif
#if KBUFFER_TARGETS > 3
KBUFFER_TARGET(3) kbufferTarget3;
#endif

vec4 accumulated;
vec2 entries[KBUFFER_SIZE - 1];

// The first (second == 0) or second (scalar, distance) entry of a target's pair of them.
vec2 entryOf(vec4 pair, int second)
{
  return second == 0 ? pair.xy : pair.zw;
}

// Reads the pixel's k-buffer: the composited color into `accumulated`, the entries into
// entries[].
void loadKBuffer()
{
  accumulated = KBUFFER_READ(kbufferTarget0);
  vec4 pairs[3];
  pairs[0] = KBUFFER_READ(kbufferTarget1);
#if KBUFFER_TARGETS > 2
  pairs[1] = KBUFFER_READ(kbufferTarget2);
#endif
#if KBUFFER_TARGETS > 3
  pairs[2] = KBUFFER_READ(kbufferTarget3);
#endif
  for (int i = 0; i < KBUFFER_SIZE - 1; ++i)
  {
    entries[i] = entryOf(pairs[i / 2], i % 2);
  }
}

// Entries `first` and `first + 1` as one target's texel; past the last entry, an empty one.
vec4 pairOf(int first)
{
  vec2 second = first + 1 < KBUFFER_SIZE - 1 ? entries[first + 1] : vec2(0.0, EMPTY_DISTANCE);
  return vec4(entries[first], second);
}

// Writes the pixel's k-buffer back: `accumulated` and the entries, two per target.
void storeKBuffer()
{
  KBUFFER_WRITE(kbufferTarget0, accumulated);
  KBUFFER_WRITE(kbufferTarget1, pairOf(0));
#if KBUFFER_TARGETS > 2
  KBUFFER_WRITE(kbufferTarget2, pairOf(2));
#endif
#if KBUFFER_TARGETS > 3
  KBUFFER_WRITE(kbufferTarget3, pairOf(4));
#endif
}

// The ray through the point of normalized device coordinates ndc, as a unit vector in view
// coordinates.
vec3 rayDirectionVC(vec2 ndc)
{
  if (parallelProjection != 0)
  {
    return vec3(0.0, 0.0, -1.0);
  }
  // The eye is the origin of view coordinates: the pixel's point on the near plane gives the
  // direction. (The far plane's point is not used: when the far plane is many times farther
  // than the near one, as VTK's minimum clipping thickness makes it for tiny data, its w
  // cancels out in float.)
  vec4 nearVC = DCVCMatrix * vec4(ndc, -1.0, 1.0);
  return normalize(nearVC.xyz / nearVC.w);
}

// Model length of a unit of distance along the ray through ndc.
float modelLengthPerDistance(vec2 ndc)
{
  return length(VCMCLinear * rayDirectionVC(ndc));
}

#ifdef HAVS_CLIPPING_PLANES
uniform vec4 clippingPlanes[6]; // the mapper's clipping planes (view coordinates): a point is
uniform int clippingPlaneCount; // kept where dot(plane, (x, 1)) >= 0 for each of them

// The distances along the pixel's ray between which every clipping plane keeps it (clipRay()).
vec2 keptDistances = vec2(0.0, EMPTY_DISTANCE);

// Where the clipping planes keep the ray through ndc, in the distances that the entries hold:
// from the eye along the unit direction, or (parallel) from the view plane along -z.
void clipRay(vec2 ndc)
{
  vec3 direction = rayDirectionVC(ndc);
  vec3 origin = vec3(0.0);
  if (parallelProjection != 0)
  {
    vec4 nearVC = DCVCMatrix * vec4(ndc, -1.0, 1.0);
    origin = vec3(nearVC.xy / nearVC.w, 0.0);
  }
  for (int k = 0; k < clippingPlaneCount; ++k)
  {
    float atOrigin = dot(clippingPlanes[k], vec4(origin, 1.0));
    float slope = dot(clippingPlanes[k].xyz, direction);
    if (slope > 0.0)
    {
      keptDistances.x = max(keptDistances.x, -atOrigin / slope);
    }
    else if (slope < 0.0)
    {
      keptDistances.y = min(keptDistances.y, -atOrigin / slope);
    }
    else if (atOrigin < 0.0)
    {
      keptDistances = vec2(EMPTY_DISTANCE, 0.0);
    }
  }
}
#endif

// Front-to-back compositing of the segment from `front` to `back` (Engel, Kraus and Ertl
// 2001: the table holds the premultiplied color and opacity of a linear segment). With
// clipping planes, of the part of it that they keep: the scalar is linear along the segment,
// so the cut ends' scalars and the shortened thickness are those of the cut segment.
void compositeSegment(vec2 front, vec2 back, float lengthScale)
{
  float frontCrossing = floor(front.x * 0.5); // 0 inside, 1 exit, 2 entry
  float backCrossing = floor(back.x * 0.5);
  if (back.y >= EMPTY_DISTANCE || (frontCrossing == 1.0 && backCrossing == 2.0))
  {
    return; // nothing behind, or a gap outside the mesh
  }
  float frontScalar = front.x - 2.0 * frontCrossing;
  float backScalar = back.x - 2.0 * backCrossing;
#ifdef HAVS_CLIPPING_PLANES
  float from = max(front.y, keptDistances.x);
  float to = min(back.y, keptDistances.y);
  if (from >= to)
  {
    return;
  }
  float perDistance = (backScalar - frontScalar) / (back.y - front.y);
  backScalar = frontScalar + (to - front.y) * perDistance;
  frontScalar += (from - front.y) * perDistance;
  front.y = from;
  back.y = to;
#endif
  float thickness = max(back.y - front.y, 0.0) * lengthScale;
  vec3 coordinate = vec3(clamp(frontScalar, 0.0, 1.0), clamp(backScalar, 0.0, 1.0),
    sqrt(min(thickness * thicknessToTable, 1.0)));
  vec4 segment = texture(preIntegrationTable, coordinate * tableTexelScale + tableTexelOffset);
  accumulated += (1.0 - accumulated.a) * segment;
}

// Insert one fragment: fill an empty entry, or composite the nearest pair and drop its front.
void insertFragment(vec2 fragment, float lengthScale)
{
  for (int i = 0; i < KBUFFER_SIZE - 1; ++i)
  {
    if (entries[i].y >= EMPTY_DISTANCE)
    {
      entries[i] = fragment;
      return;
    }
  }
  // Candidates 0 .. KBUFFER_SIZE - 2 are the entries, KBUFFER_SIZE - 1 the fragment.
  int nearest = KBUFFER_SIZE - 1;
  vec2 nearestEntry = fragment;
  for (int i = 0; i < KBUFFER_SIZE - 1; ++i)
  {
    if (entries[i].y < nearestEntry.y)
    {
      nearest = i;
      nearestEntry = entries[i];
    }
  }
  vec2 next = vec2(0.0, EMPTY_DISTANCE);
  for (int i = 0; i < KBUFFER_SIZE - 1; ++i)
  {
    if (i != nearest && entries[i].y < next.y)
    {
      next = entries[i];
    }
  }
  if (nearest != KBUFFER_SIZE - 1 && fragment.y < next.y)
  {
    next = fragment;
  }
  compositeSegment(nearestEntry, next, lengthScale);
  if (nearest != KBUFFER_SIZE - 1)
  {
    entries[nearest] = fragment;
  }
}

// Composite the entries left after the last face, in depth order, and empty the buffer.
void flushKBuffer(float lengthScale)
{
  for (int i = 0; i < KBUFFER_SIZE - 1; ++i)
  {
    for (int j = i + 1; j < KBUFFER_SIZE - 1; ++j)
    {
      if (entries[j].y < entries[i].y)
      {
        vec2 swap = entries[i];
        entries[i] = entries[j];
        entries[j] = swap;
      }
    }
  }
  for (int i = 0; i + 1 < KBUFFER_SIZE - 1; ++i)
  {
    compositeSegment(entries[i], entries[i + 1], lengthScale);
  }
  for (int i = 0; i < KBUFFER_SIZE - 1; ++i)
  {
    entries[i] = vec2(0.0, EMPTY_DISTANCE);
  }
}
