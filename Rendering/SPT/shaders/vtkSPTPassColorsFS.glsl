// SPT colors pass, after the keys pass of the same repetitions: the fragment adds to the
// ensemble's sum (additive blending)
// - with SPT_VISIBILITY_WEIGHTED (the visibility estimator), its premultiplied color and
//   opacity once for each repetition whose nearest survivor is not in front of it. It is
//   visible in a repetition with probability prod(1 - alpha_j) over the segments j in front
//   of it, so the mean is front-to-back compositing in expectation, and every segment in
//   front of the survivor contributes what it would composite;
// - otherwise (the survivor estimator), its color written opaque once for each repetition
//   whose survivor it is.
// With ENSEMBLE_SECOND_HALF (the ensemble's noise is estimated), what the repetitions from
// secondHalfStart on add also goes to the second half's sum (the second draw buffer).
// With SPT_DEPTH_SLABS, the survivors are those of the fragment's slab, and what it adds is
// weighted by the exact transmittance of the slabs in front of it and corrected by its slab's
// control variate (vtkSPTDepthSlabs.glsl). Which
// repetitions it adds to follows from the depth keys alone, so a fragment that adds to none is
// discarded before its pre-integrated color is looked up.
layout(r32ui) coherent uniform uimage3D depthKeys; // (repetition in the pass, pixel)
// Where the frame writes the farthest survivor's depth first (vtkSPTSurvivorsFS.glsl),
// the fragments behind it are rejected before they are shaded; otherwise the depth test is off.
#ifndef SPT_COMPUTE
layout(early_fragment_tests) in;
#endif
uniform int secondHalfStart; // the first repetition of the second half

#ifdef SPT_VISIBILITY_WEIGHTED
// How many of the sorted keys [begin, end) of the pixel are not in front of this key: the
// length of the tail from the first that is not below it (binary search).
int survivorsNotInFront(uint key, ivec2 pixel, int begin, int end)
{
  int low = begin;
  int high = end;
  while (low < high)
  {
    int middle = (low + high) / 2;
    if (imageLoad(depthKeys, ivec3(middle, pixel)).r < key)
    {
      low = middle + 1;
    }
    else
    {
      high = middle;
    }
  }
  return end - low;
}

// The visibility estimator's counts: of the group's repetitions, how many have their nearest
// survivor (in the key layers [base, base + passRepetitions) of the segment's slab) not in
// front of the key (x), and how many of those are in the second half (y). Each half's keys are
// sorted (vtkSPTSurvivorsFS.glsl): those survivors are the tail of each half.
//
//   key layers:  base            base + split          base + passRepetitions
//                | first half    | second half         |
//   sorted keys: [ . . . k k k k | . . k k k k k k     ]   k: not in front of the key
//                  counts = (4 + 6, 6)
ivec2 visibleCounts(uint key, ivec2 pixel, int base, int passRepetitions)
{
  int split = clamp(secondHalfStart - repetition, 0, passRepetitions);
  int inSecondHalf = survivorsNotInFront(key, pixel, base + split, base + passRepetitions);
  int count = survivorsNotInFront(key, pixel, base, base + split) + inSecondHalf;
  return ivec2(count, inSecondHalf);
}

// A segment's premultiplied color and opacity, as its depth slab weights and shifts it
// (vtkSPTDepthSlabs.glsl): T_k (C_i + (m - c_k) alpha_i).
vec4 slabWeightedColor(vec4 color, int slab, ivec2 pixel)
{
#ifdef SPT_DEPTH_SLABS
  vec4 control = slabControl(slab, pixel);
  color = control.x * vec4(color.rgb + control.yzw * color.a, color.a);
#endif
  return color;
}
#else
// Whether the key is the nearest survivor of any of the group's repetitions (in the key layers
// [base, base + passRepetitions) of the segment's slab): a fragment that holds none adds
// nothing, and is discarded before its color is looked up.
bool holdsSurvivor(uint key, ivec2 pixel, int base, int passRepetitions)
{
  bool holdsOne = false; // the minimum of some repetition is this fragment's key
  for (int r = 0; r < passRepetitions; ++r)
  {
    holdsOne = holdsOne || imageLoad(depthKeys, ivec3(base + r, pixel)).r == key;
  }
  return holdsOne;
}

// The survivor estimator's counts: of the group's repetitions, how many this fragment is the
// survivor of (x), and how many of those are in the second half (y). The key holds 8 bits of
// the cell's id: a fragment of another cell at the same depth may share it, so the
// keep-or-discard decision at the fragment's opacity is checked too.
ivec2 survivorCounts(uint key, float alpha, ivec2 pixel, int base, int passRepetitions)
{
  int count = 0;
  int inSecondHalf = 0;
  for (int r = 0; r < passRepetitions; ++r)
  {
    int wins = imageLoad(depthKeys, ivec3(base + r, pixel)).r == key &&
        threshold(uint(repetition + r)) < alpha ? 1 : 0;
    count += wins;
    inSecondHalf += repetition + r >= secondHalfStart ? wins : 0;
  }
  return ivec2(count, inSecondHalf);
}

// A survivor's color, written opaque, as its depth slab weights and shifts it
// (vtkSPTDepthSlabs.glsl): T_k (C_i / alpha_i + m - c_k).
vec4 slabWeightedOpaque(vec4 color, int slab, ivec2 pixel)
{
  vec4 opaque = vec4(color.rgb / color.a, 1.0);
#ifdef SPT_DEPTH_SLABS
  vec4 control = slabControl(slab, pixel);
  opaque = control.x * vec4(opaque.rgb + control.yzw, 1.0);
#endif
  return opaque;
}
#endif

// What this fragment's (or the compute traversal's) sample adds to the sum and to the second
// half's sum, by the estimator; false when it adds to none (then its color is not looked up).
bool colorsAtSample(out vec4 sum, out vec4 secondHalf)
{
  Segment segment;
  if (!visibleSegment(segment))
  {
    return false;
  }
  uint key = depthKey(segment);
  ivec2 pixel = ivec2(samplePosition);
  int passRepetitions = min(repetitionsInGroup, SPT_REPETITIONS_PER_PASS);
  // The survivors of the fragment's slab decide, behind the slabs in front of it.
  int slab;
  int base = firstLayerOfSlab(segment, slab);
#ifdef SPT_VISIBILITY_WEIGHTED
  ivec2 counts = visibleCounts(key, pixel, base, passRepetitions);
  if (counts.x == 0)
  {
    return false;
  }
  vec4 color = slabWeightedColor(preIntegrated(segment), slab, pixel);
  sum = float(counts.x) * color;
  secondHalf = float(counts.y) * color;
#else
  if (!holdsSurvivor(key, pixel, base, passRepetitions))
  {
    return false;
  }
  vec4 color = preIntegrated(segment);
  ivec2 counts = survivorCounts(key, color.a, pixel, base, passRepetitions);
  vec4 opaque = slabWeightedOpaque(color, slab, pixel);
  sum = float(counts.x) * opaque;
  secondHalf = float(counts.y) * opaque;
#endif
  return true;
}

#ifndef SPT_COMPUTE
void main()
{
  vec4 sum;
  vec4 secondHalf;
  if (!colorsAtSample(sum, secondHalf))
  {
    discard;
  }
  gl_FragData[0] = sum;
#ifdef ENSEMBLE_SECOND_HALF
  gl_FragData[1] = secondHalf;
#endif
}
#endif
