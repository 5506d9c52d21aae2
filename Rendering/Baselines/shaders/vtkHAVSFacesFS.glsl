//VTK::System::Dec
//HAVS::Defines::Dec

// HAVS fragment stage of the sorted faces: insert this fragment into its pixel's k-buffer.

in vec3 positionVCVSOutput;
in float scalarVSOutput;

uniform sampler2D sceneDepthTexture; // depth of the opaque scene, one texel per pixel
uniform int exitIsFrontFacing;       // boundary faces point out; 1 if the view mirrors them
uniform vec2 viewportSize;           // pixels

//HAVS::KBuffer::Impl

void main()
{
  // Opaque geometry hides what lies behind it.
  if (gl_FragCoord.z >= texelFetch(sceneDepthTexture, ivec2(gl_FragCoord.xy), 0).r)
  {
    discard;
  }
  float scalar = scalarVSOutput;
  float crossing = 0.0;
  if (scalar > 1.5)
  {
    // A boundary face, wound to face out of the mesh: the ray leaves the mesh here when it
    // sees the face from behind, and enters it when it sees the face from the front.
    crossing = gl_FrontFacing == (exitIsFrontFacing != 0) ? EXIT_CODE : ENTRY_CODE;
    scalar -= 2.0;
  }
  float distance =
    parallelProjection != 0 ? -positionVCVSOutput.z : length(positionVCVSOutput);
  vec2 fragment = vec2(clamp(scalar, 0.0, 1.0) + crossing, distance);

  vec2 ndc = gl_FragCoord.xy / viewportSize * 2.0 - 1.0;
#ifdef HAVS_CLIPPING_PLANES
  clipRay(ndc);
#endif
  KBUFFER_BEGIN_CRITICAL_SECTION;
  loadKBuffer();
  if (accumulated.a < OPAQUE_ALPHA)
  {
    insertFragment(fragment, modelLengthPerDistance(ndc));
    storeKBuffer();
  }
  KBUFFER_END_CRITICAL_SECTION;
}
