"""The wheel's classes and the vtk wheel's, across the C++ boundary in both directions: VTK
objects handed to the wheel's mappers and returned by them, the wheel's mappers held and
handed back by VTK's own C++ classes, C++ observers calling Python back, and PrintSelf writing
through VTK's stream. What was compiled against the SDK must agree with the vtk wheel's
libraries on class layouts, virtual tables and the wrapping's calls."""

import vtk

import spt
from spt import data


def test_vtk_objects_into_the_wheel_and_back():
    grid = data.make_default_mesh()
    mapper = spt.vtkSPTVolumeMapper()
    mapper.SetInputData(grid)
    assert mapper.GetInput() is grid
    assert isinstance(mapper.GetInput(), vtk.vtkUnstructuredGrid)
    planes = vtk.vtkPlaneCollection()
    plane = vtk.vtkPlane()
    planes.AddItem(plane)
    mapper.SetClippingPlanes(planes)
    assert mapper.GetClippingPlanes().GetItemAsObject(0) is plane
    # The grid's reference count includes the mapper's pipeline hold on it.
    assert grid.GetReferenceCount() > 1


def test_the_wheels_objects_held_and_returned_by_vtk():
    mapper = spt.vtkSPTVolumeMapper(target_error=0.02)
    collection = vtk.vtkCollection()
    collection.AddItem(mapper)
    held = collection.GetItemAsObject(0)
    assert held is mapper and isinstance(held, spt.vtkSPTVolumeMapper)
    volume = vtk.vtkVolume()
    volume.SetMapper(mapper)
    as_vtk = vtk.vtkAbstractVolumeMapper.SafeDownCast(volume.GetMapper())
    assert spt.vtkSPTVolumeMapper.SafeDownCast(as_vtk) is mapper
    assert mapper.IsA("vtkUnstructuredGridVolumeMapper") and mapper.GetClassName() in (
        "vtkSPTVolumeMapper", "vtkPSPTVolumeMapper")
    assert volume.GetMapper().GetTargetError() == 0.02


def test_observers_are_called_back_through_vtk():
    mapper = spt.vtkSPTVolumeMapper()
    calls = []
    mapper.AddObserver("ModifiedEvent", lambda caller, event: calls.append((caller, event)))
    mapper.SetTargetError(0.125)
    assert calls == [(mapper, "ModifiedEvent")]
    mapper.SetTargetError(0.125)  # unchanged: VTK's set macro does not call Modified
    assert len(calls) == 1


def test_print_self_through_vtks_stream():
    text = str(spt.vtkSPTVolumeMapper(target_error=0.0625))
    assert "TargetError: 0.0625" in text
    assert "vtkSPTVolumeMapper" in text or "vtkPSPTVolumeMapper" in text
