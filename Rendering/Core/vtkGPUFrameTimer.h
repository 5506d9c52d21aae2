/**
 * @class   vtkGPUFrameTimer
 * @brief   the GPU time of a stretch of OpenGL commands, with a GL_TIME_ELAPSED query
 *
 * Start() begins a query unless another GL_TIME_ELAPSED query is active (they do not nest:
 * the time is then unknown); Stop() ends it and waits for the result, in seconds. Unlike
 * glFinish() and a CPU clock, the time is the GPU's own, whatever the host did meanwhile.
 *
 * Private helper of SPT::RenderingCore, shared by the mappers; not wrapped.
 */

#ifndef vtkGPUFrameTimer_h
#define vtkGPUFrameTimer_h

#include "SPTRenderingCoreModule.h" // For export macro

class SPTRENDERINGCORE_EXPORT vtkGPUFrameTimer
{
public:
  vtkGPUFrameTimer() = default;
  vtkGPUFrameTimer(const vtkGPUFrameTimer&) = delete;
  vtkGPUFrameTimer& operator=(const vtkGPUFrameTimer&) = delete;

  /// Begin timing in the current context; false when another time query is active.
  bool Start();
  /// End timing and wait for the result: seconds, or -1 when Start() did not begin.
  double Stop();
  /// Delete the query; call with the context current (or with none, forgetting it).
  void Release(bool contextCurrent);

private:
  unsigned int Query = 0;
  bool Running = false;
};

#endif
