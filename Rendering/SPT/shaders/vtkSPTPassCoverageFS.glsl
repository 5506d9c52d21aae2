// SPT coverage pass, once per image where the keys pass does not carry it: every segment adds
// its optical depth terms (additive blending), with nothing random and no depth test.
void main()
{
  Segment segment;
  if (!visibleSegment(segment))
  {
    discard;
  }
  vec4 color = preIntegrated(segment);
  if (color.a <= 0.0)
  {
    discard;
  }
  gl_FragData[0] = opticalDepthTerms(color);
}
