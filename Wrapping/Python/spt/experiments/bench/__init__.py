"""Benchmarks: the race to quality, and the time and GPU memory of SPT, HAVS-like, PBVR and
VTK's projected tetrahedra.

``build/bin/spt-python -m spt bench`` measures, on this machine and in one process:

- the race (:mod:`.race`): every method's error against the exact reference and its frame
  time on real and generated scenes, each stochastic method's time to reach VTK PT's error,
  HAVS-like k=6's and fixed errors as multiples of VTK PT's frame, and each method's host CPU
  time per frame; at each image size of ``--size`` (256 by default), each size in its own
  race, and the growth of each method's frame from the smallest size to the largest;
- the view people look at in ParaView (:mod:`.paraview_view`): pvpython with the plugin, a
  1280 x 800 view, the still and interactive renders of "Volume", "Volume (HAVS-like)" and
  "Volume (SPT)" at their defaults, each image against the exact image of the same camera;
- sweeps of the cell count (generated meshes, 10 thousand up), the repetition level, the
  subpixel level and the image size, for every method (:mod:`.sweeps`);
- the *floor*: all tetrahedron faces drawn opaque by ``vtkPolyDataMapper`` at the same image
  size, measured next to each point of the cell sweep;
- the fitted time and memory models (:mod:`.models`), with R^2 and residual plots;
- the crossovers (:mod:`.crossovers`): the repetition level above which PBVR needs more
  memory than SPT, and SPT against HAVS-like in time at equal error;
- time to quality at fixed repetition levels on SPX, Blunt Fin and Oxygen Post
  (:mod:`.quality`);
- where SPT's host (application thread) time goes per frame as the cell count grows, from
  ``perf`` samples (:mod:`.host`);
- the paper's large case, about 13 million tetrahedra at 1024 x 1024 with 144 repetitions,
  against the prediction of the fitted model.

Sweep times are the median of several frames after one untimed warm-up frame, taken with the
pipeline finished (``WaitForCompletion``); the race keeps the best of two. The results go to
``bench.json``, PNG plots and two Markdown reports, ``bench.md`` with every table and
``results.md`` the summary for readers (:mod:`.results`, :mod:`.sections`). Nothing here
is part of ``make test``: these are measurements, not assertions.
"""

from ...progress import Progress
from .crossovers import crossovers, floor_ratios, sampling_gains
from .methods import METHODS, Method, face_polydata, generated_mesh, generated_scene
from .models import Fit, fit, memory_models, time_models
from .runner import run
from .settings import SECTIONS, Settings
from .timing import Timing, time_method

__all__ = [
    "METHODS", "SECTIONS", "Fit", "Method", "Progress", "Settings", "Timing", "crossovers",
    "face_polydata", "fit", "floor_ratios", "generated_mesh", "generated_scene",
    "memory_models", "run", "sampling_gains", "time_method", "time_models"]
