"""SPT in PyVista: :func:`add_volume`, PyVista's ``Plotter.add_volume`` for unstructured meshes.

PyVista's own ``add_volume`` turns an unstructured mesh into tetrahedra and draws it with VTK's
CPU ray caster (``vtkUnstructuredGridVolumeRayCastMapper``) whatever ``mapper=`` says, with an
opacity unit distance of 1 in the mesh's units. :func:`add_volume` takes the same arguments
and the same kinds of mesh, and draws them with an SPT mapper (or one of the baselines) on the
GPU::

    import pyvista as pv
    import spt.pyvista

    plotter = pv.Plotter()
    spt.pyvista.add_volume(plotter, mesh, cmap="viridis", opacity="sigmoid")
    plotter.show()

Colour maps (any name PyVista knows, or a ``pyvista.LookupTable``), the opacity presets of
``pyvista.opacity_transfer_function`` ('linear', 'sigmoid', 'geom', ... or an array), ``clim``,
``flip_scalars``, ``log_scale`` and the scalar bar work as in PyVista. The mesh given is never
modified: the mapper draws a copy, with the scalars on the points, split into tetrahedra
where it has other cells.

In a notebook, SPT draws in the kernel's VTK: PyVista's trame backends that render on the server
(``'trame'``, the default, and ``'server'``) show its image and re-render it as the camera turns.
The client-side ones (``'client'``, ``'html'``) send the scene to vtk.js in the browser, which
has no SPT mapper; :func:`add_volume` warns when one of them is chosen (:func:`check_backend`).
"""

from __future__ import annotations

import sys
import warnings
from typing import Any, Optional, Sequence, Tuple, Union

import numpy as np
import pyvista
from vtkmodules.vtkCommonDataModel import VTK_TETRA

from . import HAVE_BASELINES, vtkSPTVolumeMapper
from .render import DEFAULT_TARGET_ERROR

#: The mappers :func:`add_volume` can draw with (``method=``).
METHODS = ("spt", "havs", "pbvr")


#: PyVista's notebook backends that render in the browser (vtk.js), without SPT.
CLIENT_SIDE_BACKENDS = ("client", "html")


class ClientSideRenderingWarning(UserWarning):
    """A notebook backend that renders in the browser, where SPT's mapper does not exist."""


def check_backend(plotter: pyvista.Plotter) -> Optional[str]:
    """Warn (:class:`ClientSideRenderingWarning`) where ``plotter``, in a notebook, would show
    its scene through vtk.js in the browser, which has no SPT mapper, and name the backend that
    shows SPT's image; returns the warning's text, or None (outside a notebook too)."""
    if not getattr(plotter, "notebook", False):
        return None
    theme = plotter.theme
    backend = str(theme.jupyter_backend or "").lower()
    mode = str(getattr(theme.trame, "default_mode", "") or "").lower()
    if backend in CLIENT_SIDE_BACKENDS:
        what = f"the Jupyter backend '{backend}'"
    elif backend in ("trame", "server") and mode == "client":
        what = "trame's default view mode 'client' (pyvista.global_theme.trame.default_mode)"
    else:
        return None
    text = (f"SPT draws its volume in the kernel's VTK, but {what} renders in the browser "
            "with vtk.js, which has no SPT mapper: the notebook would show another image or "
            "none. Use pv.set_jupyter_backend('server') (or plotter.show(jupyter_backend="
            "'server')) to see SPT's image, re-rendered by SPT as the camera turns.")
    warnings.warn(text, ClientSideRenderingWarning, stacklevel=3)
    return text


def default_opacity_unit_distance(mesh: pyvista.DataSet) -> float:
    """The opacity unit distance PyVista gives image data, for any mesh: the diagonal of the
    bounds over the number of cells along an edge. PyVista's ``length / (mean(dimensions) - 1)``
    for an image of d x d x d points is ``length / cbrt((d - 1)^3)``, the same as this for its
    (d - 1)^3 cells; a mesh's opacity then means the same at any resolution or size."""
    cells = mesh.n_cells
    if cells == 0 or not mesh.length > 0.0:
        raise ValueError("the mesh is empty: it has no cells or no extent")
    return float(mesh.length / np.cbrt(cells))


def as_dataset(mesh: Any) -> pyvista.DataSet:
    """``mesh`` as a PyVista data set with a volume: a PyVista or VTK data set as it is (not
    copied), a MultiBlock combined into one unstructured grid."""
    if isinstance(mesh, pyvista.MultiBlock):
        mesh = mesh.combine()
    elif not pyvista.is_pyvista_dataset(mesh):
        wrapped = pyvista.wrap(mesh)
        if not isinstance(wrapped, pyvista.DataSet):
            raise TypeError(f"cannot volume-render {type(mesh).__name__}: a 3D mesh is needed")
        mesh = wrapped
    if isinstance(mesh, pyvista.PolyData):
        raise TypeError("a PolyData has no volume to render; a 3D mesh is needed")
    return mesh


def tetrahedra(mesh: Any) -> pyvista.UnstructuredGrid:
    """A copy of ``mesh`` (any data set PyVista wraps, or a MultiBlock) as an unstructured grid
    of tetrahedra with its data on the points, as PyVista's ``add_volume`` draws it."""
    # A copy: the input keeps its cell data and cells.
    grid = as_dataset(mesh).cell_data_to_point_data()
    if not isinstance(grid, pyvista.UnstructuredGrid):
        grid = grid.cast_to_unstructured_grid()
    if grid.n_cells and not (grid.celltypes == VTK_TETRA).all():
        grid = grid.triangulate()
    if grid.n_cells == 0:
        raise ValueError("the mesh has no 3D cells to render")
    return grid


def _scalars(grid: pyvista.UnstructuredGrid, scalars: Any, preference: str
             ) -> Tuple[np.ndarray, str]:
    """The point scalars to draw and their title, as PyVista picks them."""
    if scalars is None:
        if grid.active_scalars is None:
            raise ValueError("the mesh has no active scalars: give `scalars`")
        title = grid.active_scalars_name
        values = np.asarray(grid.active_scalars)
    elif isinstance(scalars, str):
        title = scalars
        values = np.asarray(pyvista.get_array(grid, scalars, preference=preference, err=True))
    else:
        title = "Data"
        values = np.asarray(scalars)
        if values.ndim == 1 and values.shape[0] == grid.n_cells != grid.n_points:
            raise ValueError("cell scalars given as an array: add them to the mesh's cell data "
                             "and pass their name (they are moved to the points)")
    if not np.issubdtype(values.dtype, np.number):
        raise TypeError("the scalars are not numbers")
    if values.ndim != 1:
        raise ValueError(f"scalars of shape {values.shape}: one value per point is needed "
                         "(RGBA scalars are not supported)")
    if values.shape[0] != grid.n_points:
        raise ValueError(f"{values.shape[0]} scalars for a mesh of {grid.n_points} points")
    return values, title


def lookup_table(values: np.ndarray, clim: Union[None, float, Sequence[float]] = None,
                 cmap=None, opacity: Any = "linear",
                 n_colors: int = 256, flip_scalars: bool = False, log_scale: bool = False,
                 theme: Optional[pyvista.themes.Theme] = None) -> pyvista.LookupTable:
    """The lookup table PyVista's ``add_volume`` builds: ``cmap`` (a name, a matplotlib
    colour map or a ``pyvista.LookupTable``, default the theme's) with ``opacity`` (a preset of
    ``pyvista.opacity_transfer_function`` or an array) over ``clim`` (default the values'
    range; a number c means -c..c)."""
    if isinstance(cmap, pyvista.LookupTable):
        table = cmap
    else:
        theme = theme or pyvista.global_theme
        table = pyvista.LookupTable()
        table.apply_cmap(theme.cmap if cmap is None else cmap, n_colors, flip=flip_scalars)
        table.apply_opacity(opacity)
    if clim is None:
        clim = (float(np.nanmin(values)), float(np.nanmax(values)))
    elif isinstance(clim, (int, float)):
        clim = (-float(clim), float(clim))
    low, high = float(clim[0]), float(clim[1])
    if log_scale and low <= 0.0:
        low = sys.float_info.min
    table.scalar_range = (low, high)
    table.log_scale = log_scale
    return table


def _mapper(method: str, target_error: float):
    if method not in METHODS:
        raise ValueError(f"unknown method '{method}'; choose from {', '.join(METHODS)}")
    if method == "spt":
        mapper = vtkSPTVolumeMapper()
        mapper.SetTargetError(target_error)
        return mapper
    if not HAVE_BASELINES:
        raise ValueError(f"method '{method}' needs the baselines, which this build leaves out")
    from . import vtkHAVSVolumeMapper, vtkPBVRVolumeMapper
    return vtkHAVSVolumeMapper() if method == "havs" else vtkPBVRVolumeMapper()


def add_volume(plotter: pyvista.Plotter, mesh: Any, scalars: Any = None, clim=None,
               cmap=None, opacity: Any = "linear", n_colors: int = 256,
               flip_scalars: bool = False, reset_camera: Optional[bool] = None,
               name: Optional[str] = None, preference: str = "point",
               opacity_unit_distance: Optional[float] = None, log_scale: bool = False,
               show_scalar_bar: Optional[bool] = None, scalar_bar_args: Optional[dict] = None,
               pickable: bool = True, render: bool = True,
               target_error: float = DEFAULT_TARGET_ERROR, method: str = "spt",
               **property_args) -> pyvista.Actor:
    """Add ``mesh`` to ``plotter`` as a volume drawn by SPT; returns the actor (a
    ``pyvista.Volume``), whose ``mapper`` is the SPT mapper and ``prop`` its property.

    The arguments are those of ``pyvista.Plotter.add_volume`` (see there), but for
    ``opacity_unit_distance``, which defaults to :func:`default_opacity_unit_distance`
    (PyVista's rule for image data) rather than 1, and:

    target_error
        SPT's error target, the RMSE of premultiplied RGBA its image may keep (see
        ``vtkSPTVolumeMapper.SetTargetError``); the default suits 8-bit images.
    method
        ``'spt'`` (default), or one of the baselines, ``'havs'`` (sorted k-buffer) or
        ``'pbvr'`` (particles).
    property_args
        ``ambient``, ``diffuse``, ``specular``, ``specular_power``, ``shade``: set on the
        volume property, as PyVista does.
    """
    unknown = set(property_args) - {"ambient", "diffuse", "specular", "specular_power", "shade"}
    if unknown:
        raise TypeError(f"unexpected arguments: {', '.join(sorted(unknown))}")
    check_backend(plotter)
    mesh = as_dataset(mesh)
    # The unit distance of the mesh's own cells (an image's: PyVista's), before the split.
    unit = opacity_unit_distance or default_opacity_unit_distance(mesh)
    grid = tetrahedra(mesh)
    values, title = _scalars(grid, scalars, preference)
    grid.point_data.set_array(values, title)
    grid.point_data.active_scalars_name = title
    table = lookup_table(values, clim, cmap, opacity, n_colors, flip_scalars, log_scale,
                         plotter.theme)
    mapper = _mapper(method, target_error)
    mapper.SetInputData(grid)
    prop = pyvista.plotting.volume_property.VolumeProperty(
        lookup_table=table, opacity_unit_distance=unit, **property_args)
    volume = pyvista.Volume()
    volume.SetMapper(mapper)
    volume.prop = prop
    actor, _ = plotter.add_actor(volume, reset_camera=reset_camera,
                                 name=name or f"SPT({grid.memory_address})",
                                 pickable=pickable, render=render)
    if show_scalar_bar is None:
        show_scalar_bar = plotter.theme.show_scalar_bar or bool(scalar_bar_args)
    if show_scalar_bar:
        arguments = {"title": title, **(scalar_bar_args or {})}
        plotter.add_scalar_bar(lookup_table=table, **arguments)
    return actor
