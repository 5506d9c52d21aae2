// SPT colors pass of the visibility estimator for one repetition, after the single pass has
// left that repetition's nearest survivor in the depth buffer (the depth test finds it: no
// keys). Every fragment not behind the survivor adds its premultiplied color and opacity
// (additive blending): it is in front of every kept segment with probability
// prod(1 - alpha_j) over the segments j in front of it, as in vtkSPTPassColorsFS.glsl.
// With SPT_WRITE_COVERAGE the traversal also adds every segment's optical depth terms to the
// second draw buffer: it visits every fragment anyway.
uniform sampler2D survivorDepth; // the nearest survivor's front, one texel per sample

void main()
{
  Segment segment;
  if (!visibleSegment(segment))
  {
    discard;
  }
  // Compared in the 24 bits of a depth key, as the keys pass compares them.
  float survivor = texelFetch(survivorDepth, ivec2(gl_FragCoord.xy), 0).r;
  bool visible = uint(segment.frontDepth * 16777215.0) <= uint(survivor * 16777215.0);
#ifdef SPT_WRITE_COVERAGE
  vec4 color = preIntegrated(segment);
  gl_FragData[0] = visible ? color : vec4(0.0);
  gl_FragData[1] = opticalDepthTerms(color);
#else
  if (!visible)
  {
    discard;
  }
  gl_FragData[0] = preIntegrated(segment);
#endif
}
