//VTK::System::Dec
//SPT::Extensions::Dec
//VTK::Output::Dec

// SPT fragment stage (Sakamoto, Kawamura, Kuwano and Koyamada 2009): look up the
// pre-integrated color and opacity of this pixel's ray segment through the tetrahedron, keep
// the fragment with probability alpha and write it opaque. With the depth test, each pass
// keeps the nearest surviving segment per pixel; the mean over passes is front-to-back
// compositing in expectation, with nothing sorted.

noperspective in vec4 frontVCOverW;
noperspective in vec4 backVCOverW;
noperspective in vec2 scalarsOverW;
flat in int tetrahedronId;

uniform sampler3D preIntegrationTable; // (front scalar, back scalar, sqrt(thickness)) -> RGBA
uniform vec3 tableTexelScale;          // maps [0, 1] onto the centers of the first and last texels
uniform vec3 tableTexelOffset;
uniform float thicknessToTable;        // 1 / largest thickness in the table, model units
uniform mat3 VCMCLinear;               // view -> model, for lengths: the unit distance of the
                                       // opacity is a length in the data's own coordinates

uniform sampler2D sceneDepthTexture;   // depth of the opaque scene, one texel per pixel
uniform int subpixelLevel;
uniform vec2 passSizeInPixels;
uniform mat4 DCVCMatrix;               // clip -> view, for the scene depth

uniform int repetition; // first repetition of this pass; bit patterns of unsigned values:
uniform int seed;       // VTK sets int uniforms only
uniform int stratumCount;  // stratified sampling: the repetitions from stratumOrigin on form
uniform int stratumOrigin; // blocks of stratumCount; 0 for independent sampling
uniform int stratumMask;   // 2^k - 1 >= stratumCount - 1, and about k / 2, for permute()
uniform int stratumShift;
uniform int repetitionsInGroup; // of the SPT_REPETITIONS_PER_PASS, how many this pass draws

// How this pass writes: SPT_PASS_SINGLE (one repetition, the fragment written opaque with the
// depth test), or, for SPT_REPETITIONS_PER_PASS repetitions at once, SPT_PASS_KEYS (each kept
// fragment takes the per-repetition minimum of its depth key) then SPT_PASS_COLORS (the
// fragment adds its color once for each repetition whose minimum it holds, or, with
// SPT_VISIBILITY_WEIGHTED, for each repetition whose minimum is not in front of it). Apart
// from these, SPT_PASS_COVERAGE adds every fragment's optical depth and color, once.
//SPT::Pass::Dec
#if !defined(SPT_PASS_SINGLE) && !defined(SPT_PASS_COVERAGE)
layout(r32ui) coherent uniform uimage3D depthKeys; // (pixel, repetition in the pass)
#endif

//SPT::Random::Impl

float unitFloat(uint bits)
{
  return float(bits >> 8u) * (1.0 / 16777216.0);
}

// A pseudo-random permutation of [0, n), keyed: a bijection of the enclosing power-of-two range
// (xor, odd multiplication and xorshift are invertible modulo 2^k), walked until it lands in
// range (the idea of Kensler's "Correlated Multi-Jittered Sampling", Pixar 2013).
uint permute(uint index, uint n, uint key)
{
  uint mask = uint(stratumMask);
  uint shift = uint(stratumShift);
  do
  {
    index ^= key;
    index *= 0xe170893du;
    index ^= (index & mask) >> shift;
    index ^= key >> 16u;
    index *= 0x0929eb3fu;
    index ^= (index & mask) >> shift;
    index += key;
    index &= mask;
  } while (index >= n);
  return index;
}

// The keep-or-discard threshold of this fragment for repetition r: uniform in [0, 1), from a
// hash of the pixel, the tetrahedron, r and the seed. Stratified: within each block of
// stratumCount repetitions, every (pixel, tetrahedron) visits each of the stratumCount strata
// once, in its own random order, so its kept count is alpha * stratumCount to within one.
//
// A fragment asks for its repetitions in increasing order, so the hashes are reused: one 4D
// hash gives the random bits of four consecutive repetitions, and the order of the strata
// is hashed once per block. threshold(r) stays a function of r alone, so one repetition per
// pass and many per pass draw the same image.
uint hashGroup = 0xFFFFFFFFu;
uvec4 hashBits;
uint orderBlock = 0xFFFFFFFFu;
uint orderKey;

float threshold(uint r)
{
  uvec3 cell = uvec3(uvec2(gl_FragCoord.xy), uint(tetrahedronId));
  if ((r >> 2u) != hashGroup)
  {
    hashGroup = r >> 2u;
    hashBits = pcg4d(uvec4(cell, hashGroup ^ (uint(seed) * 0x9E3779B9u)));
  }
  uint bits = hashBits[r & 3u];
  if (stratumCount <= 0)
  {
    return unitFloat(bits);
  }
  uint n = uint(stratumCount);
  uint local = r - uint(stratumOrigin);
  uint block = local / n;
  if (block != orderBlock)
  {
    orderBlock = block;
    orderKey = pcg4d(uvec4(cell, (uint(stratumOrigin) + block) ^ (uint(seed) * 0x85EBCA6Bu))).x;
  }
  uint stratum = permute(local - block * n, n, orderKey);
  return (float(stratum) + unitFloat(bits)) / float(n);
}

void main()
{
  vec3 frontVC = frontVCOverW.xyz / frontVCOverW.w;
  vec3 backVC = backVCOverW.xyz / backVCOverW.w;
  float frontScalar = scalarsOverW.x / frontVCOverW.w;
  float backScalar = scalarsOverW.y / backVCOverW.w;

  // Opaque geometry hides what lies behind it and cuts a segment that it passes through.
  float sceneDepth = texelFetch(sceneDepthTexture, ivec2(gl_FragCoord.xy) / subpixelLevel, 0).r;
  if (gl_FragCoord.z >= sceneDepth)
  {
    discard;
  }
  if (sceneDepth < 1.0 && frontVC.z > backVC.z)
  {
    vec4 sceneDC = vec4(gl_FragCoord.xy / passSizeInPixels * 2.0 - 1.0, sceneDepth * 2.0 - 1.0, 1.0);
    vec4 sceneVC = DCVCMatrix * sceneDC;
    float sceneZ = sceneVC.z / sceneVC.w;
    if (sceneZ > backVC.z)
    {
      float t = clamp((frontVC.z - sceneZ) / (frontVC.z - backVC.z), 0.0, 1.0);
      backVC = mix(frontVC, backVC, t);
      backScalar = mix(frontScalar, backScalar, t);
    }
  }

  float thickness = length(VCMCLinear * (backVC - frontVC));
  vec3 coordinate = vec3(clamp(frontScalar, 0.0, 1.0), clamp(backScalar, 0.0, 1.0),
    sqrt(min(thickness * thicknessToTable, 1.0)));
  vec4 segment = texture(preIntegrationTable, coordinate * tableTexelScale + tableTexelOffset);

#if defined(SPT_PASS_COVERAGE)
  // The exact coverage of the sample is 1 - exp(-sum(tau)); the tau-weighted mean of the
  // segments' colors is the coefficient of the resolve's control variate.
  if (segment.a <= 0.0)
  {
    discard;
  }
  float tau = -log(1.0 - min(segment.a, 0.99999994));
  gl_FragData[0] = vec4(segment.rgb * (tau / segment.a), tau);
#elif defined(SPT_PASS_SINGLE)
  if (threshold(uint(repetition)) >= segment.a)
  {
    discard;
  }
  // Kept with probability alpha, so the premultiplied color is divided by alpha.
  gl_FragData[0] = vec4(segment.rgb / segment.a, 1.0);
#else
  // The depth key: the depth in 24 bits (as a depth buffer holds it), then 8 bits of the
  // tetrahedron's id, so that two fragments at one depth do not both win.
  uint depthKey = (uint(clamp(gl_FragCoord.z, 0.0, 1.0) * 16777215.0) << 8u) |
    (uint(tetrahedronId) & 0xFFu);
  ivec2 pixel = ivec2(gl_FragCoord.xy);
#if defined(SPT_PASS_COLORS) && defined(SPT_VISIBILITY_WEIGHTED)
  // The visibility estimator: the fragment adds its premultiplied color and opacity once for
  // each repetition whose nearest survivor is not in front of it. It is visible in a
  // repetition with the probability prod(1 - alpha_j) over the segments j in front of it, so
  // the mean is front-to-back compositing in expectation, as with the survivor alone, but
  // every segment in front of the survivor contributes what it would composite.
  int visible = 0;
  for (int r = 0; r < min(repetitionsInGroup, SPT_REPETITIONS_PER_PASS); ++r)
  {
    visible += depthKey <= imageLoad(depthKeys, ivec3(r, pixel)).r ? 1 : 0;
  }
  if (visible == 0)
  {
    discard;
  }
  gl_FragData[0] = float(visible) * segment;
#else
  int wins = 0;
  for (int r = 0; r < min(repetitionsInGroup, SPT_REPETITIONS_PER_PASS); ++r)
  {
    if (threshold(uint(repetition + r)) < segment.a)
    {
#ifdef SPT_PASS_KEYS
      imageAtomicMin(depthKeys, ivec3(r, pixel), depthKey);
#else
      wins += imageLoad(depthKeys, ivec3(r, pixel)).r == depthKey ? 1 : 0;
#endif
    }
  }
  // The key pass writes no color (its color mask is off); the color pass adds the fragment
  // into the ensemble's sum once per repetition won.
#ifdef SPT_PASS_COLORS
  if (wins == 0)
  {
    discard;
  }
#endif
  gl_FragData[0] = float(wins) * vec4(segment.rgb / segment.a, 1.0);
#endif // SPT_VISIBILITY_WEIGHTED
#endif
}
