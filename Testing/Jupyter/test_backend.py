"""spt.pyvista.add_volume in a notebook: a warning naming the 'server' backend where PyVista's
backend would render in the browser (vtk.js, which has no SPT mapper), none where the image is
the kernel's (SPT's), and none outside a notebook."""

import warnings

import pytest
import pyvista as pv

import spt.pyvista
from spt import data


def _add(notebook, backend, mode="trame"):
    theme = pv.themes.Theme()
    theme.jupyter_backend = backend
    theme.trame.default_mode = mode
    plotter = pv.Plotter(notebook=notebook, off_screen=True, theme=theme, window_size=(32, 32))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        spt.pyvista.add_volume(plotter, pv.wrap(data.make_default_mesh()), render=False)
    plotter.close()
    return [w for w in caught if issubclass(w.category, spt.pyvista.ClientSideRenderingWarning)]


@pytest.mark.parametrize("backend", ["client", "html"])
def test_client_side_backends_warn_naming_the_server_backend(backend):
    caught = _add(True, backend)
    assert len(caught) == 1
    text = str(caught[0].message)
    assert f"'{backend}'" in text and "set_jupyter_backend('server')" in text


def test_trame_with_client_view_mode_warns():
    assert len(_add(True, "trame", mode="client")) == 1


@pytest.mark.parametrize("backend", ["trame", "server", "static"])
def test_server_side_backends_do_not_warn(backend):
    assert _add(True, backend) == []


def test_no_warning_outside_a_notebook():
    assert _add(False, "client") == []
