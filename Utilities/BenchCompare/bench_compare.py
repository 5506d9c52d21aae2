"""Compare the race of the current tree (the head) with that of a base commit, side by side on
this machine: ``make bench-compare BASE=<git ref> SCENES=<race scenes>``.

Both are built alike, each in a build folder of its own under OUTPUT (the base from its own
source tree, ``git archive`` of BASE). Then the race (``python3 -m spt bench --sections race``)
runs RUNS times for each, alternately (head, base, head, base, ...), each run in a process of
its own whose PYTHONPATH and LD_LIBRARY_PATH name only its own build tree (which holds the
package and its libraries as an install would); each run records the package and the
libraries its process loaded, and the comparison stops if any lies outside that tree. Each
side runs its own benchmark code, so the scenes (and options) asked for must exist in both. The
runs' figures, the medians and the head's ratio over the base's (comparison.py) go to
OUTPUT/compare.json, and the table is printed.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import os
import pathlib
import shutil
import subprocess
import sys
import time
from typing import Dict, List, Optional, Sequence

import comparison

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parents[1]
#: The build of both sides: what the race needs (no tests, no ParaView plugin).
BUILD_OPTIONS = ("-DCMAKE_BUILD_TYPE=Release", "-DBUILD_SHARED_LIBS=ON", "-DBUILD_TESTING=OFF",
                 "-DSPT_BUILD_PARAVIEW_PLUGIN=OFF", "-DCMAKE_INSTALL_LIBDIR=lib")


@dataclasses.dataclass
class Side:
    """One of the two builds compared: its sources and its build folder."""

    name: str
    source: pathlib.Path
    folder: pathlib.Path

    @property
    def build(self) -> pathlib.Path:
        return self.folder / "build"


def git(*arguments: str) -> str:
    """The output of a git command in the project's tree."""
    return subprocess.run(["git", "-C", str(ROOT), *arguments], check=True, text=True,
                          stdout=subprocess.PIPE).stdout.strip()


def commit_of(reference: str) -> str:
    """The commit that ``reference`` names, or a ValueError saying that it names none."""
    try:
        return git("rev-parse", "--verify", "--quiet", f"{reference}^{{commit}}")
    except subprocess.CalledProcessError:
        raise ValueError(f"BASE={reference} names no commit of this repository") from None


def checkout(commit: str, folder: pathlib.Path) -> pathlib.Path:
    """The sources of ``commit`` in ``folder/src`` (git archive), extracted again only when
    the commit changed, and then built from scratch; returns that folder."""
    source, stamp = folder / "src", folder / "src.commit"
    if source.is_dir() and stamp.exists() and stamp.read_text().strip() == commit:
        return source
    # The archive's files carry their commit's time, which can be older than the objects built
    # from another commit: a build kept from there would link those stale objects.
    for stale in (source, folder / "build"):
        shutil.rmtree(stale, ignore_errors=True)
    source.mkdir(parents=True)
    archive = subprocess.Popen(["git", "-C", str(ROOT), "archive", "--format=tar", commit],
                               stdout=subprocess.PIPE)
    subprocess.run(["tar", "-x", "-C", str(source)], stdin=archive.stdout, check=True)
    if archive.wait() != 0:
        raise RuntimeError(f"git archive {commit} failed")
    stamp.write_text(commit + "\n")
    return source


def logged(command: Sequence[str], log: pathlib.Path, **options) -> None:
    """Run ``command`` with its output in ``log``; a RuntimeError naming the log if it fails."""
    with open(log, "w", encoding="utf-8") as output:
        done = subprocess.run(list(command), stdout=output, stderr=subprocess.STDOUT, **options)
    if done.returncode != 0:
        tail = log.read_text(encoding="utf-8", errors="replace").splitlines()[-15:]
        raise RuntimeError(f"{' '.join(command[:3])} ... failed (see {log}):\n"
                           + "\n".join(tail))


def build(side: Side, vtk_dir: str, python: str, jobs: int) -> None:
    """Configure and build (niced) one side in its own build folder."""
    side.folder.mkdir(parents=True, exist_ok=True)
    launcher = (["-DCMAKE_CXX_COMPILER_LAUNCHER=ccache", "-DCMAKE_C_COMPILER_LAUNCHER=ccache"]
                if shutil.which("ccache") else [])
    environment = dict(os.environ)
    environment.setdefault("CCACHE_BASEDIR", str(ROOT))
    print(f"bench-compare: building the {side.name} ({side.source}) in {side.build}",
          flush=True)
    logged(["cmake", "-S", str(side.source), "-B", str(side.build), "-G", "Ninja",
            f"-DVTK_DIR={vtk_dir}", f"-DPython3_EXECUTABLE={python}",
            *BUILD_OPTIONS, *launcher],
           side.folder / "configure.log", env=environment)
    logged(["nice", "-n", "5", "cmake", "--build", str(side.build), "-j", str(jobs)],
           side.folder / "build.log", env=environment)


def site_folder(side: Side) -> pathlib.Path:
    """Where the side's build tree holds the package spt (SPT_PYTHON_SITE_DIR of its build)."""
    for line in (side.build / "CMakeCache.txt").read_text(encoding="utf-8").splitlines():
        if line.startswith("SPT_PYTHON_SITE_DIR:"):
            folder = side.build / line.split("=", 1)[1]
            if (folder / "spt" / "__init__.py").exists():
                return folder
    raise RuntimeError(f"no package spt built in {side.build}")


def run_environment(side: Side) -> Dict[str, str]:
    """This process's environment with the paths of ``side`` only, and its own mesh cache."""
    environment = {key: value for key, value in os.environ.items()
                   if key not in ("PYTHONPATH", "LD_LIBRARY_PATH", "PYTHONHOME")}
    environment.update(PYTHONPATH=str(site_folder(side)),
                       LD_LIBRARY_PATH=str(side.build / "lib"),
                       SPT_CACHE_DIR=str(side.folder / "meshes"), PYTHONDONTWRITEBYTECODE="1")
    return environment


def foreign(loaded: Dict[str, object], tree: pathlib.Path) -> List[str]:
    """The package folder and libraries of a run's record that are not in ``tree``."""
    root = str(tree.resolve()) + os.sep
    paths = [str(loaded["package"])] + [str(path) for path in loaded["libraries"]]
    return [path for path in paths if not path.startswith(root)]


def schedule(runs: int) -> List[tuple]:
    """The order of the runs: (side, index) for head 1, base 1, head 2, base 2, ..."""
    return [(side, index) for index in range(1, runs + 1) for side in ("head", "base")]


def race_run(side: Side, index: int, arguments: argparse.Namespace, python: str
             ) -> comparison.Record:
    """One race of one side in a process of its own; its record for the comparison."""
    folder = arguments.output / "runs" / f"{side.name}-{index}"
    shutil.rmtree(folder, ignore_errors=True)
    (folder / "race").mkdir(parents=True)
    references = side.folder / "references"  # the exact images, ray cast once per side
    references.mkdir(exist_ok=True)
    (folder / "race" / "references").symlink_to(references, target_is_directory=True)
    command = [python, str(HERE / "run_race.py"), str(folder / "loaded.json"), "bench",
               "--sections", "race", "--scenes", ",".join(arguments.scenes),
               "--race-size", str(arguments.size), "--output", str(folder)]
    load = os.getloadavg()
    started = time.monotonic()
    print(f"bench-compare: race {index} of the {side.name} (load {load[0]:.1f})", flush=True)
    logged(command, folder / "race.log", env=run_environment(side), cwd=folder)
    loaded = json.loads((folder / "loaded.json").read_text(encoding="utf-8"))
    outside = foreign(loaded, side.build)
    if outside or not loaded["libraries"]:
        raise RuntimeError(f"the {side.name}'s race loaded {outside or 'no SPT library'}, "
                           f"not only its own build tree {side.build}")
    bench = json.loads((folder / "bench.json").read_text(encoding="utf-8"))
    race = comparison.race_of(bench, arguments.scenes, arguments.size)
    return {"side": side.name, "index": index, "folder": str(folder), "loaded": loaded,
            "load_average": list(load), "load_average_after": list(os.getloadavg()),
            "wall_seconds": time.monotonic() - started, "machine": bench.get("machine"),
            "scenes": {name: comparison.scene_figures(race, name) for name in arguments.scenes}}


def _at_least(least: int):
    def parse_count(text: str) -> int:
        if not text.isdigit() or int(text) < least:
            raise argparse.ArgumentTypeError(f"{text} is not a whole number >= {least}")
        return int(text)
    return parse_count


def _scenes(text: str) -> List[str]:
    names = [name.strip() for name in text.split(",") if name.strip()]
    if not names:
        raise argparse.ArgumentTypeError("no scene named")
    return names


def parse(argv: Optional[Sequence[str]] = None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--base", required=True, help="the git reference to compare with")
    parser.add_argument("--scenes", type=_scenes, required=True,
                        help="comma-separated race scenes (they must exist in both)")
    # One run per side cannot tell a change from the noise of the runs.
    parser.add_argument("--runs", type=_at_least(2), default=2,
                        help="races per side, at least 2 (default 2)")
    parser.add_argument("--size", type=_at_least(1), default=256,
                        help="the race's image width and height (default 256)")
    parser.add_argument("--jobs", type=_at_least(1), default=os.cpu_count() or 1)
    parser.add_argument("--vtk-dir", required=True, help="VTK_DIR of both builds")
    parser.add_argument("--python", default=sys.executable,
                        help="the interpreter of both builds and their races")
    parser.add_argument("--output", type=pathlib.Path,
                        default=ROOT / "out" / "bench-compare")
    return parser.parse_args(argv)


def check_data(scenes: Sequence[str]) -> None:
    """A ValueError before anything is built if a scene reads the real data sets (all but
    the generated ``drill-*`` meshes) and ``SPT_DATA_DIR`` names no folder."""
    folder = os.environ.get("SPT_DATA_DIR", "")
    needing = [name for name in scenes if not name.startswith("drill-")]
    if needing and not os.path.isdir(folder):
        raise ValueError(f"the scenes {', '.join(needing)} read the real data sets, and "
                         f"SPT_DATA_DIR={folder!r} names no folder: "
                         "make bench-compare SPT_DATA_DIR=<folder of the data sets> ...")


def compare(arguments: argparse.Namespace) -> comparison.Record:
    """Build both sides, race them alternately and write compare.json; returns it."""
    check_data(arguments.scenes)
    output = arguments.output = arguments.output.resolve()
    base_commit = commit_of(arguments.base)
    commits = {"head": git("rev-parse", "HEAD"), "base": base_commit,
               "base_reference": arguments.base,
               "modified": bool(git("status", "--porcelain", "--untracked-files=no"))}
    head = Side("head", ROOT, output / "head")
    base = Side("base", checkout(base_commit, output / "base"), output / "base")
    for side in (head, base):
        build(side, arguments.vtk_dir, arguments.python, arguments.jobs)
    sides = {"head": head, "base": base}
    runs = [race_run(sides[name], index, arguments, arguments.python)
            for name, index in schedule(arguments.runs)]
    settings = {"scenes": arguments.scenes, "runs": arguments.runs, "size": arguments.size,
                "data": os.environ.get("SPT_DATA_DIR")}
    result = comparison.comparison(runs, arguments.scenes, commits, settings)
    (output / "compare.json").write_text(json.dumps(result, indent=1), encoding="utf-8")
    return result


def main(argv: Optional[Sequence[str]] = None) -> int:
    arguments = parse(argv)
    try:
        result = compare(arguments)
    except (OSError, ValueError, RuntimeError, subprocess.CalledProcessError) as error:
        print(f"bench-compare: error: {error}", file=sys.stderr)
        return 1
    print(comparison.table(result))
    print(f"bench-compare: {arguments.output / 'compare.json'} written")
    return 0


if __name__ == "__main__":
    sys.exit(main())
