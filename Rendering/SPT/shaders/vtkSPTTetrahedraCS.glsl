// SPT's traversals of the cells that are drawn as points, as a compute pass: a work group visits
// the samples whose centres lie in the squares that hold its cells' projections (those their
// points would cover) and does there what the points' fragments do: the keys pass's
// keysAtSample() (vtkSPTPassKeysFS.glsl) or, with SPT_COMPUTE_COLORS, the colors pass's
// colorsAtSample() (vtkSPTPassColorsFS.glsl). The keys' atomic minima give the same keys in
// any order. What the fragments add by blending (the exact coverage's optical depth terms, the
// colors and the second half's colors) is added here as fixed-point integers (SPT_FIXED_ONE per
// unit), whose sums do not depend on the order either; a full-screen pass then adds them into
// the float targets (vtkSPTComputeSumsFS.glsl).
//
// On a software rasterizer the points' setup and binning run on the application's thread, one
// point at a time; a compute pass runs on all cores.

layout(local_size_x = SPT_COMPUTE_GROUP_SIZE) in;

uniform int firstCell; // the cells [firstCell, firstCell + cellCount) are visited
uniform int cellCount;

#if defined(SPT_WRITE_COVERAGE) || defined(SPT_COMPUTE_COLORS)
layout(r32ui) coherent uniform uimage3D sums; // (term, pixel): fixed point

// Add four terms to the sums of layers [layer, layer + 4) of a sample. A term may be negative
// (a depth slab's control variate shifts colors): its two's complement, added modulo 2^32,
// subtracts it, and the sums are read as signed integers (vtkSPTComputeSumsFS.glsl).
void addToSums(int layer, vec4 terms, ivec2 pixel)
{
  ivec4 fixedTerms = ivec4(round(terms * SPT_FIXED_ONE));
  for (int k = 0; k < 4; ++k)
  {
    if (fixedTerms[k] != 0)
    {
      imageAtomicAdd(sums, ivec3(layer + k, pixel), uint(fixedTerms[k]));
    }
  }
}
#endif

#ifdef SPT_COMPUTE_COLORS
// The points' early depth test: where the frame wrote the farthest survivor's depth
// (vtkSPTSurvivorsFS.glsl) and tests against it, a sample whose survivors all lie in front of
// the cell's nearest vertex gets nothing from the cell, and is skipped before its segment is
// found.
uniform int behindSurvivorsSkipped;
uniform sampler2D farthestSurvivor; // window depth, one texel per sample
#endif

//SPT::FacePlane::Impl
//SPT::PointCell::Impl

// A work group's cells, one per invocation, and the list of their (cell, sample) pairs: cell c
// holds the pairs [samplesEnd[c - 1], samplesEnd[c]) of the group's list, its square's samples
// row by row. The invocations first find their cells, then share out the list: llvmpipe runs
// neighbouring invocations in the lanes of one vector, so that a loop over each cell's own
// samples (0 to 16, 3 on average on the large meshes) runs as long as the longest of its
// lanes, where a share of the list is the same length in every lane.
shared vec4 groupPlanes[SPT_COMPUTE_GROUP_SIZE * 5]; // a cell's four face planes, its scalar plane
shared ivec2 groupFirstSample[SPT_COMPUTE_GROUP_SIZE]; // the lowest corner of a cell's square
shared int groupSquareWidth[SPT_COMPUTE_GROUP_SIZE];  // samples per row of a cell's square
shared int samplesEnd[SPT_COMPUTE_GROUP_SIZE];        // inclusive sums of the squares' samples
#ifdef SPT_COMPUTE_COLORS
shared float groupNearestDepth[SPT_COMPUTE_GROUP_SIZE]; // a cell's nearest vertex, window depth
#endif

// Finds the invocation's cell and publishes it to the group; no samples for an invocation
// past the range, a flat cell, or one outside the viewport.
void shareCell(int local)
{
  int cell = int(gl_GlobalInvocationID.x);
  vec4 planes[4];
  vec4 scalarPlane;
  vec2 low;
  vec2 high;
  float nearest;
  int samples = 0;
  if (cell < cellCount && pointCell(firstCell + cell, planes, scalarPlane, low, high, nearest))
  {
    vec2 windowLow = (low * 0.5 + 0.5) * passSizeInPixels;
    vec2 windowHigh = (high * 0.5 + 0.5) * passSizeInPixels;
    ivec2 first = max(ivec2(ceil(windowLow - 0.5)), ivec2(0));
    ivec2 last = min(ivec2(floor(windowHigh - 0.5)), ivec2(passSizeInPixels) - 1);
    ivec2 size = max(last - first + 1, ivec2(0));
    samples = size.x * size.y;
    for (int k = 0; k < 4; ++k)
    {
      groupPlanes[local * 5 + k] = planes[k];
    }
    groupPlanes[local * 5 + 4] = scalarPlane;
    groupFirstSample[local] = first;
    groupSquareWidth[local] = size.x;
#ifdef SPT_COMPUTE_COLORS
    // The depth the point is rasterized at (vtkSPTTetrahedraPointsVS.glsl), in window depth.
    groupNearestDepth[local] = clamp(nearest, -1.0, 1.0) * 0.5 + 0.5;
#endif
  }
  samplesEnd[local] = samples;
}

// The inclusive prefix sums of the group's sample counts, in place (Hillis and Steele: log2 of
// the group's size steps).
void sumSamples(int local)
{
  for (int offset = 1; offset < SPT_COMPUTE_GROUP_SIZE; offset *= 2)
  {
    int before = local >= offset ? samplesEnd[local - offset] : 0;
    barrier();
    samplesEnd[local] += before;
    barrier();
  }
}

// The group's cell that holds pair `pair` of the list: the first whose samples end after it
// (a binary search over the group's power-of-two size).
int cellOfPair(int pair)
{
  int cell = 0;
  for (int step = SPT_COMPUTE_GROUP_SIZE / 2; step > 0; step /= 2)
  {
    if (samplesEnd[cell + step - 1] <= pair)
    {
      cell += step;
    }
  }
  return cell;
}

// The pass's work at one sample of one cell: what the point's fragment there does.
void visitSample(ivec2 pixel)
{
  samplePosition = vec2(pixel) + 0.5;
  // The random numbers' caches belong to one (sample, cell).
  hashGroup = 0xFFFFFFFFu;
  orderBlock = 0xFFFFFFFFu;
#ifdef SPT_COMPUTE_COLORS
  vec4 sum;
  vec4 secondHalf;
  if (colorsAtSample(sum, secondHalf))
  {
    addToSums(0, sum, pixel);
#ifdef ENSEMBLE_SECOND_HALF
    addToSums(4, secondHalf, pixel);
#endif
  }
#else
  vec4 coverageTerms;
  if (keysAtSample(coverageTerms))
  {
#ifdef SPT_WRITE_COVERAGE
    addToSums(0, coverageTerms, pixel);
#endif
  }
#endif
}

void main()
{
  int local = int(gl_LocalInvocationID.x);
  shareCell(local);
  barrier();
  sumSamples(local);
  int pairs = samplesEnd[SPT_COMPUTE_GROUP_SIZE - 1];
  int groupFirstCell = firstCell + int(gl_WorkGroupID.x) * SPT_COMPUTE_GROUP_SIZE;
  for (int pair = local; pair < pairs; pair += SPT_COMPUTE_GROUP_SIZE)
  {
    int cell = cellOfPair(pair);
    int inSquare = pair - (cell > 0 ? samplesEnd[cell - 1] : 0);
    int width = groupSquareWidth[cell];
    ivec2 pixel = groupFirstSample[cell] + ivec2(inSquare % width, inSquare / width);
#ifdef SPT_COMPUTE_COLORS
    if (behindSurvivorsSkipped != 0 &&
      groupNearestDepth[cell] > texelFetch(farthestSurvivor, pixel, 0).r)
    {
      continue;
    }
#endif
    tetrahedronId = groupFirstCell + cell;
    for (int k = 0; k < 4; ++k)
    {
      facePlaneNDC[k] = groupPlanes[cell * 5 + k];
    }
    scalarPlaneNDC = groupPlanes[cell * 5 + 4];
    visitSample(pixel);
  }
}
