/**
 * @file    vtkSPTRenderSetup.h
 * @brief   the checks every mapper's Render() starts with; shared, not wrapped
 *
 * The SPT, HAVS-like and PBVR mappers begin a frame alike: an OpenGL render window and a
 * viewport with pixels, the input pipeline brought up to date, the input turned into
 * tetrahedra by vtkSPTMeshBuffers with the scalars the mapper selects, and a volume property
 * they can render. What is wrong is reported once per input build with vtkErrorMacro (or
 * vtkWarningMacro, for cells left out) on the mapper itself, so that observers of the mapper
 * see it and a scene that is drawn again and again does not repeat it.
 */

#ifndef vtkSPTRenderSetup_h
#define vtkSPTRenderSetup_h

#include "SPTRenderingModule.h" // For export macro
#include "vtkOpenGLState.h"     // For SavedState
#include "vtkType.h"            // For vtkMTimeType

class vtkOpenGLRenderWindow;
class vtkRenderer;
class vtkSPTMeshBuffers;
struct vtkSPTViewMatrices;
class vtkUnstructuredGridVolumeMapper;
class vtkVolume;

class SPTRENDERING_EXPORT vtkSPTRenderSetup
{
public:
  /// What the mapper draws into: the OpenGL window and the renderer's tiled viewport.
  struct Target
  {
    vtkOpenGLRenderWindow* Window = nullptr;
    int Width = 0;
    int Height = 0;
    int X = 0;
    int Y = 0;
  };

  /**
   * The OpenGL render window and viewport of the renderer. False, with an error, when the
   * window is not an OpenGL one; false without one when the viewport has no pixels.
   */
  static bool GetTarget(vtkUnstructuredGridVolumeMapper* mapper, vtkRenderer* ren, Target& target);

  /**
   * GetTarget(), and if the mapper last drew into another window (`context`), release what it
   * holds there first: a mapper keeps its GPU resources in one context at a time. `context`
   * becomes the target's window.
   */
  static bool BeginFrame(vtkUnstructuredGridVolumeMapper* mapper, vtkRenderer* ren, Target& target,
    vtkOpenGLRenderWindow*& context);

  /**
   * The OpenGL state that the mappers change while they draw, restored when this goes out of
   * scope: blending, depth test and function, culling, scissor test, the depth and color
   * masks, the clear color and depth, the point size and the viewport.
   */
  struct SavedState
  {
    explicit SavedState(vtkOpenGLState* state);
    ~SavedState();
    SavedState(const SavedState&) = delete;
    SavedState& operator=(const SavedState&) = delete;
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
   * Update the mapper's input and rebuild the mesh if it changed, with the mapper's scalar
   * selection and `component` of a multi-component array (-1: the magnitude). True when there
   * are tetrahedra to draw. Errors (no input, no scalars, the selected array missing, point ids
   * out of range, cell scalars where `cellScalars` is false, ...) and the warning about cells
   * left out for non-finite values are reported once per build.
   */
  bool UpdateMesh(vtkUnstructuredGridVolumeMapper* mapper, vtkSPTMeshBuffers* mesh, int component,
    bool cellScalars);

  /**
   * Whether the volume's property can be rendered (independent components); an error if not.
   */
  static bool CheckProperty(vtkUnstructuredGridVolumeMapper* mapper, vtkVolume* vol);

  /**
   * Compute the frame's matrices; false, with an error, when they are not finite (a camera
   * or a volume transform with NaN or Inf in it, as ResetCamera() makes for such bounds).
   */
  static bool ComputeMatrices(vtkUnstructuredGridVolumeMapper* mapper, vtkRenderer* ren,
    vtkVolume* vol, const vtkSPTMeshBuffers* mesh, vtkSPTViewMatrices& matrices);

  /**
   * Whether opaque geometry may have been drawn into the renderer's depth buffer before the
   * volume: a visible 3D prop other than a volume with opaque geometry, or a depth buffer
   * preserved from an earlier renderer. Without it, the shaders leave out the scene depth.
   */
  static bool HasOpaqueScene(vtkRenderer* ren);

private:
  vtkMTimeType ReportedMeshError = 0;
  vtkMTimeType ReportedSkippedCells = 0;
};

#endif
