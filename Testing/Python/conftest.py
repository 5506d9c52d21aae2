"""Shared fixtures: an off-screen render window per test module and access to the data sets."""

import os

import pytest


@pytest.fixture(scope="session")
def have_display() -> bool:
    """Rendering needs an X display (the tests run under xvfb-run)."""
    if not os.environ.get("DISPLAY"):
        pytest.skip("no X display: run the rendering tests under xvfb-run")
    return True


def load_or_skip(name: str):
    """A real data set, or a skip when SPT_DATA_DIR does not hold it."""
    from spt import data

    try:
        return data.load(name)
    except FileNotFoundError as error:
        pytest.skip(str(error))
