//VTK::System::Dec
//SPT::Defines::Dec

// SPT geometry stage: Shirley-Tuchman projected tetrahedra (Shirley and Tuchman 1990) on the
// GPU. A tetrahedron (4 vertices of GL_LINES_ADJACENCY) is split into the 3 or 4 triangles of
// its projected outline that share the "thick" point, the point where the tetrahedron is
// thickest along the view ray. Degenerate projections (classes 3 and 4) are the limits of
// classes 1 and 2 and simply emit fewer non-empty triangles.
//
// Every emitted vertex carries the front and the back point of the view ray through it (both
// in view coordinates) and the scalars there. They are passed divided by their own clip w and
// interpolated without perspective, so that the fragment stage recovers the exact front and
// back points of its own ray under perspective and parallel projection alike.

layout(lines_adjacency) in;
layout(triangle_strip, max_vertices = 12) out;

in vec3 positionVCVSOutput[];
in float scalarVSOutput[];

uniform mat4 VCDCMatrix;    // view -> clip
uniform int primitiveOffset; // index of the first tetrahedron of this draw call
#ifdef SPT_CELL_SCALARS
uniform samplerBuffer cellScalars;
#endif

noperspective out vec4 frontVCOverW; // (front point, 1) / w_front
noperspective out vec4 backVCOverW;  // (back point, 1) / w_back
noperspective out vec2 scalarsOverW; // (front scalar / w_front, back scalar / w_back)
flat out int tetrahedronId;

vec3 vertexVC[4];
vec4 vertexDC[4];
vec2 vertexNDC[4];
float vertexScalar[4];

float orient2D(vec2 a, vec2 b, vec2 c)
{
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

void emitPoint(vec3 frontVC, float frontScalar, vec3 backVC, float backScalar)
{
  vec4 frontDC = VCDCMatrix * vec4(frontVC, 1.0);
  vec4 backDC = VCDCMatrix * vec4(backVC, 1.0);
  gl_Position = frontDC;
  frontVCOverW = vec4(frontVC, 1.0) / frontDC.w;
  backVCOverW = vec4(backVC, 1.0) / backDC.w;
  scalarsOverW = vec2(frontScalar / frontDC.w, backScalar / backDC.w);
  tetrahedronId = primitiveOffset + gl_PrimitiveIDIn;
  EmitVertex();
}

// One triangle of the outline: the thick point (front and back) and two outline vertices,
// where the tetrahedron has zero thickness.
void emitTriangle(vec3 thickFrontVC, float thickFrontScalar, vec3 thickBackVC,
  float thickBackScalar, vec2 thickNDC, int a, int b)
{
  if (orient2D(thickNDC, vertexNDC[a], vertexNDC[b]) == 0.0)
  {
    return; // empty in projection: the degenerate classes 3 and 4
  }
  emitPoint(thickFrontVC, thickFrontScalar, thickBackVC, thickBackScalar);
  emitPoint(vertexVC[a], vertexScalar[a], vertexVC[a], vertexScalar[a]);
  emitPoint(vertexVC[b], vertexScalar[b], vertexVC[b], vertexScalar[b]);
  EndPrimitive();
}

// The nearer of two points on one view ray is the one with the larger view-space z, for
// perspective and parallel projection alike (the camera looks down -z).
void emitFan(vec3 pVC, float pScalar, vec3 qVC, float qScalar, vec2 thickNDC, int outline[4],
  int count)
{
  bool pInFront = pVC.z >= qVC.z;
  vec3 frontVC = pInFront ? pVC : qVC;
  vec3 backVC = pInFront ? qVC : pVC;
  float frontScalar = pInFront ? pScalar : qScalar;
  float backScalar = pInFront ? qScalar : pScalar;
  for (int i = 0; i < count; ++i)
  {
    emitTriangle(frontVC, frontScalar, backVC, backScalar, thickNDC, outline[i],
      outline[(i + 1) % count]);
  }
}

// Class 1: vertex i projects inside the triangle of the other three. The thick point is that
// vertex and the point of the opposite face on the same ray.
void emitClass1(int i, vec3 screenWeights)
{
  int j = (i + 1) % 4;
  int k = (i + 2) % 4;
  int l = (i + 3) % 4;
  // Screen-space barycentric weights become perspective-correct ones through 1/w.
  vec3 weights = screenWeights / vec3(vertexDC[j].w, vertexDC[k].w, vertexDC[l].w);
  weights /= weights.x + weights.y + weights.z;
  vec3 faceVC = weights.x * vertexVC[j] + weights.y * vertexVC[k] + weights.z * vertexVC[l];
  float faceScalar = dot(weights, vec3(vertexScalar[j], vertexScalar[k], vertexScalar[l]));
  int outline[4] = int[4](j, k, l, j);
  emitFan(vertexVC[i], vertexScalar[i], faceVC, faceScalar, vertexNDC[i], outline, 3);
}

// Class 2: the projections of edges (a, b) and (c, d) cross at screen parameters u and v.
void emitClass2(int a, int b, int c, int d, float u, float v)
{
  // Screen-space parameters on an edge become view-space ones through the clip w.
  float t = u * vertexDC[a].w / (u * vertexDC[a].w + (1.0 - u) * vertexDC[b].w);
  float s = v * vertexDC[c].w / (v * vertexDC[c].w + (1.0 - v) * vertexDC[d].w);
  vec3 onFirstVC = mix(vertexVC[a], vertexVC[b], t);
  vec3 onSecondVC = mix(vertexVC[c], vertexVC[d], s);
  float onFirstScalar = mix(vertexScalar[a], vertexScalar[b], t);
  float onSecondScalar = mix(vertexScalar[c], vertexScalar[d], s);
  vec2 crossingNDC = mix(vertexNDC[a], vertexNDC[b], u);
  int outline[4] = int[4](a, c, b, d); // the outline alternates between the two diagonals
  emitFan(onFirstVC, onFirstScalar, onSecondVC, onSecondScalar, crossingNDC, outline, 4);
}

void main()
{
  for (int i = 0; i < 4; ++i)
  {
    vertexVC[i] = positionVCVSOutput[i];
    vertexDC[i] = VCDCMatrix * vec4(vertexVC[i], 1.0);
    if (vertexDC[i].w <= 0.0)
    {
      return; // reaches behind the eye: no valid projection
    }
    vertexNDC[i] = vertexDC[i].xy / vertexDC[i].w;
#ifdef SPT_CELL_SCALARS
    vertexScalar[i] = texelFetch(cellScalars, primitiveOffset + gl_PrimitiveIDIn).r;
#else
    vertexScalar[i] = scalarVSOutput[i];
#endif
  }

  // Class 1 test: the vertex whose smallest barycentric weight in the triangle of the other
  // three is largest; inside (or on the outline) when that weight is not negative.
  int bestVertex = -1;
  float bestWeight = -1.0e30;
  vec3 bestWeights = vec3(0.0);
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
  if (bestVertex < 0)
  {
    return; // all four vertices on one line: the projection covers no area
  }
  const float insideTolerance = 1.0e-6;
  if (bestWeight >= -insideTolerance)
  {
    emitClass1(bestVertex, max(bestWeights, vec3(0.0)));
    return;
  }

  // Class 2: of the three ways to pair the edges, the diagonals of the outline are the pair
  // whose crossing lies inside both segments.
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
