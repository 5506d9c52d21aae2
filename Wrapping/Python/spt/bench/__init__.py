"""Deprecated: moved to :mod:`spt.experiments.bench`; this alias goes in the next release."""

from ..experiments.bench import (  # noqa: F401
    METHODS, SECTIONS, Fit, Method, Progress, Settings, Timing, __all__, crossovers,
    face_polydata, fit, floor_ratios, generated_mesh, generated_scene, memory_models, run,
    sampling_gains, time_method, time_models)
