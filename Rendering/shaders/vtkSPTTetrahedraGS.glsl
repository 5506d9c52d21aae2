//VTK::System::Dec
//SPT::Defines::Dec

// SPT geometry stage: Shirley-Tuchman projected tetrahedra (Shirley and Tuchman 1990) on the
// GPU. A tetrahedron (4 vertices of GL_LINES_ADJACENCY) is split into the 3 or 4 triangles of
// its projected outline that share the "thick" point, the point where the tetrahedron is
// thickest along the view ray; each fan is sent as one triangle strip. Degenerate projections
// (classes 3 and 4) are the limits of classes 1 and 2: their extra triangles have no area and
// draw nothing.
//
// Every emitted vertex carries the front and the back point of the view ray through it (both
// in view coordinates) and the scalars there. They are passed divided by their own clip w and
// interpolated without perspective, so that the fragment stage recovers the exact front and
// back points of its own ray under perspective and parallel projection alike.
//
// That needs the whole tetrahedron inside the view volume: clipping does not interpolate those
// values right where w varies much across a triangle. A tetrahedron that a clipping plane cuts
// (the near plane with the camera inside or close to the mesh, possibly with vertices behind
// the eye; a side plane when the view is zoomed in) is drawn as its exit faces instead, which
// the hardware clips; each of their fragments finds its own segment from the cell's face
// planes, from the near plane or the nearest entry face on (vtkSPTTetrahedraFS.glsl).

layout(lines_adjacency) in;
#ifdef SPT_CLIPPED_CELLS
layout(triangle_strip, max_vertices = 12) out; // all four faces with the eye inside
#else
layout(triangle_strip, max_vertices = 7) out;
#endif

in vec3 positionVCVSOutput[];
in float scalarVSOutput[];

uniform mat4 VCDCMatrix;     // view -> clip
uniform int primitiveOffset; // index of the first tetrahedron of this draw call
uniform vec4 eyeVC;          // the eye in homogeneous view coordinates: (0, 0, 0, 1) in
                             // perspective, the point at infinity (0, 0, 1, 0) in parallel
#ifdef SPT_CELL_SCALARS
uniform samplerBuffer cellScalars;
#endif

noperspective out vec4 frontVCOverW; // (front point, 1) / w_front
noperspective out vec4 backVCOverW;  // (back point, 1) / w_back
noperspective out vec2 scalarsOverW; // (front scalar / w_front, back scalar / w_back)
flat out int tetrahedronId;
#ifdef SPT_CLIPPED_CELLS
flat out int clippedCell; // 1: the fragment stage computes the segment from the cell
#endif

vec3 vertexVC[4];
vec2 vertexNDC[4];
float vertexScalar[4];

// A vertex's clip coordinates, from its view coordinates. Not kept in an array: Mesa 25's
// llvmpipe (LLVM 19) reads wrong values, or crashes, when a geometry shader indexes an array of
// vec4 (an input or its own) with a variable; arrays of vec3, vec2 and float read right.
vec4 vertexDC(int i)
{
  return VCDCMatrix * vec4(vertexVC[i], 1.0);
}

// The thick point: its front and back points (view and clip coordinates) and scalars.
vec3 thickFrontVC;
vec3 thickBackVC;
vec4 thickFrontDC;
vec4 thickBackDC;
float thickFrontScalar;
float thickBackScalar;

float orient2D(vec2 a, vec2 b, vec2 c)
{
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

void emitPoint(vec3 frontVC, vec4 frontDC, float frontScalar, vec3 backVC, vec4 backDC,
  float backScalar)
{
  gl_Position = frontDC;
  frontVCOverW = vec4(frontVC, 1.0) / frontDC.w;
  backVCOverW = vec4(backVC, 1.0) / backDC.w;
  scalarsOverW = vec2(frontScalar / frontDC.w, backScalar / backDC.w);
  tetrahedronId = primitiveOffset + gl_PrimitiveIDIn;
#ifdef SPT_CLIPPED_CELLS
  clippedCell = 0;
#endif
  EmitVertex();
}

#ifdef SPT_CLIPPED_CELLS
// The exit faces of a tetrahedron that a clipping plane cuts: the faces whose plane has the eye
// on its inner side. Each pixel the cell covers in the view volume gets one fragment (the
// point where its ray leaves the cell), which carries nothing but the cell's id.
void emitExitFaces()
{
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
      gl_Position = vertexDC((k + 1 + corner) % 4);
      frontVCOverW = vec4(0.0);
      backVCOverW = vec4(0.0);
      scalarsOverW = vec2(0.0);
      tetrahedronId = primitiveOffset + gl_PrimitiveIDIn;
      clippedCell = 1;
      EmitVertex();
    }
    EndPrimitive();
  }
}
#endif

// An outline vertex: the tetrahedron has zero thickness there.
void emitOutline(int i)
{
  emitPoint(vertexVC[i], vertexDC(i), vertexScalar[i], vertexVC[i], vertexDC(i), vertexScalar[i]);
}

void emitThick()
{
  emitPoint(thickFrontVC, thickFrontDC, thickFrontScalar, thickBackVC, thickBackDC,
    thickBackScalar);
}

// The nearer of two points on one view ray is the one with the larger view-space z, for
// perspective and parallel projection alike (the camera looks down -z).
void setThick(vec3 pVC, vec4 pDC, float pScalar, vec3 qVC, vec4 qDC, float qScalar)
{
  bool pInFront = pVC.z >= qVC.z;
  thickFrontVC = pInFront ? pVC : qVC;
  thickFrontDC = pInFront ? pDC : qDC;
  thickFrontScalar = pInFront ? pScalar : qScalar;
  thickBackVC = pInFront ? qVC : pVC;
  thickBackDC = pInFront ? qDC : pDC;
  thickBackScalar = pInFront ? qScalar : pScalar;
}

// Class 1: vertex i projects inside the triangle of the other three. The thick point is that
// vertex and the point of the opposite face on the same ray.
void emitClass1(int i, vec3 screenWeights)
{
  int j = (i + 1) % 4;
  int k = (i + 2) % 4;
  int l = (i + 3) % 4;
  // Screen-space barycentric weights become perspective-correct ones through 1/w; clip
  // coordinates are linear in view coordinates, so the same weights give the clip point.
  vec3 weights = screenWeights / vec3(vertexDC(j).w, vertexDC(k).w, vertexDC(l).w);
  weights /= weights.x + weights.y + weights.z;
  vec3 faceVC = weights.x * vertexVC[j] + weights.y * vertexVC[k] + weights.z * vertexVC[l];
  vec4 faceDC = weights.x * vertexDC(j) + weights.y * vertexDC(k) + weights.z * vertexDC(l);
  float faceScalar = dot(weights, vec3(vertexScalar[j], vertexScalar[k], vertexScalar[l]));
  setThick(vertexVC[i], vertexDC(i), vertexScalar[i], faceVC, faceDC, faceScalar);
  // The fan (thick; j, k, l) as the strip k, j, thick, l, k.
  emitOutline(k);
  emitOutline(j);
  emitThick();
  emitOutline(l);
  emitOutline(k);
  EndPrimitive();
}

// Class 2: the projections of edges (a, b) and (c, d) cross at screen parameters u and v.
void emitClass2(int a, int b, int c, int d, float u, float v)
{
  // Screen-space parameters on an edge become view-space ones through the clip w.
  float t = u * vertexDC(a).w / (u * vertexDC(a).w + (1.0 - u) * vertexDC(b).w);
  float s = v * vertexDC(c).w / (v * vertexDC(c).w + (1.0 - v) * vertexDC(d).w);
  setThick(mix(vertexVC[a], vertexVC[b], t), mix(vertexDC(a), vertexDC(b), t),
    mix(vertexScalar[a], vertexScalar[b], t), mix(vertexVC[c], vertexVC[d], s),
    mix(vertexDC(c), vertexDC(d), s), mix(vertexScalar[c], vertexScalar[d], s));
  // The outline alternates between the diagonals: a, c, b, d. The fan (thick; a, c, b, d) as
  // the strip a, c, thick, b, thick, d, a (its fourth triangle has no area).
  emitOutline(a);
  emitOutline(c);
  emitThick();
  emitOutline(b);
  emitThick();
  emitOutline(d);
  emitOutline(a);
  EndPrimitive();
}

// Class 1 test: the vertex whose smallest barycentric weight in the triangle of the other
// three is largest. Returns that vertex (-1 when all four project onto one line), its
// smallest weight and its weights.
int findClass1(out float bestWeight, out vec3 bestWeights)
{
  int bestVertex = -1;
  bestWeight = -1.0e30;
  bestWeights = vec3(0.0);
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
      bestWeights = w;
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
  vec2 bestParameters = vec2(0.0);
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
      bestParameters = vec2(u, v);
    }
  }
  if (bestPair >= 0)
  {
    ivec4 e = pairs[bestPair];
    vec2 uv = clamp(bestParameters, 0.0, 1.0);
    emitClass2(e.x, e.y, e.z, e.w, uv.x, uv.y);
  }
}

void main()
{
  // Clip space puts a point outside the view volume's near and side planes at z < -w,
  // |x| > w or |y| > w (a point behind the eye too); count the vertices beyond each plane.
  ivec4 beyond = ivec4(0);
  for (int i = 0; i < 4; ++i)
  {
    vertexVC[i] = positionVCVSOutput[i];
    vec4 p = vertexDC(i);
    beyond += ivec4(p.z < -p.w, p.x < -p.w, p.x > p.w, p.y < -p.w || p.y > p.w);
  }
  if (any(equal(beyond.xyz, ivec3(4))))
  {
    return; // wholly beyond one plane: nothing visible
  }
  if (any(greaterThan(beyond, ivec4(0))))
  {
#ifdef SPT_CLIPPED_CELLS
    emitExitFaces();
#endif
    return; // (without a plane cutting the mesh's bounds, this cannot happen)
  }
  for (int i = 0; i < 4; ++i)
  {
    vertexNDC[i] = vertexDC(i).xy / vertexDC(i).w;
#ifdef SPT_CELL_SCALARS
    vertexScalar[i] = texelFetch(cellScalars, primitiveOffset + gl_PrimitiveIDIn).r;
#else
    vertexScalar[i] = scalarVSOutput[i];
#endif
  }
  float bestWeight;
  vec3 bestWeights;
  int bestVertex = findClass1(bestWeight, bestWeights);
  if (bestVertex < 0)
  {
    return; // all four vertices on one line: the projection covers no area
  }
  // Inside the triangle of the other three (or on its outline): class 1.
  const float insideTolerance = 1.0e-6;
  if (bestWeight >= -insideTolerance)
  {
    emitClass1(bestVertex, max(bestWeights, vec3(0.0)));
  }
  else
  {
    emitBestClass2();
  }
}
