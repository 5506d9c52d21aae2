// SPT colors pass, after the keys pass of the same repetitions: the fragment adds to the
// ensemble's sum (additive blending)
// - with SPT_VISIBILITY_WEIGHTED (the visibility estimator), its premultiplied color and
//   opacity once for each repetition whose nearest survivor is not in front of it. It is
//   visible in a repetition with probability prod(1 - alpha_j) over the segments j in front
//   of it, so the mean is front-to-back compositing in expectation, and every segment in
//   front of the survivor contributes what it would composite;
// - otherwise (the survivor estimator), its color written opaque once for each repetition
//   whose survivor it is.
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
  int count = 0;
  for (int r = 0; r < min(repetitionsInGroup, SPT_REPETITIONS_PER_PASS); ++r)
  {
#ifdef SPT_VISIBILITY_WEIGHTED
    count += key <= imageLoad(depthKeys, ivec3(r, pixel)).r ? 1 : 0;
#else
    if (threshold(uint(repetition + r)) < color.a)
    {
      count += imageLoad(depthKeys, ivec3(r, pixel)).r == key ? 1 : 0;
    }
#endif
  }
  if (count == 0)
  {
    discard;
  }
#ifdef SPT_VISIBILITY_WEIGHTED
  gl_FragData[0] = float(count) * color;
#else
  gl_FragData[0] = float(count) * vec4(color.rgb / color.a, 1.0);
#endif
}
