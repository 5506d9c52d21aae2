//VTK::System::Dec
//VTK::Output::Dec

// Turns the ensemble sum into the mean over repetitions and subpixels: premultiplied RGBA,
// whose alpha is the coverage 1 - prod(1 - alpha_i). The caller blends it "over" the scene.
//
// With exactCoverage, each sample's alpha is the exact coverage 1 - exp(-sum(tau_i)) from the
// coverage buffer, and its color is corrected by the control variate meanColor * (A - a):
// the coefficient (the tau-weighted mean color of the sample's segments) does not depend on
// the random numbers and E[a] = A, so the expectation stays exact; what is left of the noise
// is the segments' color differences.
//
// With interpolate, the image has fewer pixels than the viewport (an interactive render's
// sample distance): each viewport pixel is the bilinear interpolation of the four image
// pixels around it, premultiplied.
//
// Where the error target restricted its later repetitions to some tiles (`restricted`), each
// tile's sum holds passCount less the repetitions it missed.
in vec2 texCoord;
uniform sampler2D sumTexture;
uniform sampler2D coverageTexture;   // per sample: (sum(tau_i * color_i), sum(tau_i))
uniform int exactCoverage;
uniform int subpixelLevel;
uniform int interpolate;
uniform float inversePassCount;      // 1 / repetitions
uniform float passCount;
uniform int restricted;
uniform int tileSize;
uniform sampler2D tileMissed;        // per tile: the repetitions it missed

vec4 resolvePixel(ivec2 pixel)
{
  ivec2 first = pixel * subpixelLevel;
  float inverseCount = inversePassCount;
  if (restricted != 0)
  {
    inverseCount = 1.0 / (passCount - texelFetch(tileMissed, pixel / tileSize, 0).r);
  }
  vec4 sum = vec4(0.0);
  for (int j = 0; j < subpixelLevel; ++j)
  {
    for (int i = 0; i < subpixelLevel; ++i)
    {
      vec4 mean = texelFetch(sumTexture, first + ivec2(i, j), 0) * inverseCount;
      if (exactCoverage != 0)
      {
        vec4 coverage = texelFetch(coverageTexture, first + ivec2(i, j), 0);
        float exact = 1.0 - exp(-coverage.a);
        vec3 meanColor = coverage.a > 0.0 ? coverage.rgb / coverage.a : vec3(0.0);
        mean = vec4(mean.rgb + meanColor * (exact - mean.a), exact);
      }
      sum += mean;
    }
  }
  return sum / float(subpixelLevel * subpixelLevel);
}

void main()
{
  ivec2 pixels = textureSize(sumTexture, 0) / subpixelLevel;
  if (interpolate == 0)
  {
    gl_FragData[0] = resolvePixel(ivec2(floor(texCoord * vec2(pixels))));
    return;
  }
  vec2 position = texCoord * vec2(pixels) - 0.5;
  ivec2 low = ivec2(floor(position));
  vec2 weight = position - vec2(low);
  ivec2 last = pixels - 1;
  vec4 p00 = resolvePixel(clamp(low, ivec2(0), last));
  vec4 p10 = resolvePixel(clamp(low + ivec2(1, 0), ivec2(0), last));
  vec4 p01 = resolvePixel(clamp(low + ivec2(0, 1), ivec2(0), last));
  vec4 p11 = resolvePixel(clamp(low + ivec2(1, 1), ivec2(0), last));
  gl_FragData[0] = mix(mix(p00, p10, weight.x), mix(p01, p11, weight.x), weight.y);
}
