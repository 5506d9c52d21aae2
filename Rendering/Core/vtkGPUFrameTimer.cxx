#include "vtkGPUFrameTimer.h"

#include "vtkOpenGLLoader.h"

bool vtkGPUFrameTimer::Start()
{
  // Timer queries are OpenGL 3.3 (GL_ARB_timer_query); without them the time is unknown.
  if (!this->Query && !vtkOpenGLLoader::HasVersion(3, 3) &&
    !vtkOpenGLLoader::HasExtension("GL_ARB_timer_query"))
  {
    return false;
  }
  // GL_TIME_ELAPSED queries do not nest: leave the time unknown inside someone else's.
  GLint activeQuery = 0;
  glGetQueryiv(GL_TIME_ELAPSED, GL_CURRENT_QUERY, &activeQuery);
  if (activeQuery != 0)
  {
    return false;
  }
  if (!this->Query)
  {
    glGenQueries(1, &this->Query);
  }
  glBeginQuery(GL_TIME_ELAPSED, this->Query);
  this->Running = true;
  return true;
}

double vtkGPUFrameTimer::Stop()
{
  if (!this->Running)
  {
    return -1.0;
  }
  glEndQuery(GL_TIME_ELAPSED);
  this->Running = false;
  GLuint64 nanoseconds = 0;
  glGetQueryObjectui64v(this->Query, GL_QUERY_RESULT, &nanoseconds);
  return 1.0e-9 * static_cast<double>(nanoseconds);
}

void vtkGPUFrameTimer::Release(bool contextCurrent)
{
  if (this->Query && contextCurrent)
  {
    glDeleteQueries(1, &this->Query);
  }
  this->Query = 0;
  this->Running = false;
}
