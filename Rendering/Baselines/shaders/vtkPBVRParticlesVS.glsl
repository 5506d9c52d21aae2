//VTK::System::Dec

// PBVR vertex stage (Sakamoto et al. 2007, 2010): one opaque particle per vertex, drawn as a
// point of one (sub)pixel. The particles were generated at the density that the smallest pixel
// cross-section over the data needs (generatedFootprint); a particle whose own pixel
// cross-section is larger is kept with probability generatedFootprint / footprint, which
// thins the particles to exactly the density its depth needs. A particle nearer than the depth
// the particles were generated for (the camera inside the data, or close to it) has a pixel
// cross-section smaller than its own: it is drawn as a square of generatedFootprint /
// footprint pixels, whose expected coverage of pixel centres is that area, so the opacity
// stays exact.

in vec4 particleMC; // normalized unsigned shorts: position + 0.5 in model units, scalar

uniform mat4 MCVCMatrix;          // model -> view, in the mesh's normalized units
uniform mat4 VCDCMatrix;          // view -> clip
uniform mat3 VCMCLinear;          // view -> model, for lengths along the ray
uniform float viewToModelVolume;  // |det(VCMCLinear)|, for volumes
uniform float pixelAreaFactor;    // pixel cross-section in view units is this x w^2
uniform int parallelProjection;
uniform float generatedFootprint; // model units^2
uniform float largestPointSize;   // pixels
uniform vec2 clipScale;           // the pass's share of the viewport, which has a guard band
uniform int seed;                 // bit pattern of an unsigned value

uniform sampler2D colorTable;        // the color transfer function over the scalar range
uniform vec2 colorTexelScaleOffset;  // maps [0, 1] onto the centers of the first and last texels

out vec3 colorVSOutput;

//Volume::Random::Impl

// The clipping planes (PBVR_CLIPPING_PLANES, defined with the random hash where there are some).
#ifdef PBVR_CLIPPING_PLANES
uniform vec4 clippingPlanes[6]; // the mapper's clipping planes (view coordinates): a particle
uniform int clippingPlaneCount; // is kept where dot(plane, (x, 1)) >= 0 for each of them
#endif

// Whether the particle is kept: by its depth's density, and by every clipping plane.
bool kept(float keep, float footprintMC, vec4 positionVC)
{
  bool inside = keep * footprintMC < generatedFootprint;
#ifdef PBVR_CLIPPING_PLANES
  for (int k = 0; k < clippingPlaneCount; ++k)
  {
    inside = inside && dot(clippingPlanes[k], positionVC) >= 0.0;
  }
#endif
  return inside;
}

void main()
{
  vec4 positionVC = MCVCMatrix * vec4(particleMC.xyz - 0.5, 1.0);
  vec4 positionDC = VCDCMatrix * positionVC;
  positionDC.xy *= clipScale;

  // The pixel's frustum holds footprintVC x (ray length) of volume around this depth: its
  // cross-section times the cosine of the ray's angle to the view axis.
  vec3 rayVC = parallelProjection != 0 ? vec3(0.0, 0.0, -1.0) : normalize(positionVC.xyz);
  float footprintVC = pixelAreaFactor * positionDC.w * positionDC.w * abs(rayVC.z);
  float footprintMC = footprintVC * viewToModelVolume / length(VCMCLinear * rayVC);

  uvec4 key = uvec4(uint(gl_VertexID), uint(seed), 0x85EBCA6Bu, 0xC2B2AE35u);
  float keep = float(pcg4d(key).x >> 8u) * (1.0 / 16777216.0);
  // A point outside the clip volume is not drawn.
  gl_Position = kept(keep, footprintMC, positionVC) ? positionDC : vec4(2.0, 2.0, 2.0, 1.0);
  gl_PointSize = min(sqrt(max(generatedFootprint / footprintMC, 1.0)), largestPointSize);
  colorVSOutput = texture(colorTable,
    vec2(particleMC.w * colorTexelScaleOffset.x + colorTexelScaleOffset.y, 0.5)).rgb;
}
