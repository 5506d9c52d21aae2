//VTK::System::Dec
//VTK::Output::Dec

// Marks the pixels that the ensemble covers in the depth buffer, at the near plane, and writes
// no color: a compositor that keeps each pixel of the nearest process (IceT's z-buffer mode,
// which also takes far pixels for empty ones) then keeps the resolved volume's pixels.
in vec2 texCoord;
uniform sampler2D sumTexture;
uniform int subpixelLevel;

void main()
{
  ivec2 pixels = textureSize(sumTexture, 0) / subpixelLevel;
  ivec2 first = ivec2(floor(texCoord * vec2(pixels))) * subpixelLevel;
  float covered = 0.0;
  for (int j = 0; j < subpixelLevel; ++j)
  {
    for (int i = 0; i < subpixelLevel; ++i)
    {
      covered = max(covered, texelFetch(sumTexture, first + ivec2(i, j), 0).a);
    }
  }
  if (covered <= 0.0)
  {
    discard;
  }
  gl_FragData[0] = vec4(0.0);
  gl_FragDepth = 0.0;
}
