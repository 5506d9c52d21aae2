// Depth slabs (vtkSPTVolumeMapper::SetDepthSlabs()), shared by the SPT passes that use them
// (vtkSPTTetrahedraFS.glsl) and the pass that prepares their weights (vtkSPTSlabsMeanFS.glsl).
//
// The view's depth range is split in SPT_DEPTH_SLABS parts, which split each ray between its
// segments (a segment belongs to the slab that holds its front). Each slab has survivors of
// its own (its run of SPT_REPETITIONS_PER_PASS key layers), so a segment i of slab k is
// visible with probability prod(1 - alpha_j) over the segments j of its own slab in front of
// it, and what it adds is weighted by the exact transmittance T_k of the slabs in front of
// it. It also adds its slab's control variate: C_i + (m - c_k) alpha_i, where c_k is the
// slab's tau-weighted mean color and m the mean color that the resolve corrects the image
// with (vtkEnsembleResolveFS.glsl, whose coverage this pass rewrites): m A = sum_k T_k c_k A_k,
// A_k the slab's exact coverage and A the sample's. The image is then
// sum_k T_k sum_i (C_i - c_k alpha_i) V_i + m A, whose expectation is exact front-to-back
// compositing (none of T_k, c_k and m depends on the random numbers), and what is left of
// the noise is the color differences within each slab.
// The window depths where slabs 1 to 7 start (2: none).
uniform vec4 slabStartsLow;
uniform vec4 slabStartsHigh;
// Per (SPT_SLAB_TERMS * slab + term, sample): first the sums of the slab's segments' tau and
// tau-weighted color (tau, tau r, tau g, tau b), in fixed point (SPT_SLAB_FIXED_ONE per
// unit), added by the image's first key traversal; then, in their place, the slab's controls
// (vtkSPTSlabsMeanFS.glsl) as float bits: what the color traversals weight its segments with,
// T_k (negative where the slab holds no segment), and shift their color with per unit of
// alpha, m - c_k.
layout(r32ui) coherent uniform uimage3D slabSums;

// The slab that holds a window depth: how many of the slabs' starts are not beyond it.
int slabOfDepth(float depth)
{
  vec4 depths = vec4(depth);
  return int(dot(vec4(greaterThanEqual(depths, slabStartsLow)), vec4(1.0)) +
    dot(vec4(greaterThanEqual(depths, slabStartsHigh)), vec4(1.0)));
}

// Add a segment's optical depth terms (tau * color, tau) to its slab's. Beyond
// SPT_SLAB_DEPTH_CAP, where exp(-tau) vanishes in float, a slab stops adding: the fixed point
// cannot overflow.
void addSlabTerms(int slab, vec4 terms, ivec2 pixel)
{
  uvec4 fixedTerms = uvec4(round(min(terms, vec4(64.0)) * float(SPT_SLAB_FIXED_ONE)));
  int layer = SPT_SLAB_TERMS * slab;
  uint cap = SPT_SLAB_DEPTH_CAP * SPT_SLAB_FIXED_ONE;
  if (fixedTerms.a == 0u || imageLoad(slabSums, ivec3(layer, pixel)).r >= cap)
  {
    return;
  }
  imageAtomicAdd(slabSums, ivec3(layer, pixel), fixedTerms.a);
  for (int c = 0; c < 3; ++c)
  {
    if (fixedTerms[c] != 0u)
    {
      imageAtomicAdd(slabSums, ivec3(layer + 1 + c, pixel), fixedTerms[c]);
    }
  }
}

// The controls of a slab at a sample, once the sums have become them.
vec4 slabControl(int slab, ivec2 pixel)
{
  int layer = SPT_SLAB_TERMS * slab;
  return uintBitsToFloat(uvec4(imageLoad(slabSums, ivec3(layer, pixel)).r,
    imageLoad(slabSums, ivec3(layer + 1, pixel)).r, imageLoad(slabSums, ivec3(layer + 2, pixel)).r,
    imageLoad(slabSums, ivec3(layer + 3, pixel)).r));
}
