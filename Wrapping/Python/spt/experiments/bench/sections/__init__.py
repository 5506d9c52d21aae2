"""The benchmark's sections as its two documents report them: a section's summary for
``results.md`` and its full tables for ``bench.md`` side by side in a module of related
sections, :mod:`.markdown` what they share. ``SECTIONS`` is their order in both."""

from . import host, models, parallel, race, sweeps, views
from .markdown import Section

SECTIONS = (race.RACE, views.VIEWS, views.CAMERA, sweeps.CELLS, sweeps.LEVELS, models.MODELS,
            models.CROSSOVERS, sweeps.QUALITY, host.HOST, models.LARGE, parallel.PARALLEL)

__all__ = ["SECTIONS", "Section"]
