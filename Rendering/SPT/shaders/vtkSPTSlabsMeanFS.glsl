//VTK::System::Dec
#extension GL_ARB_shader_image_load_store : require
#extension GL_ARB_shader_bit_encoding : require
//VTK::Output::Dec
//SPT::Slabs::Dec

// Once per image with depth slabs, after the key traversal that adds up the coverage and the
// slabs' sums (vtkSPTDepthSlabs.glsl), per sample:
// - each slab's weight T_k and color shift m - c_k, for the color traversals, in place of its
//   sums;
// - the mean color m that the resolve corrects the sample with. The coverage holds
//   (sum(tau_i * color_i), sum(tau_i)); blended with (destination alpha, zero) for color and
//   (zero, one) for alpha, this pass makes its color m * sum(tau_i), so that the resolve,
//   which divides by sum(tau_i), finds m. On the ranks of a parallel frame, whose slab sums
//   are the whole image's, the coverage of each rank's piece takes the same m, and so does
//   their sum.

in vec2 texCoord; // the quad covers the pass: pixel centers
uniform vec2 passSize; // pixels

//SPT::Slabs::Impl

// 1 - exp(-tau), accurate for small tau too.
float coverageOf(float tau)
{
  return tau < 1.0e-3 ? tau * (1.0 - 0.5 * tau) : 1.0 - exp(-tau);
}

void main()
{
  ivec2 pixel = ivec2(floor(texCoord * passSize));
  float inFront[SPT_DEPTH_SLABS];
  vec3 slabMean[SPT_DEPTH_SLABS];
  bool empty[SPT_DEPTH_SLABS];
  float tauInFront = 0.0;
  vec3 weighted = vec3(0.0); // sum_k T_k c_k A_k
  for (int k = 0; k < SPT_DEPTH_SLABS; ++k)
  {
    int layer = SPT_SLAB_TERMS * k;
    float tau = float(imageLoad(slabSums, ivec3(layer, pixel)).r) / float(SPT_SLAB_FIXED_ONE);
    vec3 tauColor = vec3(imageLoad(slabSums, ivec3(layer + 1, pixel)).r,
                      imageLoad(slabSums, ivec3(layer + 2, pixel)).r,
                      imageLoad(slabSums, ivec3(layer + 3, pixel)).r) /
      float(SPT_SLAB_FIXED_ONE);
    empty[k] = tau <= 0.0;
    inFront[k] = exp(-tauInFront);
    slabMean[k] = tau > 0.0 ? tauColor / tau : vec3(0.0);
    weighted += inFront[k] * slabMean[k] * coverageOf(tau);
    tauInFront += tau;
  }
  float coverage = coverageOf(tauInFront);
  vec3 sampleMean = coverage > 0.0 ? weighted / coverage : vec3(0.0);
  for (int k = 0; k < SPT_DEPTH_SLABS; ++k)
  {
    uvec4 control = floatBitsToUint(
      vec4(empty[k] ? -1.0 : inFront[k], sampleMean - slabMean[k]));
    for (int term = 0; term < SPT_SLAB_TERMS; ++term)
    {
      imageStore(slabSums, ivec3(SPT_SLAB_TERMS * k + term, pixel), uvec4(control[term]));
    }
  }
  gl_FragData[0] = vec4(sampleMean, 0.0);
}
