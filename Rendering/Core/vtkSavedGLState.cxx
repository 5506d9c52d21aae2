#include "vtkSavedGLState.h"

#include "vtkOpenGLLoader.h"

vtkSavedGLState::vtkSavedGLState(vtkOpenGLState* state)
  : State(state)
  , Blend(state, GL_BLEND)
  , DepthTest(state, GL_DEPTH_TEST)
  , CullFace(state, GL_CULL_FACE)
  , ScissorTest(state, GL_SCISSOR_TEST)
  , DepthMask(state)
  , DepthFunction(state)
  , ColorMask(state)
  , ClearColor(state)
  , Viewport(state)
{
  // vtkOpenGLState has no scoped savers of these two.
  state->vtkglGetDoublev(GL_DEPTH_CLEAR_VALUE, &this->ClearDepth);
  state->vtkglGetFloatv(GL_POINT_SIZE, &this->PointSize);
}

vtkSavedGLState::~vtkSavedGLState()
{
  this->State->vtkglClearDepth(this->ClearDepth);
  this->State->vtkglPointSize(this->PointSize);
}

vtkScopedOverBlending::vtkScopedOverBlending(
  vtkOpenGLState* state, int x, int y, int width, int height)
  : Blend(state, GL_BLEND)
  , DepthTest(state, GL_DEPTH_TEST)
  , BlendFunction(state)
  , DepthMask(state)
  , Viewport(state)
{
  state->vtkglViewport(x, y, width, height);
  state->vtkglEnable(GL_BLEND);
  state->vtkglDisable(GL_DEPTH_TEST);
  state->vtkglDepthMask(GL_FALSE);
  state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
}
