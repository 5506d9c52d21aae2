//VTK::System::Dec
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

uniform int repetition; // bit patterns of unsigned values: VTK sets int uniforms only
uniform int seed;

// PCG-based 4D hash (Jarzynski and Olano, "Hash Functions for GPU Rendering", JCGT 2020).
uvec4 pcg4d(uvec4 v)
{
  v = v * 1664525u + 1013904223u;
  v.x += v.y * v.w;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  v.w += v.y * v.z;
  v ^= v >> 16u;
  v.x += v.y * v.w;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  v.w += v.y * v.z;
  return v;
}

float uniformRandom()
{
  uvec4 key = uvec4(uvec2(gl_FragCoord.xy), uint(tetrahedronId), uint(repetition));
  key.w ^= uint(seed) * 0x9E3779B9u;
  return float(pcg4d(key).x >> 8u) * (1.0 / 16777216.0);
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

  if (uniformRandom() >= segment.a)
  {
    discard;
  }
  // Kept with probability alpha, so the premultiplied color is divided by alpha.
  gl_FragData[0] = vec4(segment.rgb / segment.a, 1.0);
}
