"""Deprecated: the classes of the former single rendering module, now in SPTRenderingCore,
SPTRenderingSPT, SPTRenderingParallel, SPTRenderingBaselines and SPTRenderingEGL. Import them
from ``spt`` itself."""

from . import (vtkHAVSVolumeMapper, vtkPBVRVolumeMapper, vtkSPTEGLRenderWindow,  # noqa: F401
               vtkSPTVolumeMapper, vtkStochasticVolumeMapper, vtkTetrahedralVolumeMapper)
