//VTK::System::Dec
//VTK::Output::Dec

// Turns the ensemble sum into the mean over repetitions and subpixels: premultiplied RGBA,
// whose alpha is the coverage 1 - prod(1 - alpha_i). The caller blends it "over" the scene.
in vec2 texCoord;
uniform sampler2D sumTexture;
uniform int subpixelLevel;
uniform float inverseSampleCount; // 1 / (repetitions * subpixelLevel^2)

void main()
{
  ivec2 pixels = textureSize(sumTexture, 0) / subpixelLevel;
  ivec2 first = ivec2(floor(texCoord * vec2(pixels))) * subpixelLevel;
  vec4 sum = vec4(0.0);
  for (int j = 0; j < subpixelLevel; ++j)
  {
    for (int i = 0; i < subpixelLevel; ++i)
    {
      sum += texelFetch(sumTexture, first + ivec2(i, j), 0);
    }
  }
  gl_FragData[0] = sum * inverseSampleCount;
}
