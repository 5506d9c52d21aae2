//VTK::System::Dec
//Volume::Defines::Dec

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
#ifdef SPT_CLIPPING_PLANES
uniform vec4 clippingPlanes[6]; // view coordinates: kept where dot(plane, (x, 1)) >= 0
uniform int clippingPlaneCount;
#endif

flat out int tetrahedronId;
flat out vec4 facePlaneNDC[4]; // the cell's face planes and scalar plane (vtkSPTPointCell.glsl)
flat out vec4 scalarPlaneNDC;

//SPT::FacePlane::Impl
//SPT::PointCell::Impl

void main()
{
  tetrahedronId = gl_VertexID;
  vec2 low;
  vec2 high;
  float nearest;
  bool shown = pointCell(gl_VertexID, facePlaneNDC, scalarPlaneNDC, low, high, nearest);
  vec2 extent = (high - low) * 0.5 * passSizeInPixels;
  // A margin of a twentieth of a pixel covers the rounding of the square's edges; the fragment
  // stage decides which samples the cell covers.
  gl_PointSize = max(extent.x, extent.y) + 0.05;
  // A point is clipped by its centre, which stays inside the viewport. A flat cell and one
  // outside the viewport go beyond the far plane. The depth of the cell's nearest vertex, which
  // no fragment of the cell lies in front of: the color traversal's early depth test compares
  // it with the farthest survivor.
  gl_Position =
    shown ? vec4(0.5 * (low + high), clamp(nearest, -1.0, 1.0), 1.0) : vec4(0.0, 0.0, 2.0, 1.0);
}
