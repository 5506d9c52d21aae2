"""The ``paraview`` section: the view people look at, in ParaView.

Each scene in its own pvpython with the SPT plugin (from SPT_PARAVIEW_PLUGIN, the SPT.so to
load, or PV_PLUGIN_PATH), in a render view of ``Settings.paraview_size`` (1280 x 800 by
default), as "Volume", "Volume (HAVS-like)" and "Volume (SPT)" at their defaults: what is
measured is :mod:`.pvpython_stills`'s. The scenes: ``disk`` (ParaView's disk_out_ref.ex2
colored by Temp, read by ParaView's Exodus reader, from SPT_DATA_DIR), the race's generated
drills, and ``default`` (the embedded mesh, for a quick run).
"""

from __future__ import annotations

import json
import os
import pathlib
import shutil
import subprocess
from typing import Dict, List, Optional, Tuple

from ... import data, meshes
from ...progress import Progress
from . import race
from .race import AZIMUTH, ELEVATION
from .settings import Settings

Row = Dict[str, object]
TIMEOUT = 7200  # seconds per scene: the reference of a large view is slow
SCRIPT = pathlib.Path(__file__).with_name("pvpython_stills.py")
#: Scenes read from SPT_DATA_DIR by ParaView's own reader: the file and the array.
DATA_FILES = {"disk": ("disk_out_ref.ex2", "Temp")}


def pvpython() -> str:
    """The pvpython to run, or a RuntimeError saying what is missing."""
    path = shutil.which("pvpython")
    if not path:
        raise RuntimeError("the paraview section needs ParaView's pvpython on PATH")
    return path


def plugin_arguments() -> List[str]:
    """``--plugin SPT.so`` from SPT_PARAVIEW_PLUGIN, nothing if PV_PLUGIN_PATH loads it, or
    a RuntimeError."""
    plugin = os.environ.get("SPT_PARAVIEW_PLUGIN")
    if plugin:
        if not pathlib.Path(plugin).is_file():
            raise RuntimeError(f"SPT_PARAVIEW_PLUGIN={plugin} is not a file")
        return ["--plugin", plugin]
    if os.environ.get("PV_PLUGIN_PATH"):
        return []
    raise RuntimeError("the paraview section needs the SPT plugin: set SPT_PARAVIEW_PLUGIN to "
                       "its SPT.so, or PV_PLUGIN_PATH to its folder")


def scene_names() -> List[str]:
    """The scenes the section can show: the data files ParaView reads, and the race's."""
    return list(DATA_FILES) + [name for name in race.scene_names() if name not in DATA_FILES]


def scene_file(scene: str, directory: pathlib.Path) -> Tuple[pathlib.Path, str]:
    """The file pvpython reads for ``scene`` and the point array to color by: a data set of
    SPT_DATA_DIR, or the race's scene written as a legacy .vtk file."""
    if scene in DATA_FILES:
        name, array = DATA_FILES[scene]
        path = data.data_dir() / name
        if not path.is_file():
            raise FileNotFoundError(f"{path} is missing: the paraview section reads {name} "
                                    f"from SPT_DATA_DIR")
        return path, array
    grid = race.race_scene(scene).grid
    scalars = grid.GetPointData().GetScalars()
    if scalars is None or not scalars.GetName():
        raise ValueError(f"the scene {scene} has no named point scalars to color by")
    path = directory / f"{scene}.vtk"
    if not path.exists():
        directory.mkdir(parents=True, exist_ok=True)
        meshes.write_legacy(grid, path)
    return path, scalars.GetName()


def run_scene(scene: str, settings: Settings, output: pathlib.Path) -> Row:
    """pvpython on one scene: its report (rows per representation, the reference's time)."""
    path, array = scene_file(scene, output / "data")
    folder = output / scene
    command = [pvpython(), str(SCRIPT), "--data", str(path), "--array", array,
               "--scene", scene, "--output", str(folder),
               "--references", str(output / "references"),
               "--size", ",".join(str(v) for v in settings.paraview_size),
               "--azimuth", str(AZIMUTH), "--elevation", str(ELEVATION)]
    command += plugin_arguments()
    for representation in settings.paraview_representations:
        command += ["--representation", representation]
    environment = dict(os.environ)
    package = str(pathlib.Path(__file__).resolve().parents[3])
    environment["PYTHONPATH"] = os.pathsep.join(
        [package] + [p for p in environment.get("PYTHONPATH", "").split(os.pathsep) if p])
    result = subprocess.run(command, capture_output=True, text=True, timeout=TIMEOUT,
                            env=environment, check=False)
    if result.returncode != 0:
        raise RuntimeError(f"{' '.join(command)} failed ({result.returncode}):\n"
                           f"{result.stdout[-2000:]}\n{result.stderr[-4000:]}")
    return json.loads((folder / "report.json").read_text())


def steps(settings: Settings) -> int:
    return len(settings.paraview_scenes)


def paraview(settings: Settings, progress: Progress, output: pathlib.Path,
             previous: Optional[Dict[str, object]] = None) -> Dict[str, object]:
    """Every scene of ``settings.paraview_scenes`` in its own pvpython, with the scenes of
    ``previous`` (an earlier run of this section at the same size) that this one did not
    run."""
    output.mkdir(parents=True, exist_ok=True)
    size = list(settings.paraview_size)
    scenes: List[Row] = []
    for scene in settings.paraview_scenes:
        report = run_scene(scene, settings, output)
        scenes.append(report)
        times = ", ".join(f"{r['representation']} {r['seconds']:.2f} s" for r in report["rows"])
        progress.step(f"paraview {scene}: {times}")
    if previous and previous.get("size") == size:
        measured = {s["scene"] for s in scenes}
        scenes += [s for s in previous.get("scenes", []) if s["scene"] not in measured]
    order = {name: index for index, name in enumerate(settings.paraview_scenes)}
    scenes.sort(key=lambda s: order.get(s["scene"], len(order)))
    return {"size": size, "azimuth": AZIMUTH, "elevation": ELEVATION,
            "representations": list(settings.paraview_representations), "scenes": scenes}
