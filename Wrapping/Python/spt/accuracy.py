"""Deprecated: moved to :mod:`spt.experiments.accuracy`; this alias goes in the next release."""

from .experiments.accuracy import (  # noqa: F401
    DEFAULT_LEVELS, check_unbiased, exact_brightness, fit_slope, main, plot, random_rays, run,
    stochastic_brightness)

if __name__ == "__main__":
    raise SystemExit(main())
