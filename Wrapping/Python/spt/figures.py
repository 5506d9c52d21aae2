"""Deprecated: moved to :mod:`spt.experiments.figures` (the demo to :mod:`spt.experiments.demo`);
this alias goes in the next release."""

from .experiments.demo import demo  # noqa: F401
from .experiments.figures import (  # noqa: F401
    PBVR_METHODS, PBVR_TABLE_HEADER, SORTING_HEADER, STEEP_SCENES, accuracy_figure, compare,
    convergence, pbvr_compare, pbvr_figure, sorting, sorting_scene)
