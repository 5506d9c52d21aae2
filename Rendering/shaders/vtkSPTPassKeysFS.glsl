// SPT keys pass, for SPT_REPETITIONS_PER_PASS repetitions at once: each repetition that keeps
// the fragment takes the atomic minimum of its depth key, so that after the pass every sample
// holds each repetition's nearest survivor. With SPT_WRITE_COVERAGE the same traversal also
// adds the segment's optical depth terms (additive blending into the coverage buffer);
// otherwise the color mask is off.
layout(r32ui) coherent uniform uimage3D depthKeys; // (repetition in the pass, pixel)

void main()
{
  Segment segment;
  if (!visibleSegment(segment))
  {
    discard;
  }
  vec4 color = preIntegrated(segment);
  uint key = depthKey(segment);
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  for (int r = 0; r < min(repetitionsInGroup, SPT_REPETITIONS_PER_PASS); ++r)
  {
    // A kept fragment behind the nearest survivor so far changes nothing: a plain load
    // spares it the atomic read-modify-write.
    if (threshold(uint(repetition + r)) < color.a &&
      key < imageLoad(depthKeys, ivec3(r, pixel)).r)
    {
      imageAtomicMin(depthKeys, ivec3(r, pixel), key);
    }
  }
#ifdef SPT_WRITE_COVERAGE
  gl_FragData[0] = opticalDepthTerms(color);
#else
  gl_FragData[0] = vec4(0.0);
#endif
}
