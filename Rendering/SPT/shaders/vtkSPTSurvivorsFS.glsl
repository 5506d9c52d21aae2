//VTK::System::Dec
#extension GL_ARB_shader_image_load_store : require
#extension GL_ARB_shader_bit_encoding : require
//VTK::Output::Dec
//SPT::Survivors::Dec

// Runs once per sample between a group's keys traversal and its color traversal
// (vtkSPTPassKeysFS.glsl, vtkSPTPassColorsFS.glsl).
// - With SPT_SORT_KEYS (the visibility estimator, which asks only how many repetitions'
//   survivors are not in front of a fragment), it sorts the nearest survivors' keys of each
//   half of the group in increasing order, in place: a fragment of the color traversal then
//   counts them by binary search, in log2 of the repetitions' loads instead of one per
//   repetition. The survivor estimator asks which repetitions a fragment won, so its keys keep
//   their order.
// - It writes a depth no nearer than every repetition's nearest survivor (of the last depth
//   slab that holds segments), and no color. The color traversal tests its fragments against
//   it before shading them (early depth test): a fragment behind the survivors of all its
//   repetitions adds nothing there. Where some repetition kept nothing, the far plane.

in vec2 texCoord; // the quad covers the pass: pixel centers
layout(r32ui) coherent uniform uimage3D depthKeys; // (repetition in the pass, pixel)
uniform int repetitionsInGroup;
uniform int secondHalfFrom; // the first repetition of the group in the second half
uniform vec2 passSize; // pixels
#ifdef SPT_SLAB_TERMS
// The slabs' controls (vtkSPTDepthSlabs.glsl): a slab whose weight is negative holds no
// segment that adds anything.
layout(r32ui) coherent uniform uimage3D slabSums;
#endif

#ifdef SPT_SORT_KEYS
// Two buffers of the group's keys for a bottom-up merge sort, which reads one and writes the
// other: keys[0, N) and keys[N, 2N). (GLSL 1.50 has no arrays of arrays.)
const int N = SPT_REPETITIONS_PER_PASS;
uint keys[2 * N];

// Merge the sorted runs of `width` keys in [begin, end) of buffer `from` into the other one.
void mergeRuns(int from, int begin, int end, int width)
{
  int source = from * N;
  int target = (1 - from) * N;
  for (int left = begin; left < end; left += 2 * width)
  {
    int middle = min(left + width, end);
    int right = min(left + 2 * width, end);
    int i = left;
    int j = middle;
    for (int k = left; k < right; ++k)
    {
      uint a = keys[source + min(i, middle - 1)];
      uint b = keys[source + min(j, right - 1)];
      bool first = j >= right || (i < middle && a <= b);
      keys[target + k] = first ? a : b;
      i += first ? 1 : 0;
      j += first ? 0 : 1;
    }
  }
}

// Sort keys[begin, end) of buffer 0, n log2(n) steps; the buffer that holds the result.
int sortKeys(int begin, int end)
{
  int from = 0;
  for (int width = 1; width < end - begin; width *= 2)
  {
    mergeRuns(from, begin, end, width);
    from = 1 - from;
  }
  return from;
}

// Sorts a slab's kept keys, gathered in keys[] (kept[0] of the first half from 0, kept[1] of
// the second from `split`), and writes them back to its key layers from `base`: each half's at
// the start of the half, and the rest of the half "nothing kept", the largest key, as a sort
// of the whole half would leave it.
//
//   read:     [ 7 - 3 - 5 | - 9 - 2 - - ]    -: nothing kept (0xFFFFFFFF)
//   written:  [ 3 5 7 - - | 2 9 - - - - ]    kept = (3, 2)
void storeSortedKeys(int base, ivec2 pixel, int passRepetitions, int split, int kept[2])
{
  if (kept[0] + kept[1] > 0)
  {
    int firstHalf = sortKeys(0, kept[0]) * N;
    int secondHalf = sortKeys(split, split + kept[1]) * N;
    for (int r = 0; r < passRepetitions; ++r)
    {
      bool second = r >= split;
      bool isKept = r - (second ? split : 0) < kept[second ? 1 : 0];
      uint key = keys[(second ? secondHalf : firstHalf) + r];
      imageStore(depthKeys, ivec3(base + r, pixel), uvec4(isKept ? key : 0xFFFFFFFFu));
    }
  }
}
#endif

// The last depth slab that holds segments at the sample (0 when none does). Each slab's layers
// are sorted apart, and only the survivors of that slab bound what the color traversal may
// skip: a segment of an earlier slab adds its color whatever lies behind it.
int lastSlabWithSegments(ivec2 pixel)
{
  int lastSlab = SPT_DEPTH_SLABS - 1;
#ifdef SPT_SLAB_TERMS
  while (lastSlab > 0 &&
    uintBitsToFloat(imageLoad(slabSums, ivec3(SPT_SLAB_TERMS * lastSlab, pixel)).r) < 0.0)
  {
    --lastSlab;
  }
#endif
  return lastSlab;
}

// Reads one slab's nearest survivors: returns `farthest`, raised to the farthest of them when
// the slab is lastSlab. With SPT_SORT_KEYS, sorts the slab's kept keys in place. Only the kept
// keys are sorted: where few repetitions keep anything (thin parts of the volume, and outside
// its footprint, where none does) that is far less work than sorting every repetition's key.
uint readSlabSurvivors(int slab, int lastSlab, ivec2 pixel, int passRepetitions, uint farthest)
{
  int base = slab * SPT_REPETITIONS_PER_PASS;
#ifdef SPT_SORT_KEYS
  int split = clamp(secondHalfFrom, 0, passRepetitions);
  int kept[2] = int[2](0, 0);
#endif
  for (int r = 0; r < passRepetitions; ++r)
  {
    uint key = imageLoad(depthKeys, ivec3(base + r, pixel)).r;
    farthest = slab == lastSlab ? max(farthest, key) : farthest;
#ifdef SPT_SORT_KEYS
    if (key != 0xFFFFFFFFu)
    {
      int part = r < split ? 0 : 1;
      keys[part * split + kept[part]] = key;
      ++kept[part];
    }
#endif
  }
#ifdef SPT_SORT_KEYS
  storeSortedKeys(base, pixel, passRepetitions, split, kept);
#endif
  return farthest;
}

// The window depth no nearer than a key's: a key holds the depth in its upper 24 bits,
// rounded down, and the next two steps up cover the rounding of the key and of this division.
// The far plane for the key of nothing kept.
float windowDepthBehindKey(uint key)
{
  float windowDepth = float((key >> 8u) + 2u) / 16777215.0;
  return key == 0xFFFFFFFFu ? 1.0 : min(windowDepth, 1.0);
}

// Sorts each slab's survivors (with SPT_SORT_KEYS) and writes the depth behind the farthest
// survivor of the last slab that holds segments.
void main()
{
  ivec2 pixel = ivec2(floor(texCoord * passSize));
  int passRepetitions = min(repetitionsInGroup, SPT_REPETITIONS_PER_PASS);
  uint farthest = 0u;
  int lastSlab = lastSlabWithSegments(pixel);
  for (int slab = 0; slab < SPT_DEPTH_SLABS; ++slab)
  {
    farthest = readSlabSurvivors(slab, lastSlab, pixel, passRepetitions, farthest);
  }
  gl_FragDepth = windowDepthBehindKey(farthest);
  gl_FragData[0] = vec4(0.0);
}
