"""The race to quality: in ``results.md`` one row per scene and what the rows show; in
``bench.md`` each method's time to each target and every measurement, at each image size."""

from __future__ import annotations

import math
from typing import Callable, Dict, List, Optional, Sequence, Tuple

from ...tables import format_value, markdown
from .markdown import Entry, Results, Section, figure, short, short_table

Time = Optional[Dict[str, float]]

#: The time to an error of a method that the race did not run.
NOT_RACED = {"ratio": math.nan, "repetitions": 0}
FIGURES = {"race": ("race.png", "error against time in the race", "race")}


def find(rows: Sequence[Entry], scene: str, method: str) -> Optional[Entry]:
    """The row (or summary) of ``method`` on ``scene``, None where there is none."""
    return next((r for r in rows if r["scene"] == scene and r["method"] == method), None)


def reached(race: Results, scene: str, method: str, target: str = "VTK PT's error") -> Time:
    """The method's time to the target on the scene, None where it did not reach it, and
    NOT_RACED where it did not run."""
    entry = find(race["summary"], scene, method)
    return entry["reached"].get(target) if entry else NOT_RACED


def at(time: Time, number: Callable[[object], str] = short) -> str:
    """A time to an error: its multiple of VTK PT's frame and the L that reached it."""
    if time is None:
        return "not reached"
    if time is NOT_RACED:
        return "not raced"
    return f"{number(time['ratio'])} (L={time['repetitions']})"


def scenes(race: Results) -> List[str]:
    """The race's scenes in the order they were raced."""
    return list(dict.fromkeys(r["scene"] for r in race["rows"]))


def _against(row: Optional[Entry], pt: Entry) -> str:
    return f"{short(row['rmse'])}, {short(row['seconds'] / pt['seconds'])}" if row else "-"


def race_table(race: Results) -> str:
    """One row per scene: VTK PT, HAVS-like k=6 and SPT's time to VTK PT's error."""
    rows = []
    for scene in scenes(race):
        pt, havs, single = (find(race["rows"], scene, m) for m in ("pt", "havs6", "spt"))
        rows.append([scene, f"{pt['cells']:,}", f"{short(pt['rmse'])}, {short(pt['seconds'])} s",
                     _against(havs, pt)]
                    + [at(reached(race, scene, m)) for m in ("spt", "spt-target", "spt-slabs")]
                    + [_against(single, pt), at(reached(race, scene, "pbvr"))])
    return short_table(
        ["scene", "tetrahedra", "VTK PT: RMSE, frame", "HAVS-like k=6: RMSE, time",
         "SPT: time to VTK PT's error", "SPT, error target: time", "SPT, 8 depth slabs: time",
         "SPT at L=1: RMSE, time", "PBVR: time to VTK PT's error"], rows)


def _listing(items: Sequence[Tuple[str, Dict[str, float]]]) -> str:
    return ", ".join(f"{scene} ({short(r['ratio'])} at L={r['repetitions']})"
                     for scene, r in items) or "none"


def _havs_finding(race: Results) -> str:
    better, worse = [], []
    for scene in scenes(race):
        pt, havs = find(race["rows"], scene, "pt"), find(race["rows"], scene, "havs6")
        if pt and havs:
            (better if havs["rmse"] < pt["rmse"] else worse).append(scene)
    return ("- Sorted HAVS-like k=6 has a smaller error than VTK PT on "
            f"{', '.join(better) or 'no scene'} and a larger one on "
            f"{', '.join(worse) or 'no scene'}: its centroid sort and k-buffer recover the "
            "order along a ray only where the faces' order is nearly right.")


def findings(race: Results) -> List[str]:
    """What the race shows, read from its rows: where SPT wins, where it loses."""
    wins, losses, missed = [], [], []
    for scene in scenes(race):
        time = reached(race, scene, "spt")
        if time is None:
            missed.append(scene)
        elif time is not NOT_RACED:
            (wins if time["ratio"] <= 1.0 else losses).append((scene, time))
    paper = [s for s in scenes(race)
             if reached(race, s, "spt-paper-sampling") not in (None, NOT_RACED)]
    return [f"- SPT reaches VTK PT's error in at most one VTK PT frame on: {_listing(wins)}.",
            f"- **Where SPT loses:** it takes longer than VTK PT's frame on {_listing(losses)}"
            + (f", and does not reach VTK PT's error by L = {race['max_repetitions']} on "
               f"{', '.join(missed)}" if missed else "")
            + ". Where one repetition is enough, SPT's time is that of its two traversals of "
            "the mesh, each paid per primitive and per pixel; where the noise "
            "needs many repetitions, it is their traversal pair. SPT's frame grows more "
            "slowly with the cells than VTK PT's, whose sort and projection run on the host, "
            "so the ratio falls as the mesh grows (compare the drills).",
            f"- The paper's sampling (the survivor estimator, one traversal per repetition, "
            f"independent thresholds) reaches VTK PT's error by L = "
            f"{race['max_repetitions']} on {len(paper)} of {len(scenes(race))} scenes"
            + (f" ({', '.join(paper)})" if paper else "") + ".",
            _havs_finding(race), ""]


def runs(race: Results, note: str = ": each scene's methods in one process, so compare "
                                    "ratios within a scene.") -> str:
    """Which scenes were raced together, where a race was run scene by scene, and ``note``."""
    measured = race.get("runs") or []
    if len(measured) < 2:
        return ""
    groups = "; ".join(", ".join(run["scenes"]) for run in measured)
    return f" The scenes were raced in {len(measured)} runs ({groups}){note}"


def summary(results: Results, folder: str) -> List[str]:
    race = results["race"]
    floors = [r["read_back_floor"] for r in race["rows"] if r.get("read_back_floor")]
    return [
        f"Each scene in one process at {race['size']} x {race['size']} (azimuth "
        f"{race['azimuth']:g}, elevation {race['elevation']:g}): every method's error "
        "against the exact reference (RMSE of premultiplied RGBA over the footprint) and its "
        f"frame, the best of {race['frames']}. The stochastic methods draw L = 1, 2, 4, ... "
        f"up to {race['max_repetitions']}; a method's time to an error is the frame of the "
        "smallest L at or below it, as a multiple of VTK PT's frame in the same process "
        "(below 1: faster than VTK PT). \"Error target\": SPT with `TargetError` set to VTK "
        "PT's error, from a new mapper. Images are read back in 8 bits per channel, which "
        f"alone leaves an error of about {short(min(floors)) if floors else '0.0011'}."
        + runs(race, ", with the methods that each run had: compare within a scene."), "",
        race_table(race)] + findings(race) + figure(FIGURES["race"], folder)


def _objects(objects: Dict[str, float]) -> str:
    """Shared objects and their milliseconds per frame, as in ``libvtkCommonCore 12``."""
    return "; ".join(f"{name.split('.so')[0].split('-pv')[0]} {1000.0 * t:.3g}"
                     for name, t in objects.items()) or "-"


def _times_table(race: Results) -> str:
    """Each method's time to each target as a multiple of VTK PT's frame."""
    times = race["summary"]
    if not times:
        return ""
    targets = list(times[0]["reached"])
    return markdown(["scene", "method"] + [f"to {t}" for t in targets]
                    + ["host CPU [ms/frame]", "at L"],
                    [[s["scene"], s["label"]]
                     + [at(s["reached"].get(t), format_value) for t in targets]
                     + [1000.0 * s["host_seconds"], s["host_repetitions"]] for s in times])


def _rows_table(race: Results) -> str:
    """Every measurement of the race."""
    pt = {r["scene"]: r["seconds"] for r in race["rows"] if r["method"] == "pt"}
    # the objects are recorded where perf measured the host time
    objects = any(r.get("host_objects") for r in race["rows"])
    return markdown(["scene", "method", "L", "RMSE", "frame [s]", "frame / VTK PT",
                     "host CPU [ms]"] + (["host CPU's largest objects [ms]"] if objects else [])
                    + ["CPU, all threads [s]"],
                    [[r["scene"], r["label"], r["repetitions"], r["rmse"], r["seconds"],
                      r["seconds"] / pt[r["scene"]] if r["scene"] in pt else "-",
                      1000.0 * r["host_seconds"]]
                     + ([_objects(r.get("host_objects", {}))] if objects else [])
                     + [r["cpu_seconds"]] for r in race["rows"]])


def _read_back_floors(race: Results) -> str:
    """Each scene's least error of an 8-bit image, where the race recorded it."""
    floors: Dict[str, float] = {}
    for row in race["rows"]:
        if row.get("read_back_floor") is not None:
            floors.setdefault(row["scene"], row["read_back_floor"])
    if not floors:
        return ""
    listed = ", ".join(f"{scene} {format_value(value)}" for scene, value in floors.items())
    return (" Every image is read back through 8 bits per channel, so no error can be below "
            f"that of the exact image rounded to 8 bits: {listed}.")


def race_full(race: Results, heading: str = "The race: time to quality") -> List[str]:
    """The race at one size, under ``heading``."""
    source = ("`perf` samples of the application thread outside the OpenGL driver"
              if race["host_source"] == "perf" else
              "CPU time of the application thread during the frame (`perf` was not "
              "available; this includes the driver's work on that thread)")
    return [f"## {heading}", "",
            f"{race['size']} x {race['size']}, azimuth {race['azimuth']:g}, elevation "
            f"{race['elevation']:g}, every error against the exact reference (RMSE of "
            f"premultiplied RGBA), every time the best of {race['frames']} frames in one "
            f"process. Stochastic methods at L = 1, 2, 4, ... up to "
            f"{race['max_repetitions']}, until every target is reached. Time to an error: "
            "the frame of the smallest L at or below it, as a multiple of VTK PT's frame. "
            f"Host CPU time: {source}.{runs(race)}{_read_back_floors(race)}", "",
            "![race](race.png)", "", _times_table(race), _rows_table(race)]


def full(results: Results) -> List[str]:
    """The race, then the race at each other size it was run at."""
    lines = race_full(results["race"])
    for other in results.get("race_sizes") or []:
        lines += race_full(other, f"The race at {other['size']} x {other['size']}")
    return lines


RACE = Section("The race: time to quality", "race", summary, full, FIGURES, "race")
