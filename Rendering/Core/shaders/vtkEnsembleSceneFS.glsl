//VTK::System::Dec
//VTK::Output::Dec

// The opaque scene that the volume is resolved over, where several processes drew it: the
// color and the depth of the process nearest at each pixel, one texel per pixel.
in vec2 texCoord;
uniform sampler2D sceneColorTexture;
uniform sampler2D sceneDepthTexture;

void main()
{
  ivec2 texel = ivec2(floor(texCoord * vec2(textureSize(sceneColorTexture, 0))));
  gl_FragData[0] = texelFetch(sceneColorTexture, texel, 0);
  gl_FragDepth = texelFetch(sceneDepthTexture, texel, 0).r;
}
