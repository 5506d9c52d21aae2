"""Benchmarks: the race to quality, and the time and GPU memory of SPT, HAVS-like, PBVR and
VTK's projected tetrahedra.

``build/bin/spt-python -m spt bench`` measures, on this machine and in one process, the
sections of :data:`SECTIONS`, each in its module: the race (:mod:`.race`), the camera anywhere
(:mod:`.camera`), the sweeps of the cell count, repetition level, subpixel level and image size
and time to quality on the real data (:mod:`.sweeps`, with the *floor*: every face drawn opaque
by ``vtkPolyDataMapper``), host time per frame (:mod:`.host`), the paper's large case, MPI
ranks (:mod:`.parallel`) and the ParaView view (:mod:`.paraview_view`); then it fits the time
and memory models (:mod:`.models`) and finds the crossovers (:mod:`.crossovers`).

Sweep times are the median of several frames after one untimed warm-up frame, taken with the
pipeline finished (``WaitForCompletion``); the race keeps the best of two. The results go to
``bench.json``, PNG plots and two Markdown reports, ``bench.md`` with every table and
``results.md`` the summary for readers (:mod:`.results`, :mod:`.sections`). Nothing here
is part of ``make test``: these are measurements, not assertions.
"""

from ...progress import Progress
from .crossovers import crossovers, sampling_gains
from .methods import METHODS, face_polydata
from .models import fit, memory_models, time_models
from .runner import run
from .settings import SECTIONS, Settings

__all__ = ["METHODS", "SECTIONS", "Progress", "Settings", "crossovers", "face_polydata", "fit",
           "memory_models", "run", "sampling_gains", "time_models"]
