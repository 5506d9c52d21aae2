// SPT's traversals of the cells that are drawn as points, as a compute pass: one invocation per
// cell visits the samples whose centres lie in the square that holds the cell's projection
// (those its point would cover) and does there what the point's fragments do: the keys pass's
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

void main()
{
  int cell = int(gl_GlobalInvocationID.x);
  vec2 low;
  vec2 high;
  float nearest;
  if (cell >= cellCount ||
    !pointCell(firstCell + cell, facePlaneNDC, scalarPlaneNDC, low, high, nearest))
  {
    return;
  }
  tetrahedronId = firstCell + cell;
  vec2 windowLow = (low * 0.5 + 0.5) * passSizeInPixels;
  vec2 windowHigh = (high * 0.5 + 0.5) * passSizeInPixels;
  ivec2 first = max(ivec2(ceil(windowLow - 0.5)), ivec2(0));
  ivec2 last = min(ivec2(floor(windowHigh - 0.5)), ivec2(passSizeInPixels) - 1);
#ifdef SPT_COMPUTE_COLORS
  // The depth the point is rasterized at (vtkSPTTetrahedraPointsVS.glsl), in window depth.
  float nearestDepth = clamp(nearest, -1.0, 1.0) * 0.5 + 0.5;
#endif
  for (int y = first.y; y <= last.y; ++y)
  {
    for (int x = first.x; x <= last.x; ++x)
    {
      samplePosition = vec2(x, y) + 0.5;
      // The random numbers' caches belong to one (sample, cell).
      hashGroup = 0xFFFFFFFFu;
      orderBlock = 0xFFFFFFFFu;
#ifdef SPT_COMPUTE_COLORS
      if (behindSurvivorsSkipped != 0 &&
        nearestDepth > texelFetch(farthestSurvivor, ivec2(x, y), 0).r)
      {
        continue;
      }
      vec4 sum;
      vec4 secondHalf;
      if (colorsAtSample(sum, secondHalf))
      {
        addToSums(0, sum, ivec2(x, y));
#ifdef SPT_SECOND_HALF
        addToSums(4, secondHalf, ivec2(x, y));
#endif
      }
#else
      vec4 coverageTerms;
      if (keysAtSample(coverageTerms))
      {
#ifdef SPT_WRITE_COVERAGE
        addToSums(0, coverageTerms, ivec2(x, y));
#endif
      }
#endif
    }
  }
}
