// SPT single pass, the paper's: one repetition, the fragment kept with probability alpha and
// written opaque with the depth test, so each sample keeps its nearest survivor. The depth is
// the segment's front: the rasterized one, but for the exit faces of clipped cells and for
// cells drawn as points, whose fragments write it (and so only then lose early depth tests).
void main()
{
  Segment segment;
  if (!visibleSegment(segment))
  {
    discard;
  }
  vec4 color = preIntegrated(segment);
  if (threshold(uint(repetition)) >= color.a)
  {
    discard;
  }
  // Kept with probability alpha, so the premultiplied color is divided by alpha.
  gl_FragData[0] = vec4(color.rgb / color.a, 1.0);
#if defined(SPT_CLIPPED_CELLS) || defined(SPT_POINT_SPRITES)
  gl_FragDepth = segment.frontDepth;
#endif
}
