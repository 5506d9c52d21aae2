"""SPT: sorting-free pre-integrated projected tetrahedra for VTK.

The compiled mappers are re-exported here, next to the pure-Python helpers:

    import vtk, spt
    mapper = spt.vtkSPTVolumeMapper()    # sorting-free (the paper's method)
    baseline = spt.vtkHAVSVolumeMapper() # sorted baseline: HAVS (Callahan et al. 2005)
    particles = spt.vtkPBVRVolumeMapper() # sorting-free baseline: particles (PBVR)
    mesher = spt.vtkTetGenMesher()        # surface -> tetrahedra (TetGen; HAVE_MESHING)
    window = spt.vtkHeadlessEGLRenderWindow()  # a render window without X (EGL)

Submodules: ``spt.data`` (data sets and the generated default mesh), ``spt.meshes`` (the
generated drill and torus meshes at any size, cached on disk), ``spt.scenes`` (named scenes),
``spt.render`` (rendering helpers and the reference), ``spt.raycast`` (the exact ray caster)
and ``spt.metrics`` (image error); ``spt.opengl_window`` names the window VTK makes without an X
display. ``python3 -m spt`` is the command line. Apart from the
library, ``spt.experiments`` holds the demo, the benchmark and the paper's figures: in the source
and build trees only (``build/bin/spt-python -m spt demo``), not in an install or the wheel.
"""

# A wheel loads the vtk installed beside it: first, that it is one the wheel was built for.
from . import _vtk_guard  # noqa: F401
# The wrapped classes derive from VTK's; importing their VTK modules first registers the bases.
from vtkmodules import vtkCommonExecutionModel as _vtkCommonExecutionModel  # noqa: F401
from vtkmodules import vtkRenderingCore as _vtkRenderingCore  # noqa: F401
from vtkmodules import vtkRenderingOpenGL2 as _vtkRenderingOpenGL2  # noqa: F401
from vtkmodules import vtkRenderingVolume as _vtkRenderingVolume  # noqa: F401
from vtkmodules import vtkParallelCore as _vtkParallelCore  # noqa: F401

import importlib.util as _importlib_util

from vtkmodules.vtkCommonCore import vtkVersion as _vtkVersion

from . import opengl_window as _opengl_window

from .SPTRenderingCore import vtkStochasticVolumeMapper, vtkTetrahedralVolumeMapper
from .SPTRenderingEGL import vtkHeadlessEGLRenderWindow
# Importing the parallel module registers vtkPSPTVolumeMapper in VTK's object factory:
# vtkSPTVolumeMapper() then makes the mapper that also renders across MPI ranks.
from .SPTRenderingParallel import vtkPSPTVolumeMapper
from .SPTRenderingSPT import vtkSPTFrameStatistics, vtkSPTVolumeMapper

# Without an X display, VTK 9.4 and later would try X first and print an error before falling
# back to EGL: name the display-less window instead, unless the user has chosen one.
_opengl_window.choose(_vtkVersion.GetVTKVersion())

__all__ = [
    "MeshingUnavailable", "vtkHeadlessEGLRenderWindow", "vtkPSPTVolumeMapper",
    "vtkSPTFrameStatistics", "vtkSPTVolumeMapper", "vtkStochasticVolumeMapper",
    "vtkTetrahedralVolumeMapper"]

#: Whether the build has the TetGen meshing module (SPT_BUILD_MESHING; the pip wheel has not):
#: without it, :mod:`spt.meshes` (the generated drill and ring) raises :class:`MeshingUnavailable`.
HAVE_MESHING = _importlib_util.find_spec(__name__ + ".SPTMeshing") is not None
if HAVE_MESHING:
    from .SPTMeshing import vtkTetGenMesher

    __all__ += ["vtkTetGenMesher"]


class MeshingUnavailable(RuntimeError):
    """Raised where the package would mesh with TetGen in a build without the meshing module."""

    def __init__(self, what: str):
        super().__init__(
            f"{what} needs SPT's TetGen meshing module (spt.vtkTetGenMesher), which this build "
            "leaves out (the pip wheel does: TetGen is not on PyPI). Use a data set that needs no "
            "meshing (e.g. the generated default mesh, `--dataset default`), or build the project "
            "from source with TetGen (SPT_BUILD_MESHING=ON).")


#: Whether the build has the baselines SPT is compared with (SPT_BUILD_BASELINES).
HAVE_BASELINES = _importlib_util.find_spec(__name__ + ".SPTRenderingBaselines") is not None
if HAVE_BASELINES:
    from .SPTRenderingBaselines import vtkHAVSVolumeMapper, vtkPBVRVolumeMapper

    __all__ += ["vtkHAVSVolumeMapper", "vtkPBVRVolumeMapper"]
__version__ = "0.1.0"
