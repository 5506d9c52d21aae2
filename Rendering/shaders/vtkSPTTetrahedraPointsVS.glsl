//VTK::System::Dec
//SPT::Defines::Dec

// SPT vertex stage for tetrahedra drawn as points: one point per tetrahedron (glDrawArrays of
// GL_POINTS, gl_VertexID is the tetrahedron's index), a square that holds the tetrahedron's
// projection. The fragment stage clips its own view ray by the four face planes made here and
// discards the samples that miss the cell (vtkSPTTetrahedraFS.glsl).
//
// Where tetrahedra cover few pixels each (about a million at 256 x 256), a point is one
// primitive to set up and rasterize against the one or two triangles of the projected
// outline, and it needs no geometry stage. Only the leading classes of size are drawn so
// (vtkSPTMeshBuffers, vtkSPTFrame: their squares stay small on the screen, and the mesh's bounds
// lie in front of the near plane); the geometry stage draws the others.

uniform mat4 MCVCMatrix; // model -> view, in the mesh's normalized units
uniform mat4 VCDCMatrix; // view -> clip
uniform mat4 DCVCMatrix; // clip -> view
uniform vec2 passSizeInPixels;
uniform usamplerBuffer tetrahedra; // four point ids per tetrahedron
uniform samplerBuffer points;      // model coordinates
uniform samplerBuffer scalars;     // per point, or per tetrahedron (SPT_CELL_SCALARS)

flat out int tetrahedronId;
// The cell's face planes as functions of normalized device coordinates (x, y, z, 1): the
// face opposite vertex k is facePlaneNDC[k] = 0, and the value, divided by the w of the point
// in view coordinates (DCVCMatrix * (x, y, z, 1)), is minus the point's barycentric weight of
// vertex k (so negative inside). scalarPlaneNDC is the sum of the four weighted by the
// vertices' scalars: minus the interpolated scalar, times the same w.
flat out vec4 facePlaneNDC[4];
flat out vec4 scalarPlaneNDC;

//SPT::FacePlane::Impl

void main()
{
  tetrahedronId = gl_VertexID;
  uvec4 ids = texelFetch(tetrahedra, gl_VertexID);
  vec3 v0 = (MCVCMatrix * vec4(texelFetch(points, int(ids.x)).xyz, 1.0)).xyz;
  vec3 v1 = (MCVCMatrix * vec4(texelFetch(points, int(ids.y)).xyz, 1.0)).xyz;
  vec3 v2 = (MCVCMatrix * vec4(texelFetch(points, int(ids.z)).xyz, 1.0)).xyz;
  vec3 v3 = (MCVCMatrix * vec4(texelFetch(points, int(ids.w)).xyz, 1.0)).xyz;
#ifdef SPT_CELL_SCALARS
  vec4 scalar = vec4(texelFetch(scalars, gl_VertexID).r);
#else
  vec4 scalar = vec4(texelFetch(scalars, int(ids.x)).r, texelFetch(scalars, int(ids.y)).r,
    texelFetch(scalars, int(ids.z)).r, texelFetch(scalars, int(ids.w)).r);
#endif
  facePlaneNDC[0] = ndcFacePlane(v0, v1, v2, v3);
  facePlaneNDC[1] = ndcFacePlane(v1, v2, v3, v0);
  facePlaneNDC[2] = ndcFacePlane(v2, v3, v0, v1);
  facePlaneNDC[3] = ndcFacePlane(v3, v0, v1, v2);
  scalarPlaneNDC = scalar.x * facePlaneNDC[0] + scalar.y * facePlaneNDC[1] +
    scalar.z * facePlaneNDC[2] + scalar.w * facePlaneNDC[3];
  // The projection's bounding square in window coordinates of the pass.
  vec4 c0 = VCDCMatrix * vec4(v0, 1.0);
  vec4 c1 = VCDCMatrix * vec4(v1, 1.0);
  vec4 c2 = VCDCMatrix * vec4(v2, 1.0);
  vec4 c3 = VCDCMatrix * vec4(v3, 1.0);
  vec2 p0 = c0.xy / c0.w;
  vec2 p1 = c1.xy / c1.w;
  vec2 p2 = c2.xy / c2.w;
  vec2 p3 = c3.xy / c3.w;
  // Cut to the viewport: a point is clipped by its centre, which must stay inside.
  vec2 low = max(min(min(p0, p1), min(p2, p3)), vec2(-1.0));
  vec2 high = min(max(max(p0, p1), max(p2, p3)), vec2(1.0));
  vec2 extent = (high - low) * 0.5 * passSizeInPixels;
  // A flat cell holds no volume, and one outside the viewport shows nothing: their points go
  // beyond the far plane.
  bool hidden = dot(cross(v1 - v0, v2 - v0), v3 - v0) == 0.0 || any(lessThan(high, low));
  // A margin of a twentieth of a pixel covers the rounding of the square's edges; the fragment
  // stage decides which samples the cell covers.
  gl_PointSize = max(extent.x, extent.y) + 0.05;
  // The depth of the cell's nearest vertex, which no fragment of the cell lies in front of: the
  // color traversal's early depth test compares it with the farthest survivor.
  float nearest = min(min(c0.z / c0.w, c1.z / c1.w), min(c2.z / c2.w, c3.z / c3.w));
  gl_Position =
    hidden ? vec4(0.0, 0.0, 2.0, 1.0) : vec4(0.5 * (low + high), clamp(nearest, -1.0, 1.0), 1.0);
}
