//VTK::System::Dec
//VTK::Output::Dec

// PBVR fragment stage: the particle is opaque; the depth test keeps the nearest particle per
// (sub)pixel, and the mean over the particle sets is the volume's image.

in vec3 colorVSOutput;

uniform sampler2D sceneDepthTexture; // depth of the opaque scene, one texel per pixel
uniform int subpixelLevel;

void main()
{
  float sceneDepth = texelFetch(sceneDepthTexture, ivec2(gl_FragCoord.xy) / subpixelLevel, 0).r;
  if (gl_FragCoord.z >= sceneDepth)
  {
    discard;
  }
  gl_FragData[0] = vec4(colorVSOutput, 1.0);
}
