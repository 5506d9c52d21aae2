// SPT keys pass, for up to SPT_REPETITIONS_PER_PASS repetitions at once: each repetition that keeps
// the fragment takes the atomic minimum of its depth key, so that after the pass every sample
// holds each repetition's nearest survivor. With SPT_WRITE_COVERAGE the same traversal also
// adds the segment's optical depth terms (additive blending into the coverage buffer);
// otherwise the color mask is off. With SPT_DEPTH_SLABS, the fragment's slab's layers hold
// its keys, and with the coverage it adds its optical depth terms to its slab's.
layout(r32ui) coherent uniform uimage3D depthKeys; // (repetition in the pass, pixel)
// Where an error target draws only into some tiles, their stencil rejects the other fragments
// before they are shaded (the depth test is off in this pass).
#ifndef SPT_COMPUTE
layout(early_fragment_tests) in;
#endif

// Key layer `layer` (a repetition of the pass) keeps the fragment. A kept fragment behind the
// nearest survivor so far changes nothing: a plain load spares it the atomic read-modify-write.
void keep(int layer, uint key, ivec2 pixel)
{
  if (key < imageLoad(depthKeys, ivec3(layer, pixel)).r)
  {
    imageAtomicMin(depthKeys, ivec3(layer, pixel), key);
  }
}

// The group's repetitions that keep the fragment, found from the strata below its opacity:
// the same repetitions as testing each one, at a cost that follows alpha, not the group.
void keepByStrata(float alpha, uint key, ivec2 pixel, int base, int passRepetitions)
{
  uint first = uint(repetition);
  uint n = uint(stratumCount);
  uint local = first - uint(stratumOrigin);
  for (uint block = local / n; block * n < local + uint(passRepetitions); ++block)
  {
    for (uint stratum = 0u; strataBelow(stratum, alpha); ++stratum)
    {
      uint r;
      if (keptRepetition(block, stratum, alpha, r) && r - first < uint(passRepetitions))
      {
        keep(base + int(r - first), key, pixel);
      }
    }
  }
}

// The pass's work for this fragment's (or the compute traversal's) sample: the keys of the
// repetitions that keep the segment, and its optical depth terms for the exact coverage. False
// when the sample's ray misses the visible part of the cell.
bool keysAtSample(out vec4 coverageTerms)
{
  Segment segment;
  if (!visibleSegment(segment))
  {
    return false;
  }
  vec4 color = preIntegrated(segment);
  uint key = depthKey(segment);
  ivec2 pixel = ivec2(samplePosition);
  int passRepetitions = min(repetitionsInGroup, SPT_REPETITIONS_PER_PASS);
  int slab;
  int base = firstLayerOfSlab(segment, slab);
  if (fewStrataKeep(color.a, repetition, passRepetitions))
  {
    keepByStrata(color.a, key, pixel, base, passRepetitions);
  }
  else
  {
    for (int r = 0; r < passRepetitions; ++r)
    {
      if (threshold(uint(repetition + r)) < color.a)
      {
        keep(base + r, key, pixel);
      }
    }
  }
#ifdef SPT_WRITE_COVERAGE
  coverageTerms = opticalDepthTerms(color);
#ifdef SPT_DEPTH_SLABS
  addSlabTerms(slab, coverageTerms, pixel);
#endif
#else
  coverageTerms = vec4(0.0);
#endif
  return true;
}

#ifndef SPT_COMPUTE
void main()
{
  vec4 coverageTerms;
  if (!keysAtSample(coverageTerms))
  {
    discard;
  }
#ifdef SPT_WRITE_COVERAGE
  gl_FragData[0] = coverageTerms;
#else
  gl_FragData[0] = vec4(0.0);
#endif
}
#endif
