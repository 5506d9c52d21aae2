//VTK::System::Dec
#extension GL_ARB_shader_image_load_store : require
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
// - It writes a depth no nearer than every repetition's nearest survivor, and no color. The
//   color traversal tests its fragments against it before shading them (early depth test): a
//   fragment behind the survivors of all its repetitions adds nothing there. Where some
//   repetition kept nothing, the far plane.

in vec2 texCoord; // the quad covers the pass: pixel centers
layout(r32ui) coherent uniform uimage3D depthKeys; // (repetition in the pass, pixel)
uniform int repetitionsInGroup;
uniform int secondHalfFrom; // the first repetition of the group in the second half
uniform vec2 passSize; // pixels

#ifdef SPT_SORT_KEYS
uint keys[SPT_REPETITIONS_PER_PASS];

// Insertion sort of keys[begin, end): short runs (at most 64), mostly nearly sorted.
void sortKeys(int begin, int end)
{
  for (int i = begin + 1; i < end; ++i)
  {
    uint key = keys[i];
    int j = i - 1;
    while (j >= begin && keys[j] > key)
    {
      keys[j + 1] = keys[j];
      --j;
    }
    keys[j + 1] = key;
  }
}
#endif

void main()
{
  ivec2 pixel = ivec2(floor(texCoord * passSize));
  int lanes = min(repetitionsInGroup, SPT_REPETITIONS_PER_PASS);
  uint farthest = 0u;
  for (int r = 0; r < lanes; ++r)
  {
    uint key = imageLoad(depthKeys, ivec3(r, pixel)).r;
    farthest = max(farthest, key);
#ifdef SPT_SORT_KEYS
    keys[r] = key;
#endif
  }
#ifdef SPT_SORT_KEYS
  int split = clamp(secondHalfFrom, 0, lanes);
  sortKeys(0, split);
  sortKeys(split, lanes);
  for (int r = 0; r < lanes; ++r)
  {
    imageStore(depthKeys, ivec3(r, pixel), uvec4(keys[r]));
  }
#endif
  // A key holds the depth in its upper 24 bits, rounded down; the next two steps up cover the
  // rounding of the key and of this division.
  float depth = float((farthest >> 8u) + 2u) / 16777215.0;
  gl_FragDepth = farthest == 0xFFFFFFFFu ? 1.0 : min(depth, 1.0);
  gl_FragData[0] = vec4(0.0);
}
