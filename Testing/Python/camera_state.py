"""A camera handed between processes as JSON (a notebook's kernel, a child process)."""

from vtkmodules.vtkRenderingCore import vtkCamera


def vtk_camera(state: dict) -> vtkCamera:
    """The vtkCamera of ``state``: position, focal_point, view_up, view_angle and
    clipping_range, as PyVista's Camera names them."""
    camera = vtkCamera()
    camera.SetPosition(state["position"])
    camera.SetFocalPoint(state["focal_point"])
    camera.SetViewUp(state["view_up"])
    camera.SetViewAngle(state["view_angle"])
    camera.SetClippingRange(state["clipping_range"])
    return camera
