//VTK::System::Dec
//VTK::Output::Dec

// PBVR fragment stage: the particle is opaque; the depth test keeps the nearest particle per
// (sub)pixel, and the mean over the particle sets is the volume's image.

in vec3 colorVSOutput;

uniform sampler2D sceneDepthTexture; // depth of the opaque scene, one texel per pixel
uniform int subpixelLevel;
uniform vec2 pixelScale; // viewport pixels per image pixel: 1 but in interactive renders

void main()
{
  ivec2 scenePixel = ivec2(gl_FragCoord.xy) / subpixelLevel;
  if (pixelScale != vec2(1.0))
  {
    // An image with fewer pixels than the viewport: the viewport pixel at this one's center.
    scenePixel = min(ivec2((vec2(scenePixel) + 0.5) * pixelScale),
      textureSize(sceneDepthTexture, 0) - 1);
  }
  float sceneDepth = texelFetch(sceneDepthTexture, scenePixel, 0).r;
  if (gl_FragCoord.z >= sceneDepth)
  {
    discard;
  }
  gl_FragData[0] = vec4(colorVSOutput, 1.0);
}
