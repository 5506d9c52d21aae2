"""The camera anywhere: each method's frame time and error with the camera outside the mesh,
with the near plane cutting it, and inside it, side by side in one process.

The camera starts from the scene's framing (azimuth 35, elevation 25) and dollies towards the
focal point; the clipping range is reset around the data, as VTK and ParaView do. Each frame
time is the best of two frames after a warm-up; the error is against the exact reference of
the same camera (spt.raycast, rays from the near plane).
"""

from __future__ import annotations

from typing import Dict, List

import numpy as np

from ... import metrics, raycast, render, scenes
from ...progress import Progress
from .methods import METHODS, Method, havs_method, timed_frames
from .settings import Settings

Entry = Dict[str, object]

#: Dolly factors from the framed view.
CAMERAS = {"outside": 1.0, "near plane cutting": 8.0, "inside": 12.0, "deep inside": 30.0}
AZIMUTH, ELEVATION = 35.0, 25.0
FRAMES = 2
#: The methods compared; the stochastic ones at the section's repetitions.
COMPARED = (METHODS["pt"], havs_method(6), METHODS["spt-visibility"], METHODS["pbvr"])


def _frames(s: scenes.Scene, method: Method, dolly: float, size: int, repetitions: int):
    """The best frame time, the last image and the camera."""
    window, renderer = render.make_window(size, size)
    mapper = method.make(repetitions, 1)
    render.add_volume(renderer, s.grid, s.property, mapper)
    view = render.View(AZIMUTH, ELEVATION, s.view.zoom)
    render.place_camera(renderer, s.grid.GetBounds(), view)
    renderer.GetActiveCamera().Dolly(dolly)
    renderer.ResetCameraClippingRange(s.grid.GetBounds())
    render.warm_up(window, mapper)
    best = min(timed_frames(window, FRAMES).seconds)
    image = render.read_rgba(window)
    camera = renderer.GetActiveCamera()
    copied = type(camera)()
    copied.DeepCopy(camera)
    renderer.RemoveAllViewProps()
    window.Finalize()
    return best, image, copied


def camera_rows(name: str, settings: Settings, progress: Progress) -> List[Entry]:
    """Every compared method at every camera of one scene."""
    s = scenes.scene(name)
    rows: List[Entry] = []
    references = {}
    for method in COMPARED:
        for camera, dolly in CAMERAS.items():
            seconds, image, placed = _frames(s, method, dolly, settings.camera_size,
                                             settings.camera_repetitions)
            if camera not in references:
                references[camera] = raycast.render(s.grid, s.property, placed,
                                                    (settings.camera_size,) * 2)
            rows.append({"scene": name, "method": method.name, "label": method.label,
                         "camera": camera, "dolly": dolly, "seconds": seconds,
                         "rmse": metrics.rmse(image, references[camera]),
                         "repetitions": settings.camera_repetitions if method.stochastic
                         else 1})
            progress.step(f"{name} {method.name} {camera}: {seconds:.3f} s, "
                          f"RMSE {rows[-1]['rmse']:.4f}")
    outside = {row["method"]: row["seconds"] for row in rows if row["camera"] == "outside"}
    for row in rows:
        row["ratio_to_outside"] = row["seconds"] / outside[row["method"]]
    return rows


def steps(settings: Settings) -> int:
    return len(settings.camera_scenes) * len(COMPARED) * len(CAMERAS)


def camera_section(settings: Settings, progress: Progress) -> Dict[str, object]:
    rows: List[Entry] = []
    for name in settings.camera_scenes:
        rows += camera_rows(name, settings, progress)
    return {"size": settings.camera_size, "repetitions": settings.camera_repetitions,
            "frames": FRAMES, "rows": rows,
            "worst_ratio": {m.name: float(np.max([r["ratio_to_outside"] for r in rows
                                                  if r["method"] == m.name]))
                            for m in COMPARED}}
