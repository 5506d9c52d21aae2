// The outward plane in view coordinates of the face (a, b, c) of a tetrahedron, scaled so that
// the opposite vertex k lies at -1, taken to normalized device coordinates (needs DCVCMatrix,
// clip -> view). At a point (x, y, z, 1) of normalized device coordinates, the plane's value
// divided by the w of the point in view coordinates (DCVCMatrix * (x, y, z, 1)) is minus the
// point's barycentric weight of vertex k: negative inside the cell, zero on the face. The
// fragment stage clips its view ray by the four planes, a line along z in these coordinates.
// Their sum weighted by the vertices' scalars, the cell's scalar plane, is there minus the
// interpolated scalar, times the same w.
vec4 ndcFacePlane(vec3 k, vec3 a, vec3 b, vec3 c)
{
  vec3 normal = cross(b - a, c - a);
  normal /= -dot(normal, k - a);
  return vec4(normal, -dot(normal, a)) * DCVCMatrix;
}
