"""ParaView users zoom into volumes: the plugin's representations fly the view's own camera
from outside the default mesh to deep inside it (render_volume.py --fly-in under pvpython). At
every step the image has no holes: no pixel is empty where the exact image of the same camera
(spt.raycast, rays from the near plane) has an alpha above 0.05. SPT sets the alpha exactly
(ExactCoverage), and HAVS-like is deterministic, so an empty pixel there is a missing part of
the volume, not noise.
"""

import numpy as np
import pytest

import paraview_support as pvs

#: Dolly factors from the framed view: outside, the near plane cutting the mesh, inside.
DOLLIES = (1.0, 4.0, 8.0, 12.0, 30.0)
REPRESENTATIONS = {"spt": pvs.SPT, "havs": pvs.HAVS}


@pytest.fixture(scope="module")
def flights(have_x_display, tmp_path_factory):
    """Both representations fly in, one after the other, in one pvpython (with no error
    target, so that the repetitions are the ones asked for): each its output."""
    directory = tmp_path_factory.mktemp("fly_in")
    mesh = pvs.write_mesh(directory / "mesh.vtk")
    outputs = {method: directory / f"{method}.png" for method in REPRESENTATIONS}
    pvs.run(pvs.render_command(*[
        pvs.scene(mesh, output, "--plugin", pvs.plugin_path(), "--representation",
                  REPRESENTATIONS[method], "--size", 96, "--repetitions", 16, "--seed", 1,
                  "--target-error", 0, "--fly-in", *DOLLIES)
        for method, output in outputs.items()]))
    return outputs


@pytest.mark.parametrize("method", REPRESENTATIONS)
def test_flying_into_the_volume_leaves_no_holes(flights, method):
    report = pvs.read_report(flights[method])
    steps = report["fly_in"]
    assert [step["dolly"] for step in steps] == list(DOLLIES)
    assert report["representation"] == REPRESENTATIONS[method]
    assert report["mapper_class"] == pvs.MAPPERS[REPRESENTATIONS[method]]
    # The camera went in: the near plane of the last steps lies inside the mesh's bounds.
    assert steps[-1]["clipping_range"][0] < steps[0]["clipping_range"][0]
    for step in steps:
        name = f"dolly{step['dolly']:g}"
        path = flights[method].with_suffix(f".{name}.png")
        image = pvs.read_png(path)
        reference = np.load(path.with_suffix(".npy"))
        pvs.keep(path, f"fly_in_{method}_{name}.png")
        assert image.shape == reference.shape
        assert reference[..., 3].max() > 0.2, f"{name}: the reference is empty"
        holes = (reference[..., 3] > 0.05) & (image[..., 3] == 0.0)
        assert not holes.any(), f"{name}: {int(holes.sum())} empty pixels"
        # The image is this volume, not merely some cover: its mean alpha is the reference's.
        assert abs(image[..., 3].mean() - reference[..., 3].mean()) < 0.02, name
