//VTK::System::Dec
//VTK::Output::Dec

// Adds the compute traversal's fixed-point sums into the float targets of the pass (additive
// blending is set by the caller), one fragment per sample (vtkSPTTetrahedraCS.glsl): layers
// 0 to 3 into the first target and, with ENSEMBLE_SECOND_HALF, layers 4 to 7 into the second.
//Volume::Defines::Dec
in vec2 texCoord;
uniform usampler3D sums; // (term, pixel): signed fixed point, SPT_FIXED_ONE per unit

// Four sums of a sample, layers [layer, layer + 4), from signed fixed point to float.
vec4 sumsAt(int layer, ivec2 pixel)
{
  return vec4(int(texelFetch(sums, ivec3(layer, pixel), 0).r),
           int(texelFetch(sums, ivec3(layer + 1, pixel), 0).r),
           int(texelFetch(sums, ivec3(layer + 2, pixel), 0).r),
           int(texelFetch(sums, ivec3(layer + 3, pixel), 0).r)) /
    SPT_FIXED_ONE;
}

void main()
{
  // The quad covers the pass exactly: texCoord finds the sample.
  ivec2 pixel = ivec2(texCoord * vec2(textureSize(sums, 0).yz));
  gl_FragData[0] = sumsAt(0, pixel);
#ifdef ENSEMBLE_SECOND_HALF
  gl_FragData[1] = sumsAt(4, pixel);
#endif
}
