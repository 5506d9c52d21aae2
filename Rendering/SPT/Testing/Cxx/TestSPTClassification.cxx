// Unit test of the GPU projection and classification (Shirley-Tuchman's classes) of the SPT
// geometry shader: the shader itself runs under transform feedback, and its triangles are
// checked on the CPU (GLM) against the exact geometry, for the four classes and for random
// tetrahedra, in perspective and parallel projection:
// - the triangles cover exactly the projected outline (the convex hull of the four projected
//   vertices), one triangle when it is a triangle and two when it is a quadrilateral: each
//   point inside it lies in exactly one triangle, none outside;
// - at every point, the front and back points and scalars that the fragment shader finds from
//   the cell's face planes and scalar plane are the exact entry and exit of the view ray
//   through the tetrahedron;
// - the triangles lie no deeper than any of their segments' fronts (the early depth test).
// The exact geometry, on the CPU, is SPTClassificationModel.h.

#include "vtkNew.h"
#include "vtkOpenGLLoader.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkShaderProgram.h"
#include "vtkTransformFeedback.h"

#include "SPTClassificationModel.h"
#include "SPTTestWindow.h"

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#ifndef SPT_SHADER_DIR
#error "SPT_SHADER_DIR must name Rendering/SPT/shaders"
#endif

namespace
{
using namespace SPTClassificationModel;

// One emitted vertex, as captured: clip position, then the cell's planes (flat outputs).
struct Captured
{
  glm::vec4 Position;
  glm::vec4 FacePlanes[4];
  glm::vec4 ScalarPlane;
};
static_assert(sizeof(Captured) == 24 * sizeof(float), "captured vertices must be packed");

// A shader file as the mapper has it, its defines empty and the face-plane code substituted.
std::string ReadShader(const char* name)
{
  std::ifstream file(std::string(SPT_SHADER_DIR) + "/" + name);
  std::stringstream text;
  text << file.rdbuf();
  std::string source = text.str();
  vtkShaderProgram::Substitute(source, "//Volume::Defines::Dec", "");
  if (source.find("//SPT::FacePlane::Impl") != std::string::npos)
  {
    vtkShaderProgram::Substitute(
      source, "//SPT::FacePlane::Impl", ReadShader("vtkSPTFacePlane.glsl"));
  }
  return source;
}

std::vector<Tetrahedron> MakeTetrahedra()
{
  std::vector<Tetrahedron> tetrahedra = {
    { { glm::vec3(0.1f, 0.05f, -5.0f), glm::vec3(-1.0f, -0.8f, -6.0f),
        glm::vec3(1.1f, -0.7f, -6.2f), glm::vec3(0.0f, 1.0f, -5.8f) },
      { 0.2f, 0.9f, 0.4f, 0.6f }, 1, "class 1 (thick vertex in front)" },
    { { glm::vec3(0.1f, 0.05f, -6.5f), glm::vec3(-1.0f, -0.8f, -5.0f),
        glm::vec3(1.1f, -0.7f, -5.2f), glm::vec3(0.0f, 1.0f, -5.4f) },
      { 0.7f, 0.1f, 0.3f, 0.5f }, 1, "class 1 (thick vertex behind)" },
    { { glm::vec3(-1.0f, 0.1f, -5.0f), glm::vec3(1.0f, -0.1f, -5.1f), glm::vec3(0.1f, -1.0f, -6.0f),
        glm::vec3(-0.1f, 1.0f, -6.3f) },
      { 0.0f, 1.0f, 0.25f, 0.75f }, 2, "class 2" },
    { { glm::vec3(0.0f, 0.0f, -5.0f), glm::vec3(-1.2f, 0.0f, -6.0f), glm::vec3(1.2f, 0.0f, -6.0f),
        glm::vec3(0.0f, 1.0f, -6.0f) },
      { 0.5f, 0.0f, 1.0f, 0.3f }, 1, "class 3 (vertex projects onto an edge)" },
    { { glm::vec3(0.0f, 0.0f, -5.0f), glm::vec3(0.0f, 0.0f, -6.5f), glm::vec3(1.0f, 0.0f, -5.7f),
        glm::vec3(0.0f, 1.0f, -5.9f) },
      { 0.1f, 0.8f, 0.4f, 0.6f }, 1, "class 4 (two vertices on one ray)" },
  };
  std::mt19937 random(7);
  std::uniform_real_distribution<float> coordinate(-1.5f, 1.5f), depth(-8.0f, -4.0f),
    unit(0.0f, 1.0f);
  for (int n = 0; n < 400; ++n)
  {
    Tetrahedron t{ {}, {}, 0, "random" };
    for (int v = 0; v < 4; ++v)
    {
      t.Points[v] = glm::vec3(coordinate(random), coordinate(random), depth(random));
      t.Scalars[v] = unit(random);
    }
    // Skip slivers, whose exact answer is ill-conditioned in single precision.
    const float volume = std::abs(glm::dot(
      t.Points[1] - t.Points[0], glm::cross(t.Points[2] - t.Points[0], t.Points[3] - t.Points[0])));
    if (volume > 0.05f)
    {
      tetrahedra.push_back(t);
    }
  }
  return tetrahedra;
}

// A tetrahedron's projected outline and the triangles emitted for it, in NDC.
struct ScreenGeometry
{
  std::vector<glm::vec2> Hull;
  float HullArea = 0.0f;
  std::vector<std::array<glm::vec2, 3>> Triangles;
};

// The triangles cover the outline's area, with as many non-empty as the class asks.
int CheckArea(const Tetrahedron& t, const ScreenGeometry& screen)
{
  int failures = 0;
  float area = 0.0f;
  int nonEmpty = 0;
  for (const std::array<glm::vec2, 3>& s : screen.Triangles)
  {
    const float a = std::abs(0.5f * Cross2(s[0], s[1], s[2]));
    area += a;
    nonEmpty += a > 1.0e-5f * screen.HullArea;
  }
  if (std::abs(area - screen.HullArea) > 1.0e-4f * screen.HullArea + 1.0e-7f)
  {
    std::cerr << t.Name << ": triangles cover " << area << ", the outline " << screen.HullArea
              << "\n";
    ++failures;
  }
  if (t.ExpectedTriangles && nonEmpty != t.ExpectedTriangles)
  {
    std::cerr << t.Name << ": " << nonEmpty << " non-empty triangles, expected "
              << t.ExpectedTriangles << "\n";
    ++failures;
  }
  return failures;
}

// Weights of q in every non-empty triangle; true if q is too close to any edge to call.
bool Weights(const ScreenGeometry& screen, glm::vec2 q, std::vector<glm::vec3>& weights)
{
  weights.assign(screen.Triangles.size(), glm::vec3(-1.0f));
  bool ambiguous = false;
  for (size_t i = 0; i < screen.Triangles.size(); ++i)
  {
    const std::array<glm::vec2, 3>& s = screen.Triangles[i];
    const float whole = Cross2(s[0], s[1], s[2]);
    if (std::abs(whole) > 1.0e-5f * screen.HullArea)
    {
      weights[i] =
        glm::vec3(Cross2(q, s[1], s[2]), Cross2(s[0], q, s[2]), Cross2(s[0], s[1], q)) / whole;
      ambiguous = ambiguous ||
        std::abs(std::min(weights[i].x, std::min(weights[i].y, weights[i].z))) < 1.0e-4f;
    }
  }
  return ambiguous;
}

// The checks of one projection, perspective or parallel.
class Checker
{
public:
  Checker(bool parallel)
    : Projection(parallel ? glm::ortho(-2.0f, 2.0f, -2.0f, 2.0f, 1.0f, 20.0f)
                          : glm::perspective(glm::radians(40.0f), 1.0f, 1.0f, 20.0f))
    , Name(parallel ? " (parallel)" : " (perspective)")
  {
  }

  int Check(const Tetrahedron& t, const std::vector<Captured>& vertices, std::mt19937& random) const
  {
    const ScreenGeometry screen = this->Screen(t, vertices);
    int failures = CheckArea(t, screen);

    // Sample the outline's bounding box: coverage and the interpolated segment.
    glm::vec2 lo(1.0e30f), hi(-1.0e30f);
    for (const glm::vec2& p : screen.Hull)
    {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    std::uniform_real_distribution<float> ux(lo.x, hi.x), uy(lo.y, hi.y);
    const float scale = std::max(hi.x - lo.x, hi.y - lo.y);
    for (int n = 0; n < 60; ++n)
    {
      const glm::vec2 q(ux(random), uy(random));
      failures += this->CheckPoint(t, vertices, screen, q, scale);
    }
    return failures;
  }

  const glm::mat4 Projection;

private:
  ScreenGeometry Screen(const Tetrahedron& t, const std::vector<Captured>& vertices) const
  {
    ScreenGeometry screen;
    std::array<glm::vec2, 4> projected;
    for (int v = 0; v < 4; ++v)
    {
      const glm::vec4 clip = this->Projection * glm::vec4(t.Points[v], 1.0f);
      projected[v] = glm::vec2(clip) / clip.w;
    }
    screen.Hull = Hull(projected);
    for (size_t i = 1; i + 1 < screen.Hull.size(); ++i)
    {
      screen.HullArea += 0.5f * Cross2(screen.Hull[0], screen.Hull[i], screen.Hull[i + 1]);
    }
    screen.Triangles.resize(vertices.size() / 3);
    for (size_t i = 0; i < vertices.size(); ++i)
    {
      screen.Triangles[i / 3][i % 3] = glm::vec2(vertices[i].Position) / vertices[i].Position.w;
    }
    return screen;
  }

  // A point inside the outline lies in exactly one triangle, a point outside in none.
  int CheckPoint(const Tetrahedron& t, const std::vector<Captured>& vertices,
    const ScreenGeometry& screen, glm::vec2 q, float scale) const
  {
    const float margin = InsideMargin(screen.Hull, q);
    std::vector<glm::vec3> weights;
    if (std::abs(margin) < 1.0e-3f * scale || Weights(screen, q, weights))
    {
      return 0; // too close to the outline or to an edge to call
    }
    int failures = 0;
    int containing = 0;
    for (size_t i = 0; i < weights.size(); ++i)
    {
      if (std::min(weights[i].x, std::min(weights[i].y, weights[i].z)) >= 0.0f)
      {
        ++containing;
        failures += this->CheckSegment(t, &vertices[3 * i], q);
      }
    }
    const int expected = margin > 0.0f ? 1 : 0;
    if (containing != expected)
    {
      std::cerr << t.Name << this->Name << ": point (" << q.x << ", " << q.y << ") "
                << (expected ? "inside" : "outside") << " the outline lies in " << containing
                << " triangles\n";
      ++failures;
    }
    return failures;
  }

  // What the fragment shader finds at q from the triangle's planes is the exact entry and exit
  // of the view ray, and the triangle's vertices lie no deeper than the entry (the early depth
  // test).
  int CheckSegment(const Tetrahedron& t, const Captured* triangle, glm::vec2 q) const
  {
    const glm::mat4 inverse = glm::inverse(this->Projection);
    const glm::vec4 nearPoint = inverse * glm::vec4(q, -1.0f, 1.0f);
    const glm::vec4 farPoint = inverse * glm::vec4(q, 1.0f, 1.0f);
    const glm::vec3 origin = glm::vec3(nearPoint) / nearPoint.w;
    const glm::vec3 direction = glm::normalize(glm::vec3(farPoint) / farPoint.w - origin);
    Segment exact;
    if (!ExactSegment(t, origin, direction, exact))
    {
      return 0; // grazing ray
    }
    const Segment found =
      PlaneSegment(triangle[0].FacePlanes, triangle[0].ScalarPlane, q, this->Projection);
    const float tolerance = 2.0e-3f;
    int failures = 0;
    if (glm::distance(found.Front, exact.Front) > tolerance ||
      glm::distance(found.Back, exact.Back) > tolerance ||
      std::abs(found.Thickness - exact.Thickness) > tolerance ||
      std::abs(found.FrontScalar - exact.FrontScalar) > tolerance ||
      std::abs(found.BackScalar - exact.BackScalar) > tolerance)
    {
      std::cerr << t.Name << this->Name << " at (" << q.x << ", " << q.y << "): thickness "
                << found.Thickness << " vs exact " << exact.Thickness << ", scalars "
                << found.FrontScalar << " " << found.BackScalar << " vs exact " << exact.FrontScalar
                << " " << exact.BackScalar << "\n";
      ++failures;
    }
    const glm::vec4 exactFrontDC = this->Projection * glm::vec4(exact.Front, 1.0f);
    const float exactFrontDepth = exactFrontDC.z / exactFrontDC.w;
    for (int v = 0; v < 3; ++v)
    {
      const float depth = triangle[v].Position.z / triangle[v].Position.w;
      if (depth > exactFrontDepth + 1.0e-5f)
      {
        std::cerr << t.Name << this->Name << " at (" << q.x << ", " << q.y
                  << "): a triangle at depth " << depth << " behind the segment's front at "
                  << exactFrontDepth << "\n";
        return failures + 1;
      }
    }
    return failures;
  }

  const char* Name;
};

// The mapper's vertex and geometry shaders, compiled by the window's shader cache as the
// mapper's are, with their outputs captured; null (after the cache's error) if they do not link.
vtkShaderProgram* ReadyProgram(vtkOpenGLRenderWindow* window, vtkTransformFeedback* capture)
{
  // A role gives only the size of a captured output: four floats for each of these.
  capture->AddVarying(vtkTransformFeedback::Vertex_ClipCoordinate_F, "gl_Position");
  for (const char* plane : { "facePlaneNDC[0]", "facePlaneNDC[1]", "facePlaneNDC[2]",
         "facePlaneNDC[3]", "scalarPlaneNDC" })
  {
    capture->AddVarying(vtkTransformFeedback::Color_RGBA_F, plane);
  }
  return window->GetShaderCache()->ReadyShaderProgram(ReadShader("vtkSPTTetrahedraVS.glsl").c_str(),
    "//VTK::System::Dec\nvoid main()\n{\n}\n", ReadShader("vtkSPTTetrahedraGS.glsl").c_str(),
    capture);
}

// Four vertices per tetrahedron in, up to two triangles each out.
void UploadTetrahedra(vtkShaderProgram* program, const std::vector<Tetrahedron>& tetrahedra,
  GLuint vao, const GLuint buffers[3])
{
  std::vector<float> points, scalars;
  for (const Tetrahedron& t : tetrahedra)
  {
    for (int v = 0; v < 4; ++v)
    {
      points.insert(points.end(), { t.Points[v].x, t.Points[v].y, t.Points[v].z });
      scalars.push_back(t.Scalars[v]);
    }
  }
  glBindVertexArray(vao);
  auto attribute = [&](GLuint buffer, const char* name, int size, const std::vector<float>& values)
  {
    glBindBuffer(GL_ARRAY_BUFFER, buffer);
    glBufferData(GL_ARRAY_BUFFER, values.size() * sizeof(float), values.data(), GL_STATIC_DRAW);
    const GLint location = glGetAttribLocation(program->GetHandle(), name);
    glEnableVertexAttribArray(location);
    glVertexAttribPointer(location, size, GL_FLOAT, GL_FALSE, 0, nullptr);
  };
  attribute(buffers[0], "vertexMC", 3, points);
  attribute(buffers[1], "scalarTF", 1, scalars);
  const size_t capacity = tetrahedra.size() * 2 * 3; // at most two triangles each
  glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, buffers[2]);
  glBufferData(GL_TRANSFORM_FEEDBACK_BUFFER, capacity * sizeof(Captured), nullptr, GL_STATIC_READ);
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, buffers[2]);
}

// The n-th tetrahedron drawn alone, so that its triangles are known to be its own.
std::vector<Captured> CaptureTriangles(GLuint query, size_t n)
{
  glEnable(GL_RASTERIZER_DISCARD);
  glBeginQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN, query);
  glBeginTransformFeedback(GL_TRIANGLES);
  glDrawArrays(GL_LINES_ADJACENCY, static_cast<GLint>(4 * n), 4);
  glEndTransformFeedback();
  glEndQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN);
  glDisable(GL_RASTERIZER_DISCARD);
  GLuint written = 0;
  glGetQueryObjectuiv(query, GL_QUERY_RESULT, &written);
  std::vector<Captured> captured(3 * written);
  glGetBufferSubData(
    GL_TRANSFORM_FEEDBACK_BUFFER, 0, captured.size() * sizeof(Captured), captured.data());
  return captured;
}

// Every tetrahedron in one projection, until the failures (counted on from those given) pass 20.
int CheckProjection(vtkShaderProgram* program, GLuint query,
  const std::vector<Tetrahedron>& tetrahedra, bool parallel, std::mt19937& random, int failures)
{
  Checker checker(parallel);
  glm::mat4 matrices[3] = { glm::mat4(1.0f), checker.Projection, glm::inverse(checker.Projection) };
  program->SetUniformMatrix4x4("MCVCMatrix", glm::value_ptr(matrices[0]));
  program->SetUniformMatrix4x4("VCDCMatrix", glm::value_ptr(matrices[1]));
  program->SetUniformMatrix4x4("DCVCMatrix", glm::value_ptr(matrices[2]));
  program->SetUniformi("primitiveOffset", 0);
  for (size_t n = 0; n < tetrahedra.size(); ++n)
  {
    failures += checker.Check(tetrahedra[n], CaptureTriangles(query, n), random);
    if (failures > 20)
    {
      break;
    }
  }
  return failures;
}
}

int TestSPTClassification(int, char*[])
{
  SPTTestWindow::RawContext raw(16);
  if (!raw.Context)
  {
    std::cerr << "Needs an OpenGL render window.\n";
    return 125;
  }

  vtkNew<vtkTransformFeedback> capture;
  vtkShaderProgram* program = ReadyProgram(raw.Context, capture);
  if (!program)
  {
    return EXIT_FAILURE;
  }

  const std::vector<Tetrahedron> tetrahedra = MakeTetrahedra();
  GLuint vao, buffers[3], query;
  glGenVertexArrays(1, &vao);
  glGenBuffers(3, buffers);
  glGenQueries(1, &query);
  UploadTetrahedra(program, tetrahedra, vao, buffers);

  int failures = 0;
  std::mt19937 random(11);
  for (bool parallel : { false, true })
  {
    failures = CheckProjection(program, query, tetrahedra, parallel, random, failures);
  }
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
  {
    std::cerr << "OpenGL error " << error << "\n";
    ++failures;
  }
  glBindVertexArray(0);
  glDeleteQueries(1, &query);
  glDeleteBuffers(3, buffers);
  glDeleteVertexArrays(1, &vao);
  std::cout << tetrahedra.size() << " tetrahedra checked in two projections, " << failures
            << " failures\n";
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
