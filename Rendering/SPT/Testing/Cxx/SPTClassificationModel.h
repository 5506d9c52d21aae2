// The exact geometry against which TestSPTClassification checks the projection and
// classification of the SPT geometry shader, on the CPU in single precision (GLM): the
// projected outline of a tetrahedron (the convex hull of its projected vertices) and the exact
// entry and exit of a view ray through it; and the segment that the fragment shader finds from
// the cell's face planes and scalar plane (planeSegment() in vtkSPTTetrahedraFS.glsl).

#ifndef SPTClassificationModel_h
#define SPTClassificationModel_h

#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace SPTClassificationModel
{
struct Tetrahedron
{
  std::array<glm::vec3, 4> Points; // view coordinates
  std::array<float, 4> Scalars;
  int ExpectedTriangles; // non-empty triangles, or 0 when not checked
  const char* Name;
};

// Where a view ray enters and leaves a tetrahedron (view coordinates), the scalars there and
// the length between.
struct Segment
{
  glm::vec3 Front;
  glm::vec3 Back;
  float FrontScalar;
  float BackScalar;
  float Thickness;
};

inline float Cross2(glm::vec2 a, glm::vec2 b, glm::vec2 c)
{
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// Convex hull of four points, counter-clockwise, without collinear points (Andrew's monotone
// chain: the lower hull from left to right, then the upper hull back).
inline std::vector<glm::vec2> Hull(std::array<glm::vec2, 4> p)
{
  std::sort(p.begin(), p.end(),
    [](glm::vec2 a, glm::vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  std::vector<glm::vec2> hull;
  for (int pass = 0; pass < 2; ++pass)
  {
    const size_t start = hull.size();
    for (int n = 0; n < 4; ++n)
    {
      const glm::vec2 q = p[pass == 0 ? n : 3 - n];
      while (hull.size() >= start + 2 && Cross2(hull[hull.size() - 2], hull.back(), q) <= 0.0f)
      {
        hull.pop_back();
      }
      hull.push_back(q);
    }
    hull.pop_back(); // the first point of the other half
  }
  return hull;
}

// Signed distance-like margin of q inside a convex counter-clockwise polygon (>0 inside).
inline float InsideMargin(const std::vector<glm::vec2>& polygon, glm::vec2 q)
{
  float margin = 1.0e30f;
  for (size_t i = 0; i < polygon.size(); ++i)
  {
    const glm::vec2 a = polygon[i], b = polygon[(i + 1) % polygon.size()];
    const float edge = glm::length(b - a);
    if (edge > 0.0f)
    {
      margin = std::min(margin, Cross2(a, b, q) / edge);
    }
  }
  return margin;
}

// The scalar at p, interpolated linearly (barycentric weights) over the tetrahedron.
inline float ScalarAt(const Tetrahedron& t, glm::vec3 p)
{
  const glm::mat3 m(
    t.Points[1] - t.Points[0], t.Points[2] - t.Points[0], t.Points[3] - t.Points[0]);
  const glm::vec3 w = glm::inverse(m) * (p - t.Points[0]);
  return t.Scalars[0] * (1.0f - w.x - w.y - w.z) + t.Scalars[1] * w.x + t.Scalars[2] * w.y +
    t.Scalars[3] * w.z;
}

// The exact entry and exit of a ray (origin o, direction d) through a tetrahedron, by clipping
// the ray against its four face planes; false when the ray misses it.
inline bool ExactSegment(const Tetrahedron& t, glm::vec3 o, glm::vec3 d, Segment& segment)
{
  float enter = -1.0e30f, exit = 1.0e30f;
  for (int f = 0; f < 4; ++f)
  {
    const glm::vec3 a = t.Points[(f + 1) % 4], b = t.Points[(f + 2) % 4], c = t.Points[(f + 3) % 4];
    glm::vec3 n = glm::cross(b - a, c - a);
    if (glm::dot(n, t.Points[f] - a) > 0.0f)
    {
      n = -n; // outward
    }
    const float denominator = glm::dot(n, d);
    const float numerator = glm::dot(n, a - o);
    if (denominator == 0.0f)
    {
      if (numerator < 0.0f)
      {
        return false;
      }
      continue;
    }
    const float s = numerator / denominator;
    if (denominator < 0.0f)
    {
      enter = std::max(enter, s);
    }
    else
    {
      exit = std::min(exit, s);
    }
  }
  if (enter > exit)
  {
    return false;
  }
  segment.Front = o + enter * d;
  segment.Back = o + exit * d;
  segment.FrontScalar = ScalarAt(t, segment.Front);
  segment.BackScalar = ScalarAt(t, segment.Back);
  segment.Thickness = glm::distance(segment.Front, segment.Back);
  return true;
}

// The segment at the NDC point q as the fragment shader finds it from the cell's face planes
// and scalar plane in NDC (the rows of a tetrahedron's captured vertices); the thickness is 0
// where the planes leave no segment.
inline Segment PlaneSegment(const glm::vec4 facePlanes[4], const glm::vec4& scalarPlane,
  glm::vec2 q, const glm::mat4& projection)
{
  float enter = -1.0f, leave = 1.0f;
  for (int f = 0; f < 4; ++f)
  {
    const glm::vec4& plane = facePlanes[f];
    const float atZero = plane.x * q.x + plane.y * q.y + plane.w;
    if (plane.z < 0.0f)
    {
      enter = std::max(enter, -atZero / plane.z);
    }
    else if (plane.z > 0.0f)
    {
      leave = std::min(leave, -atZero / plane.z);
    }
  }
  const glm::mat4 inverse = glm::inverse(projection);
  const glm::vec4 front = inverse * glm::vec4(q, enter, 1.0f);
  const glm::vec4 back = inverse * glm::vec4(q, leave, 1.0f);
  Segment segment;
  segment.Front = glm::vec3(front) / front.w;
  segment.Back = glm::vec3(back) / back.w;
  segment.FrontScalar = -glm::dot(scalarPlane, glm::vec4(q, enter, 1.0f)) / front.w;
  segment.BackScalar = -glm::dot(scalarPlane, glm::vec4(q, leave, 1.0f)) / back.w;
  segment.Thickness = enter < leave ? glm::distance(segment.Front, segment.Back) : 0.0f;
  return segment;
}
}

#endif
