"""The ParaView plugin in pvpython: LoadPlugin, the representation type "Volume (SPT)" with its
documented settings, a volume image, `import spt` inside ParaView's Python, the same through a
pvserver over loopback, and (after `make install`) the installed plugin found by PV_PLUGIN_PATH.
"""

import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

import paraview_support as pvs

SETTINGS = ("RepetitionLevel", "SubpixelLevel", "Seed", "PreIntegrationScalarResolution",
            "PreIntegrationThicknessResolution", "RepetitionsPerPass", "StratifiedSampling",
            "ProgressiveRefinement")
REPETITIONS = 8
SEED = 3


@pytest.fixture(scope="module")
def mesh(tmp_path_factory):
    return pvs.write_mesh(tmp_path_factory.mktemp("data") / "mesh.vtk")


def render_command(mesh, output, *extra):
    return [pvs.executable("pvpython"), pvs.SCRIPTS / "render_volume.py",
            "--data", mesh, "--output", output, "--report", output.with_suffix(""),
            "--repetitions", REPETITIONS, "--seed", SEED, *extra]


def read_report(output):
    return json.loads(output.with_suffix(".rank0.json").read_text())


def check_volume_image(image):
    """A volume, not an empty view: part of the view is covered, with varied colors."""
    covered = pvs.footprint(image)
    assert 0.05 < covered.mean() < 0.8, f"{covered.mean():.3f} of the view is covered"
    colors = image[covered][:, :3]
    assert colors.mean() > 0.1
    assert colors.std(axis=0).max() > 0.05, "a flat color, not a volume"


@pytest.fixture(scope="module")
def builtin(have_display, mesh, tmp_path_factory):
    """pvpython on its own: LoadPlugin, show the mesh as "Volume (SPT)", screenshot."""
    output = tmp_path_factory.mktemp("builtin") / "spt.png"
    pvs.run(render_command(mesh, output, "--plugin", pvs.plugin_path()))
    pvs.keep(output, "pvpython_spt.png")
    return output


def test_representation_type_is_listed(builtin):
    report = read_report(builtin)
    assert report["representation"] == "Volume (SPT)"
    assert {"Volume", "Volume (SPT)", "Surface"} <= set(report["representation_types"])


def test_settings_reach_the_mapper_on_the_server(builtin):
    report = read_report(builtin)
    expected = {"RepetitionLevel": REPETITIONS, "SubpixelLevel": 1, "Seed": SEED,
                "PreIntegrationScalarResolution": 128, "PreIntegrationThicknessResolution": 64,
                "RepetitionsPerPass": 16, "StratifiedSampling": 1, "ProgressiveRefinement": 0}
    assert report["settings"] == expected
    assert report["mapper_class"] == "vtkSPTVolumeMapper" and report["mapper_is_spt"]
    assert report["mapper_settings"] == expected
    assert report["tetrahedra"] == report["cells"] == 48000


def test_settings_are_documented_and_grouped(builtin):
    """The XML documentation is what the Properties panel shows as tooltips."""
    report = read_report(builtin)
    for name in SETTINGS:
        text = report["documentation"][name]
        assert len(text) > 60 and "default" in text.lower(), (name, text)
    assert report["property_groups"]["SPT Volume Rendering"] == list(SETTINGS)


def test_spt_imports_inside_pvpython_from_this_build(builtin):
    """`import spt` works in ParaView's Python, wraps the plugin's mapper, and both come from
    the build tree under test, one copy of the library."""
    report = read_report(builtin)
    build = pathlib.Path(pvs.plugin_path()).parents[4]
    assert pathlib.Path(report["spt_file"]).resolve().is_relative_to(build.resolve())
    libraries = [pathlib.Path(p) for p in report["spt_libraries"]]
    rendering = [p for p in libraries if p.name.startswith("libSPTRendering")]
    assert len(rendering) == 1 and rendering[0].is_relative_to(build), libraries


def test_image_is_a_volume(builtin):
    check_volume_image(pvs.read_png(builtin))


def test_pvserver_with_a_pvpython_client_over_loopback(builtin, mesh, tmp_path):
    """The client loads the plugin on itself and on the server (what Tools > Manage Plugins
    does), renders remotely, and gets the same image as pvpython on its own."""
    port = pvs.free_port()
    server = subprocess.Popen(
        [pvs.executable("pvserver"), f"--server-port={port}"], env=pvs.environment(),
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        pvs.wait_for(server, "Accepting connection", 120)
        output = tmp_path / "client.png"
        pvs.run(render_command(mesh, output, "--plugin", pvs.plugin_path(),
                               "--connect", f"localhost:{port}"))
        # pvserver ends by itself when its client disconnects.
        assert server.wait(timeout=120) == 0
    finally:
        if server.poll() is None:
            server.kill()
            server.wait()
    pvs.keep(output, "pvserver_client_spt.png")
    report = read_report(output)
    assert report["representation"] == "Volume (SPT)"
    assert report["settings"]["RepetitionLevel"] == REPETITIONS
    remote, local = pvs.read_png(output), pvs.read_png(builtin)
    check_volume_image(remote)
    # The same seed, data and camera: the same image, up to the rounding of its delivery.
    assert np.abs(remote - local).max() <= 2.0 / 255.0


def test_installed_plugin_is_found_by_pv_plugin_path(have_display, mesh, tmp_path):
    """After `make install`: PV_PLUGIN_PATH=PREFIX/lib/paraview-5.11/plugins loads the
    installed plugin at start-up, with the installed libraries (checked when the Makefile ran
    the install: SPT_TEST_INSTALLED=1)."""
    if os.environ.get("SPT_TEST_INSTALLED") != "1":
        pytest.skip("set SPT_TEST_INSTALLED=1 after installing to check the installed plugin")
    prefix = pathlib.Path(os.environ["SPT_INSTALL_PREFIX"])
    plugins = prefix / os.environ["SPT_PARAVIEW_PLUGIN_SUBDIR"]
    python = prefix / os.environ["SPT_PYTHON_SITE_DIR"]
    assert (plugins / "SPT" / "SPT.so").is_file()
    output = tmp_path / "installed.png"
    pvs.run(render_command(mesh, output),
            env=pvs.environment(PV_PLUGIN_PATH=str(plugins), PYTHONPATH=str(python)))
    report = read_report(output)
    assert report["representation"] == "Volume (SPT)" and report["tetrahedra"] == 48000
    assert all(pathlib.Path(p).is_relative_to(prefix) for p in report["spt_libraries"]), \
        report["spt_libraries"]
    check_volume_image(pvs.read_png(output))
