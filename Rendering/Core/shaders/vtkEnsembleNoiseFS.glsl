//VTK::System::Dec
//VTK::Output::Dec

// Per pixel, the squared difference between the images of the two independent halves of the
// ensemble, each resolved as vtkEnsembleResolveFS.glsl resolves the whole (the exact coverage and
// its control variate included), summed over the four channels; and whether the pixel is in
// the image's footprint (alpha over 1/255, as the project's image metrics count it). The
// variance of the mean of both halves is a quarter of the expected squared difference. Where
// the error target restricted its later repetitions to some tiles (`restricted`), each tile's
// halves hold halfCount less half of the repetitions it missed.
in vec2 texCoord;
uniform sampler2D sumTexture;        // both halves
uniform sampler2D secondHalfTexture; // the second half alone
uniform sampler2D coverageTexture;   // per sample: (sum(tau_i * color_i), sum(tau_i))
uniform int exactCoverage;
uniform int subpixelLevel;
uniform float halfCount;             // repetitions in each half
uniform int restricted;
uniform int tileSize;
uniform sampler2D tileMissed;        // per tile: the repetitions it missed

void main()
{
  ivec2 pixels = textureSize(sumTexture, 0) / subpixelLevel;
  ivec2 pixel = ivec2(floor(texCoord * vec2(pixels)));
  ivec2 first = pixel * subpixelLevel;
  float perHalf = halfCount;
  if (restricted != 0)
  {
    perHalf -= 0.5 * texelFetch(tileMissed, pixel / tileSize, 0).r;
  }
  float inverseHalfCount = 1.0 / perHalf;
  vec4 difference = vec4(0.0);
  float alpha = 0.0;
  for (int j = 0; j < subpixelLevel; ++j)
  {
    for (int i = 0; i < subpixelLevel; ++i)
    {
      ivec2 sample = first + ivec2(i, j);
      vec4 second = texelFetch(secondHalfTexture, sample, 0);
      vec4 firstHalf = texelFetch(sumTexture, sample, 0) - second;
      vec4 d = (firstHalf - second) * inverseHalfCount;
      float a = 0.5 * (firstHalf.a + second.a) * inverseHalfCount;
      if (exactCoverage != 0)
      {
        vec4 coverage = texelFetch(coverageTexture, sample, 0);
        vec3 meanColor = coverage.a > 0.0 ? coverage.rgb / coverage.a : vec3(0.0);
        d = vec4(d.rgb - meanColor * d.a, 0.0);
        a = 1.0 - exp(-coverage.a);
      }
      difference += d;
      alpha += a;
    }
  }
  float samples = float(subpixelLevel * subpixelLevel);
  difference /= samples;
  gl_FragData[0] = vec4(dot(difference, difference), alpha / samples > 1.0 / 255.0 ? 1.0 : 0.0,
    0.0, 0.0);
}
