"""The views people look at: the race at each image size it was run at, how each method's frame
grows from the smallest size to the largest, the ``paraview`` section (still and interactive
renders in a ParaView view), and the camera anywhere (outside, cutting and inside the mesh).

A run's own ``bench.json`` holds these as ``race`` and ``race_sizes`` (the race at each size,
smallest first) and ``paraview``. Measurements made apart from the full run can be kept in
``large-views.json`` next to it, a ``bench.json`` of the ``race`` and ``paraview`` sections
only, and the ``paraview`` section measured again alone in ``paraview-views.json``;
:func:`attach` reads them, and the summary then reports those files' runs, each with its own
date and load.
"""

from __future__ import annotations

import json
import pathlib
from typing import List, Optional

from ...tables import markdown
from .race import at, find, race_table, reached, scenes
from .markdown import BENCH_COMMAND, SPT, Entry, Results, Section, short, short_table

#: The file of measurements made apart from the full run, next to ``bench.json``.
LARGE_VIEWS = "large-views.json"
#: The ParaView section measured alone, next to ``bench.json``; it takes the place of the one in
#: ``large-views.json``.
PARAVIEW_VIEWS = "paraview-views.json"
PARAVIEW_COMMAND = BENCH_COMMAND.format(sections="paraview")
SIZES_COMMAND = SPT + " bench --sections race,paraview --size 256,1024 --output out/bench"


def attach(results: Results, source: pathlib.Path) -> Results:
    """``results`` with the runs of ``large-views.json`` and ``paraview-views.json`` next
    to ``source`` as ``large_views`` and ``paraview_views``, where those files exist."""
    attached = dict(results)
    for key, name in (("large_views", LARGE_VIEWS), ("paraview_views", PARAVIEW_VIEWS)):
        path = source.parent / name
        if not path.exists() or key in results:
            continue
        try:
            attached[key] = json.loads(path.read_text(encoding="utf-8"))
        except (OSError, ValueError) as error:
            raise ValueError(f"cannot read {path}: {error}") from None
    return attached


def _measured_apart(run: Results, name: str, sections: str) -> str:
    load = run.get("load_average")
    return (f"Measured apart from the full run (`{name}`, a `bench.json` of the {sections} "
            f"only), on {run['date']} on {run['machine']}"
            + (f", shared with other jobs (load average {load[0]:.1f} on its "
               f"{run.get('cores', 2)} cores when the last section ended)" if load else "")
            + ".")


def races(results: Results) -> List[Results]:
    """The race at each size it was run at, smallest first."""
    chosen = [results.get("race")] + list(results.get("race_sizes") or [])
    return sorted((r for r in chosen if r), key=lambda r: r["size"])


def _growth(small: Optional[Entry], large: Optional[Entry]) -> str:
    if not small or not large:
        return "-"
    return (f"{short(small['seconds'])} s to {short(large['seconds'])} s "
            f"({short(large['seconds'] / small['seconds'])}x)")


def growth_table(small: Results, large: Results) -> str:
    """Per scene raced at both sizes: VTK PT's frame, SPT's frame at VTK PT's error (its
    error target), and SPT's time to VTK PT's error as a multiple of VTK PT's frame, at the
    smaller size and the larger."""
    rows = []
    for scene in scenes(small):
        if scene not in scenes(large):
            continue
        pt = [find(r["rows"], scene, "pt") for r in (small, large)]
        target = [find(r["rows"], scene, "spt-target") for r in (small, large)]
        rows.append([scene, f"{pt[1]['cells']:,}", _growth(*pt), _growth(*target),
                     "; ".join(at(reached(r, scene, "spt")) for r in (small, large))])
    return short_table(["scene", "tetrahedra", "VTK PT's frame",
                        "SPT at VTK PT's error (error target)",
                        f"SPT's time to VTK PT's error at {small['size']}; at {large['size']}"],
                       rows)


def sizes_part(results: Results) -> List[str]:
    """The race at each size and the growth from the smallest to the largest."""
    measured = races(results)
    if len(measured) < 2:
        return ["The race was run at one image size. Run it at several with "
                f"`{SIZES_COMMAND}`.", ""]
    lines = ["The race's camera and methods at each image size (`--size`), the sizes one "
             "after the other in one process per scene, the stochastic methods up to L = "
             f"{measured[0]['max_repetitions']}; the columns as in the race above.", ""]
    for race in measured:
        lines += [f"**{race['size']} x {race['size']}.**", "", race_table(race)]
    small, large = measured[0], measured[-1]
    return lines + [f"**From {small['size']} x {small['size']} to {large['size']} x "
                    f"{large['size']}** ({(large['size'] / small['size']) ** 2:g} times the "
                    "pixels): each method's frame at both sizes and its growth.", "",
                    growth_table(small, large)]


def _against(row: Optional[Entry], volume: Optional[Entry]) -> str:
    if not row or not volume:
        return "-"
    return f"{short(row['seconds'] / volume['seconds'])}, {short(row['rmse'])}"


def _spt_cell(row: Optional[Entry], volume: Optional[Entry]) -> str:
    if not row:
        return "-"
    still = row.get("still") or {}
    return _against(row, volume) + (f" (L={still['repetitions']})" if still else "")


def _interactive(row: Optional[Entry], volume: Optional[Entry] = None) -> str:
    if not row or not row.get("desired_update_rate"):
        return "-"
    requested = 1.0 / row["desired_update_rate"]
    # "Volume"'s own interactive render, where this run measured it as SPT's
    theirs = ("" if not volume or "interactive_all_seconds" not in volume
              or volume.get("used_lod") else
              f"; \"Volume\" {short(volume['interactive_seconds'])} s")
    # with ParaView's stand-in drawn, the mapper's own count is its last still render's
    state = {} if row.get("used_lod") else (row.get("interactive") or {})
    reps, distance = state.get("repetitions"), state.get("sample_distance")
    shape = (f"L={reps}" if reps else "") + (f", d={short(distance)}" if reps and distance else "")
    return (f"{short(row['interactive_seconds'])} s, "
            f"{short(row['interactive_seconds'] / requested)}"
            + (f" ({shape})" if shape else "") + (", LOD" if row.get("used_lod") else "")
            + theirs)


def paraview_table(measured: Results) -> str:
    rows = []
    for scene in sorted(measured["scenes"], key=lambda s: s["rows"][0]["cells"]):
        shown = {r["representation"]: r for r in scene["rows"]}
        volume, havs, spt = (shown.get(name) for name in (
            "Volume", "Volume (HAVS-like)", "Volume (SPT)"))
        rows.append([scene["scene"], f"{scene['rows'][0]['cells']:,}",
                     f"{short(volume['seconds'])} s, {short(volume['rmse'])}" if volume else "-",
                     _against(havs, volume), _spt_cell(spt, volume), _interactive(spt, volume),
                     f"{short(scene['reference_seconds'])} s" if scene.get("reference_seconds")
                     else "cached"])
    return short_table(["scene", "tetrahedra", "\"Volume\": still render, RMSE",
                        "\"Volume (HAVS-like)\": time / Volume's, RMSE",
                        "\"Volume (SPT)\": time / Volume's, RMSE",
                        "SPT interactive: time, / requested", "exact reference"], rows)


def paraview_part(results: Results) -> List[str]:
    measured = results.get("paraview")
    if not measured or not measured.get("scenes"):
        return ["This run did not measure the ParaView view. Measure it with "
                f"`{PARAVIEW_COMMAND}` (pvpython and the plugin: SPT_PARAVIEW_PLUGIN or "
                "PV_PLUGIN_PATH).", ""]
    width, height = measured["size"]
    return [f"**In ParaView.** pvpython with the plugin, a {width} x {height} render view, "
            "ParaView's default transfer functions for the scene's array, the camera turned "
            f"by azimuth {measured['azimuth']:g} and elevation {measured['elevation']:g} from "
            "ParaView's own and reset; each representation at its defaults, one after the "
            "other in one process. Time: the second still render (`StillRender`, finished); "
            "RMSE: the image that render left in the view (over black, the premultiplied "
            "color) against the exact reference of the same camera and size (spt.raycast on "
            "the tetrahedra ParaView hands the mappers). SPT interactive: the median of the "
            "last three of six `InteractiveRender`s, the camera turned by half a degree before "
            "each as a drag turns it, and its ratio to the time ParaView asks for (one over the "
            "render window's desired update rate), with the repetitions L and, where "
            "measured, the image's sample distance d and \"Volume\"'s interactive render "
            "measured alike; LOD where ParaView drew its stand-in. "
            "The exact reference's own time is given where this run rendered it.", "",
            paraview_table(measured)]


def views_summary(results: Results, folder: str) -> List[str]:
    """From ``large-views.json`` where :func:`attach` found it, else from the run itself."""
    source = results.get("large_views") or results
    lines = []
    if results.get("large_views"):
        lines += [_measured_apart(source, LARGE_VIEWS, "sections race and paraview"), ""]
    lines += sizes_part(source)
    paraview = results.get("paraview_views")
    if paraview and paraview.get("paraview"):
        lines += [_measured_apart(paraview, PARAVIEW_VIEWS, "section paraview") + " "
                  f"Measured again by `{PARAVIEW_COMMAND}`.", ""]
        return lines + paraview_part(paraview)
    return lines + paraview_part(source)


def views_full(results: Results) -> List[str]:
    """Every still and interactive render of the ``paraview`` section."""
    measured = results.get("paraview")
    if not measured or not measured.get("scenes"):
        return []
    rows = [[r["scene"], r["representation"], r["cells"], r["seconds"],
             ", ".join(f"{v:.3g}" for v in r["still_seconds"]), r["rmse"], r["rmse_rgba"],
             (r.get("still") or {}).get("repetitions", "-"), r["interactive_seconds"],
             1.0 / r["desired_update_rate"], (r.get("interactive") or {}).get("repetitions", "-"),
             r["used_lod"]]
            for scene in measured["scenes"] for r in scene["rows"]]
    width, height = measured["size"]
    return [f"## ParaView: a {width} x {height} view", "",
            "pvpython with the plugin, each representation at its defaults. Still renders: "
            "the first three, the second is the one timed; RMSE of the second's image in the "
            "view (RGB over black) and of a screenshot over a transparent background (RGBA), "
            "against the exact reference; the second interactive render against one over the "
            "desired update rate.", "",
            markdown(["scene", "representation", "tetrahedra", "still [s]", "still renders [s]",
                      "RMSE (view)", "RMSE (RGBA shot)", "L", "interactive [s]",
                      "requested [s]", "L interactive", "LOD"], rows),
            markdown(["scene", "exact reference [s]", "read-back floor", "unit distance"],
                     [[m["scene"], m["reference_seconds"], m["read_back_floor"],
                       m["unit_distance"]] for m in measured["scenes"]])]


VIEWS = Section("Larger views and ParaView", "race,paraview", views_summary, views_full)


def _camera_rows(results: Results, *columns: str) -> List[List[object]]:
    return [[r["scene"], r["label"], r["camera"]] + [r[c] for c in columns]
            for r in results["camera"]["rows"]]


def camera_summary(results: Results, folder: str) -> List[str]:
    return ["The camera dollies from the framed view into the mesh; ratio: the frame "
            "over the same method's from outside.", "",
            short_table(["scene", "method", "camera", "frame [s]", "ratio", "RMSE"],
                        _camera_rows(results, "seconds", "ratio_to_outside", "rmse"))]


def camera_full(results: Results) -> List[str]:
    camera = results["camera"]
    return ["## The camera anywhere", "",
            f"{camera['size']} x {camera['size']}, the stochastic methods at "
            f"{camera['repetitions']} repetitions; best of {camera['frames']} frames; the "
            "camera dollies from the framed view into the mesh. Ratio: the frame time over "
            "the same method's with the camera outside.", "",
            markdown(["scene", "method", "camera", "dolly", "frame [s]", "ratio", "RMSE"],
                     _camera_rows(results, "dolly", "seconds", "ratio_to_outside", "rmse")),
            ""]


CAMERA = Section("The camera anywhere", "camera", camera_summary, camera_full, key="camera")
