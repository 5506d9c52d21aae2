// One tetrahedron drawn as a point (or visited by the compute traversal): its face planes and
// scalar plane as functions of normalized device coordinates (see vtkSPTFacePlane.glsl), the
// square of normalized device coordinates that holds its projection, cut to the viewport, and
// the depth of its nearest vertex. False for a flat cell, which holds no volume, for one
// outside the viewport, and for one wholly on the cut side of a clipping plane. Needs
// MCVCMatrix, VCDCMatrix, DCVCMatrix, the mesh's buffers (and the clipping planes).
bool pointCell(int id, out vec4 facePlanes[4], out vec4 scalarPlane, out vec2 low,
  out vec2 high, out float nearest)
{
  uvec4 ids = texelFetch(tetrahedra, id);
  vec3 v0 = (MCVCMatrix * vec4(texelFetch(points, int(ids.x)).xyz, 1.0)).xyz;
  vec3 v1 = (MCVCMatrix * vec4(texelFetch(points, int(ids.y)).xyz, 1.0)).xyz;
  vec3 v2 = (MCVCMatrix * vec4(texelFetch(points, int(ids.z)).xyz, 1.0)).xyz;
  vec3 v3 = (MCVCMatrix * vec4(texelFetch(points, int(ids.w)).xyz, 1.0)).xyz;
#ifdef SPT_CELL_SCALARS
  vec4 scalar = vec4(texelFetch(scalars, id).r);
#else
  vec4 scalar = vec4(texelFetch(scalars, int(ids.x)).r, texelFetch(scalars, int(ids.y)).r,
    texelFetch(scalars, int(ids.z)).r, texelFetch(scalars, int(ids.w)).r);
#endif
  facePlanes[0] = ndcFacePlane(v0, v1, v2, v3);
  facePlanes[1] = ndcFacePlane(v1, v2, v3, v0);
  facePlanes[2] = ndcFacePlane(v2, v3, v0, v1);
  facePlanes[3] = ndcFacePlane(v3, v0, v1, v2);
  scalarPlane = scalar.x * facePlanes[0] + scalar.y * facePlanes[1] + scalar.z * facePlanes[2] +
    scalar.w * facePlanes[3];
  vec4 c0 = VCDCMatrix * vec4(v0, 1.0);
  vec4 c1 = VCDCMatrix * vec4(v1, 1.0);
  vec4 c2 = VCDCMatrix * vec4(v2, 1.0);
  vec4 c3 = VCDCMatrix * vec4(v3, 1.0);
  vec2 p0 = c0.xy / c0.w;
  vec2 p1 = c1.xy / c1.w;
  vec2 p2 = c2.xy / c2.w;
  vec2 p3 = c3.xy / c3.w;
  low = max(min(min(p0, p1), min(p2, p3)), vec2(-1.0));
  high = min(max(max(p0, p1), max(p2, p3)), vec2(1.0));
  nearest = min(min(c0.z / c0.w, c1.z / c1.w), min(c2.z / c2.w, c3.z / c3.w));
#ifdef SPT_CLIPPING_PLANES
  for (int k = 0; k < clippingPlaneCount; ++k)
  {
    vec4 plane = clippingPlanes[k];
    if (max(max(dot(plane, vec4(v0, 1.0)), dot(plane, vec4(v1, 1.0))),
          max(dot(plane, vec4(v2, 1.0)), dot(plane, vec4(v3, 1.0)))) < 0.0)
    {
      return false;
    }
  }
#endif
  return dot(cross(v1 - v0, v2 - v0), v3 - v0) != 0.0 && !any(lessThan(high, low));
}
