/**
 * @class   vtkSavedGLState
 * @brief   the OpenGL state the module's mappers change while they draw, restored on scope exit
 *
 * vtkScopedOverBlending, beside it, sets and restores the state of a resolve into the window.
 *
 * Blending, depth test and function, culling, scissor test, the depth and color masks, the
 * clear color and depth, the point size and the viewport are saved when an instance is made and
 * restored when it goes out of scope, on every return path of a mapper's Render().
 *
 * Private helper of the module's mappers; not wrapped.
 */

#ifndef vtkSavedGLState_h
#define vtkSavedGLState_h

#include "SPTRenderingCoreModule.h" // For export macro
#include "vtkOpenGLState.h"         // For the scoped savers

class SPTRENDERINGCORE_EXPORT vtkSavedGLState
{
public:
  explicit vtkSavedGLState(vtkOpenGLState* state);
  ~vtkSavedGLState();
  vtkSavedGLState(const vtkSavedGLState&) = delete;
  vtkSavedGLState& operator=(const vtkSavedGLState&) = delete;

private:
  vtkOpenGLState* State;
  double ClearDepth = 1.0;
  float PointSize = 1.0f;
  vtkOpenGLState::ScopedglEnableDisable Blend;
  vtkOpenGLState::ScopedglEnableDisable DepthTest;
  vtkOpenGLState::ScopedglEnableDisable CullFace;
  vtkOpenGLState::ScopedglEnableDisable ScissorTest;
  vtkOpenGLState::ScopedglDepthMask DepthMask;
  vtkOpenGLState::ScopedglDepthFunc DepthFunction;
  vtkOpenGLState::ScopedglColorMask ColorMask;
  vtkOpenGLState::ScopedglClearColor ClearColor;
  vtkOpenGLState::ScopedglViewport Viewport;
};

/**
 * Premultiplied colors composited "over" what the window holds, in a viewport, with neither
 * depth test nor depth writes: the state of a resolve into the window, set when an instance
 * is made and restored when it goes out of scope.
 */
class SPTRENDERINGCORE_EXPORT vtkScopedOverBlending
{
public:
  vtkScopedOverBlending(vtkOpenGLState* state, int x, int y, int width, int height);
  vtkScopedOverBlending(const vtkScopedOverBlending&) = delete;
  vtkScopedOverBlending& operator=(const vtkScopedOverBlending&) = delete;

private:
  vtkOpenGLState::ScopedglEnableDisable Blend;
  vtkOpenGLState::ScopedglEnableDisable DepthTest;
  vtkOpenGLState::ScopedglBlendFuncSeparate BlendFunction;
  vtkOpenGLState::ScopedglDepthMask DepthMask;
  vtkOpenGLState::ScopedglViewport Viewport;
};

#endif
