//VTK::System::Dec
#extension GL_ARB_shader_image_load_store : require
//VTK::Output::Dec

// Writes, per sample, a depth no nearer than every repetition's nearest survivor of the keys
// just found (vtkSPTPassKeysFS.glsl), and no color. The color traversal tests its fragments
// against it before shading them (early depth test): a fragment behind the survivors of all
// its repetitions adds nothing there. Where some repetition kept nothing, the far plane.

in vec2 texCoord; // the quad covers the pass: pixel centers
layout(r32ui) coherent uniform uimage3D depthKeys; // (repetition in the pass, pixel)
uniform int repetitionsInGroup;
uniform vec2 passSize; // pixels

void main()
{
  ivec2 pixel = ivec2(floor(texCoord * passSize));
  uint farthest = 0u;
  for (int r = 0; r < repetitionsInGroup; ++r)
  {
    farthest = max(farthest, imageLoad(depthKeys, ivec3(r, pixel)).r);
  }
  // A key holds the depth in its upper 24 bits, rounded down; the next two steps up cover the
  // rounding of the key and of this division.
  float depth = float((farthest >> 8u) + 2u) / 16777215.0;
  gl_FragDepth = farthest == 0xFFFFFFFFu ? 1.0 : min(depth, 1.0);
  gl_FragData[0] = vec4(0.0);
}
