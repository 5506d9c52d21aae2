"""Shared fixtures and helpers: an X display for ParaView's windows, access to the data sets,
and Python in a child process."""

import os
import pathlib
import subprocess
import sys

import pytest


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


def run_python(code: str, *arguments: str, without_display: bool = False,
               **variables: str) -> subprocess.CompletedProcess:
    """Python ``code`` run with ``arguments`` in a child process, with the package under test
    first on its path and the environment's ``variables`` set; without DISPLAY if
    ``without_display``. A crash or a failed check there fails the test, not pytest."""
    import spt

    env = dict(os.environ, **variables)
    if without_display:
        env.pop("DISPLAY", None)
    package_parent = str(pathlib.Path(spt.__file__).resolve().parent.parent)
    env["PYTHONPATH"] = os.pathsep.join([package_parent, env.get("PYTHONPATH", "")])
    return subprocess.run([sys.executable, "-c", code, *arguments], capture_output=True,
                          text=True, env=env, check=False, timeout=600)
