"""ParaView users zoom into volumes: the plugin's representations fly the view's own camera
from outside the default mesh to deep inside it (fly_in.py under pvpython). At every step the
image has no holes: no pixel is empty where the exact image of the same camera (spt.raycast,
rays from the near plane) has an alpha above 0.05. SPT sets the alpha exactly (ExactCoverage),
and HAVS-like is deterministic, so an empty pixel there is a missing part of the volume, not
noise.
"""

import json

import numpy as np
import pytest

import paraview_support as pvs

#: Dolly factors from the framed view: outside, the near plane cutting the mesh, inside.
DOLLIES = (1.0, 4.0, 8.0, 12.0, 30.0)
REPRESENTATIONS = {"spt": "Volume (SPT)", "havs": "Volume (HAVS-like)"}
MAPPERS = {"spt": "vtkPSPTVolumeMapper", "havs": "vtkHAVSVolumeMapper"}


@pytest.fixture(scope="module")
def flights(have_x_display, tmp_path_factory):
    """Both representations fly in, one after the other, in one pvpython; each its own
    folder of steps."""
    directory = tmp_path_factory.mktemp("fly_in")
    mesh = pvs.write_mesh(directory / "mesh.vtk")
    pvs.run([pvs.executable("pvpython"), pvs.SCRIPTS / "fly_in.py", "--data", mesh,
             "--plugin", pvs.plugin_path(), "--output-dir", directory,
             "--representation", *REPRESENTATIONS.values(),
             "--dolly", *[str(d) for d in DOLLIES]])
    return {method: directory / str(index) for index, method in enumerate(REPRESENTATIONS)}


@pytest.mark.parametrize("method", REPRESENTATIONS)
def test_flying_into_the_volume_leaves_no_holes(flights, method):
    directory = flights[method]
    steps = json.loads((directory / "steps.json").read_text())
    assert [step["dolly"] for step in steps] == list(DOLLIES)
    assert {(step["representation"], step["mapper_class"]) for step in steps} == {
        (REPRESENTATIONS[method], MAPPERS[method])}
    # The camera went in: the near plane of the last steps lies inside the mesh's bounds.
    assert steps[-1]["clipping_range"][0] < steps[0]["clipping_range"][0]
    for step in steps:
        image = pvs.read_png(directory / f"{step['name']}.png")
        reference = np.load(directory / f"{step['name']}.npy")
        pvs.keep(directory / f"{step['name']}.png", f"fly_in_{method}_{step['name']}.png")
        assert image.shape == reference.shape
        assert reference[..., 3].max() > 0.2, f"{step['name']}: the reference is empty"
        holes = (reference[..., 3] > 0.05) & (image[..., 3] == 0.0)
        assert not holes.any(), f"{step['name']}: {int(holes.sum())} empty pixels"
        # The image is this volume, not merely some cover: its mean alpha is the reference's.
        assert abs(image[..., 3].mean() - reference[..., 3].mean()) < 0.02, step["name"]
