// SPT single pass, the paper's: one repetition, the fragment kept with probability alpha and
// written opaque with the depth test, so each sample keeps its nearest survivor. The depth is
// the segment's front, which the fragment writes: a cell is rasterized at its nearest vertex's
// depth (a clipped cell at its exit faces').
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
  gl_FragDepth = segment.frontDepth;
}
