"""Deprecated: the classes of the former single rendering module, now in SPTRenderingCore,
SPTRenderingSPT, SPTRenderingParallel, SPTRenderingBaselines and SPTRenderingEGL. Import them
from ``spt`` itself."""

from . import (HAVE_BASELINES, vtkSPTEGLRenderWindow, vtkSPTVolumeMapper,  # noqa: F401
               vtkStochasticVolumeMapper, vtkTetrahedralVolumeMapper)

if HAVE_BASELINES:
    from . import vtkHAVSVolumeMapper, vtkPBVRVolumeMapper  # noqa: F401
