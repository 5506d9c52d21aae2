"""Shared fixtures: an off-screen render window per test module and access to the data sets."""

import os

import pytest


@pytest.fixture(scope="session")
def have_display() -> bool:
    """A window to render in: an X display (the tests run under xvfb-run), or else the EGL
    window (spt.render.new_render_window), which must then work: no skip."""
    return True


@pytest.fixture(scope="session")
def have_x_display() -> bool:
    """An X display, for what only renders through X: ParaView's own windows (pvpython,
    pvbatch, pvserver and the GUI are built for GLX only)."""
    if not os.environ.get("DISPLAY"):
        pytest.skip("needs an X display: ParaView's render windows are GLX only (run under "
                    "xvfb-run); SPT's own rendering without X is tested through EGL")
    return True


def load_or_skip(name: str):
    """A real data set, or a skip when SPT_DATA_DIR does not hold it."""
    from spt import data

    try:
        return data.load(name)
    except FileNotFoundError as error:
        pytest.skip(str(error))
