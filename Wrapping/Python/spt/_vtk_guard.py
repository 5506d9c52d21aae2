"""Imported first by the package: refuses a vtk the extensions were not built for, before any
of them is loaded (spt.vtkcheck)."""

from vtkmodules.vtkCommonCore import vtkVersion

from . import _vtk_build, vtkcheck

vtkcheck.check(vtkVersion.GetVTKVersion(), _vtk_build.VTK_VERSION, _vtk_build.VTK_REQUIREMENT)
