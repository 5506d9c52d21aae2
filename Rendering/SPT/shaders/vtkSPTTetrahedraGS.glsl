//VTK::System::Dec
//Volume::Defines::Dec

// SPT geometry stage: a tetrahedron (4 vertices of GL_LINES_ADJACENCY) is drawn as its
// projected outline, the convex hull of its four projected vertices: one triangle when a vertex
// projects inside the triangle of the other three (Shirley and Tuchman's class 1), two when the
// outline is a quadrilateral (class 2). Degenerate projections (classes 3 and 4) are the limits
// of class 1. The fragment stage clips its own view ray by the cell's four face planes, made
// here in normalized device coordinates, where the ray is a line along z, and reads the scalars
// at the segment's ends from the cell's scalar plane (vtkSPTTetrahedraFS.glsl).
//
// Shirley and Tuchman split the outline into the 3 or 4 triangles that share the thick point
// and interpolate the segment's ends across them. On a software rasterizer the setup of those
// triangles takes most of a traversal; the outline is 1 or 2 triangles with the same fragments,
// which find the same segments.
//
// All of a cell's fragments are rasterized at the depth of its nearest vertex, which none of
// its segments lies in front of: the color traversal's early depth test compares it with the
// farthest survivor. The fragment stage writes the segment's own depth where the depth test
// decides (the single pass).
//
// The outline needs the whole tetrahedron in front of the near plane; the hardware clips it by
// the side planes (a view zoomed into the mesh), and the fragments inside the viewport find
// their segments as anywhere else. A tetrahedron that the near plane cuts (the camera inside
// or close to the mesh, possibly with vertices behind the eye) is drawn as its exit faces
// instead, which the hardware clips; each of their fragments finds its own segment from the
// cell's face planes, from the near plane or the nearest entry face on.

layout(lines_adjacency) in;
#ifdef SPT_CLIPPED_CELLS
layout(triangle_strip, max_vertices = 12) out; // all four faces with the eye inside
#else
layout(triangle_strip, max_vertices = 4) out;
#endif

in vec3 positionVCVSOutput[];
in float scalarVSOutput[];

uniform mat4 VCDCMatrix;     // view -> clip
uniform mat4 DCVCMatrix;     // clip -> view
uniform int primitiveOffset; // index of the first tetrahedron of this draw call
uniform vec4 eyeVC;          // the eye in homogeneous view coordinates: (0, 0, 0, 1) in
                             // perspective, the point at infinity (0, 0, 1, 0) in parallel
#ifdef SPT_CELL_SCALARS
uniform samplerBuffer cellScalars;
#endif

flat out int tetrahedronId;
flat out vec4 facePlaneNDC[4]; // the cell's face planes (vtkSPTFacePlane.glsl)
flat out vec4 scalarPlaneNDC;
#ifdef SPT_CLIPPED_CELLS
flat out int clippedCell; // 1: the fragment stage computes the segment from the cell
#endif

vec3 vertexVC[4];
vec2 vertexNDC[4];       // the projection, in normalized device coordinates
float vertexDepthNDC[4]; // and the depth
float vertexScalar[4];

// A vertex's clip coordinates, from its view coordinates. Not kept in an array: Mesa 25's
// llvmpipe (LLVM 19) reads wrong values, or crashes, when a geometry shader indexes an array of
// vec4 (an input or its own) with a variable; arrays of vec3, vec2 and float read right. For
// the same reason the planes are four variables, and the output array takes constant indices.
vec4 vertexDC(int i)
{
  return VCDCMatrix * vec4(vertexVC[i], 1.0);
}

vec4 plane0;
vec4 plane1;
vec4 plane2;
vec4 plane3;
vec4 scalarPlane;
float nearestDepthNDC; // of the cell's vertices

//SPT::FacePlane::Impl

// Twice the signed area of the triangle (a, b, c): positive when it turns counter-clockwise.
float orient2D(vec2 a, vec2 b, vec2 c)
{
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// One vertex of the cell's triangles, with the cell's flat outputs: its id, its face planes
// and scalar plane, and (with clipped cells) whether the fragment stage clips the ray itself.
void emitVertex(vec4 position, int clipped)
{
  gl_Position = position;
  facePlaneNDC[0] = plane0;
  facePlaneNDC[1] = plane1;
  facePlaneNDC[2] = plane2;
  facePlaneNDC[3] = plane3;
  scalarPlaneNDC = scalarPlane;
  tetrahedronId = primitiveOffset + gl_PrimitiveIDIn;
#ifdef SPT_CLIPPED_CELLS
  clippedCell = clipped;
#endif
  EmitVertex();
}

// An outline vertex, at the depth of the cell's nearest vertex.
void emitOutline(int i)
{
  emitVertex(vec4(vertexNDC[i], nearestDepthNDC, 1.0), 0);
}

#ifdef SPT_CLIPPED_CELLS
// The exit faces of a tetrahedron that a clipping plane cuts: the faces whose plane has the eye
// on its inner side. Each pixel the cell covers in the view volume gets one fragment (the
// point where its ray leaves the cell), which carries nothing but the cell's id.
void emitExitFaces()
{
  plane0 = plane1 = plane2 = plane3 = scalarPlane = vec4(0.0);
  for (int k = 0; k < 4; ++k)
  {
    int a = (k + 1) % 4;
    int b = (k + 2) % 4;
    int c = (k + 3) % 4;
    vec3 normal = cross(vertexVC[b] - vertexVC[a], vertexVC[c] - vertexVC[a]);
    float towardsOpposite = dot(normal, vertexVC[k] - vertexVC[a]);
    if (towardsOpposite == 0.0)
    {
      return; // a flat tetrahedron holds no volume
    }
    normal = towardsOpposite > 0.0 ? -normal : normal; // outward
    if (dot(vec4(normal, -dot(normal, vertexVC[a])), eyeVC) >= 0.0)
    {
      continue; // an entry face, or seen edge-on
    }
    for (int corner = 0; corner < 3; ++corner)
    {
      emitVertex(vertexDC((k + 1 + corner) % 4), 1);
    }
    EndPrimitive();
  }
}
#endif

// Class 1: vertex i projects inside the triangle of the other three, which is the outline.
//
//             j
//            / \            the outline is the triangle (j, k, l) of the other three
//           /   \           vertices; i, inside it, is the thick point, where the ray
//          /  i  \          through the cell is longest
//         /       \
//        k---------l
void emitClass1(int i)
{
  emitOutline((i + 1) % 4);
  emitOutline((i + 2) % 4);
  emitOutline((i + 3) % 4);
  EndPrimitive();
}

// Class 2: the projections of edges (a, b) and (c, d) cross; the outline alternates between
// these diagonals, a, c, b, d, and is drawn as the strip a, c, d, b.
//
//        a---------c
//        | \     / |        the diagonals (a, b) and (c, d) cross at x, the thick point;
//        |   \ /   |        the strip's triangles (a, c, d) and (c, d, b) share the
//        |    x    |        diagonal (c, d)
//        |   / \   |
//        | /     \ |
//        d---------b
void emitClass2(int a, int b, int c, int d)
{
  emitOutline(a);
  emitOutline(c);
  emitOutline(d);
  emitOutline(b);
  EndPrimitive();
}

// Class 1 test: the vertex whose smallest barycentric weight in the triangle of the other
// three is largest. Returns that vertex (-1 when all four project onto one line) and its
// smallest weight.
int findClass1(out float bestWeight)
{
  int bestVertex = -1;
  bestWeight = -1.0e30;
  for (int i = 0; i < 4; ++i)
  {
    vec2 pj = vertexNDC[(i + 1) % 4];
    vec2 pk = vertexNDC[(i + 2) % 4];
    vec2 pl = vertexNDC[(i + 3) % 4];
    float area = orient2D(pj, pk, pl);
    if (area == 0.0)
    {
      continue;
    }
    vec2 p = vertexNDC[i];
    vec3 w = vec3(orient2D(p, pk, pl), orient2D(pj, p, pl), orient2D(pj, pk, p)) / area;
    float smallest = min(w.x, min(w.y, w.z));
    if (smallest > bestWeight)
    {
      bestWeight = smallest;
      bestVertex = i;
    }
  }
  return bestVertex;
}

// Class 2: of the three ways to pair the edges, the diagonals of the outline are the pair
// whose crossing lies inside both segments.
void emitBestClass2()
{
  ivec4 pairs[3] = ivec4[3](ivec4(0, 1, 2, 3), ivec4(0, 2, 1, 3), ivec4(0, 3, 1, 2));
  int bestPair = -1;
  float bestMargin = -1.0e30;
  for (int p = 0; p < 3; ++p)
  {
    ivec4 e = pairs[p];
    vec2 r = vertexNDC[e.y] - vertexNDC[e.x];
    vec2 s = vertexNDC[e.w] - vertexNDC[e.z];
    float denominator = r.x * s.y - r.y * s.x;
    if (denominator == 0.0)
    {
      continue;
    }
    vec2 q = vertexNDC[e.z] - vertexNDC[e.x];
    float u = (q.x * s.y - q.y * s.x) / denominator;
    float v = (q.x * r.y - q.y * r.x) / denominator;
    float margin = min(min(u, 1.0 - u), min(v, 1.0 - v));
    if (margin > bestMargin)
    {
      bestMargin = margin;
      bestPair = p;
    }
  }
  if (bestPair >= 0)
  {
    ivec4 e = pairs[bestPair];
    emitClass2(e.x, e.y, e.z, e.w);
  }
}

// Projects the four vertices once, into vertexVC, vertexNDC and vertexDepthNDC (the divisions
// are used only when all four lie inside), and counts the vertices beyond each of the view
// volume's near and side planes, which decide how the cell is drawn. Clip space puts a point
// beyond those planes at z < -w, |x| > w or |y| > w (a point behind the eye too).
//
//                 y = w
//          +---------------+
//          |               |
//   x = -w |     inside    | x = w       (the view volume seen from the eye)
//          |               |
//          +---------------+
//                 y = -w
//
// beyond.x counts the vertices nearer than the near plane (z < -w), .y those left of x = -w,
// .z those right of x = w, and .w those above y = w or below y = -w.
ivec4 projectVertices()
{
  ivec4 beyond = ivec4(0);
  for (int i = 0; i < 4; ++i)
  {
    vertexVC[i] = positionVCVSOutput[i];
    vec4 positionDC = vertexDC(i);
    beyond += ivec4(positionDC.z < -positionDC.w, positionDC.x < -positionDC.w,
      positionDC.x > positionDC.w, positionDC.y < -positionDC.w || positionDC.y > positionDC.w);
    vertexNDC[i] = positionDC.xy / positionDC.w;
    vertexDepthNDC[i] = positionDC.z / positionDC.w;
  }
  return beyond;
}

// The scalars at the four vertices, into vertexScalar: the cell's own scalar at each of them
// with scalars per cell, the points' otherwise.
void readVertexScalars()
{
  for (int i = 0; i < 4; ++i)
  {
#ifdef SPT_CELL_SCALARS
    vertexScalar[i] = texelFetch(cellScalars, primitiveOffset + gl_PrimitiveIDIn).r;
#else
    vertexScalar[i] = scalarVSOutput[i];
#endif
  }
}

// Whether the tetrahedron is flat: its vertices lie in one plane, so that it holds no volume
// and its projection may cover no area (and its face planes do not exist).
bool isFlat()
{
  vec3 v0 = vertexVC[0];
  vec3 v1 = vertexVC[1];
  vec3 v2 = vertexVC[2];
  vec3 v3 = vertexVC[3];
  return dot(cross(v1 - v0, v2 - v0), v3 - v0) == 0.0;
}

// The cell's flat outputs for the fragment stage: its four face planes and its scalar plane in
// normalized device coordinates (vtkSPTFacePlane.glsl), and the depth of its nearest vertex,
// at which the whole outline is rasterized (no segment lies in front of it).
void makeCellPlanes()
{
  vec3 v0 = vertexVC[0];
  vec3 v1 = vertexVC[1];
  vec3 v2 = vertexVC[2];
  vec3 v3 = vertexVC[3];
  plane0 = ndcFacePlane(v0, v1, v2, v3);
  plane1 = ndcFacePlane(v1, v2, v3, v0);
  plane2 = ndcFacePlane(v2, v3, v0, v1);
  plane3 = ndcFacePlane(v3, v0, v1, v2);
  scalarPlane = vertexScalar[0] * plane0 + vertexScalar[1] * plane1 + vertexScalar[2] * plane2 +
    vertexScalar[3] * plane3;
  nearestDepthNDC = min(1.0,
    min(min(vertexDepthNDC[0], vertexDepthNDC[1]), min(vertexDepthNDC[2], vertexDepthNDC[3])));
}

// Culls the cells that lie wholly beyond one plane of the view volume, draws a cell that the
// near plane cuts as its exit faces, and any other as its projected outline, by its class.
void main()
{
  ivec4 beyond = projectVertices();
  if (any(equal(beyond.xyz, ivec3(4))))
  {
    return; // wholly beyond one plane: nothing visible
  }
  if (beyond.x > 0)
  {
#ifdef SPT_CLIPPED_CELLS
    emitExitFaces();
#endif
    return; // (without the near plane cutting the mesh's bounds, this cannot happen)
  }
  readVertexScalars();
  float bestWeight;
  int bestVertex = findClass1(bestWeight);
  if (bestVertex < 0 || isFlat())
  {
    return; // a flat tetrahedron: no volume, and its projection may cover no area
  }
  makeCellPlanes();
  // Inside the triangle of the other three (or on its outline): class 1.
  const float insideTolerance = 1.0e-6;
  if (bestWeight >= -insideTolerance)
  {
    emitClass1(bestVertex);
  }
  else
  {
    emitBestClass2();
  }
}
