"""Run ``python3 -m spt`` of whichever package ``spt`` this interpreter finds, in this process,
and record which package and which of its libraries that process really loaded.

    python3 run_race.py LOADED.json bench --sections race ...

runs ``spt``'s own command line with the arguments after LOADED.json, exactly as
``python3 -m spt`` would, then writes LOADED.json: the package's folder, and every mapped
file of this process that is one of the project's libraries (``libSPT*``) or lies in the
package's folder (its wrapped extension modules). The comparison checks those against the
build tree it built, so that a run cannot silently measure another build's libraries.
"""

from __future__ import annotations

import json
import os
import pathlib
import runpy
import sys
from typing import Dict, List


def mapped_files() -> List[str]:
    """The files mapped into this process (Linux: /proc/self/maps)."""
    files = set()
    with open("/proc/self/maps", encoding="utf-8") as maps:
        for line in maps:
            fields = line.split(maxsplit=5)
            if len(fields) == 6 and fields[5].startswith("/"):
                files.add(fields[5].strip())
    return sorted(files)


def loaded(package_folder: pathlib.Path) -> Dict[str, object]:
    """The package's folder and the project's libraries this process has mapped."""
    folder = str(package_folder.resolve())
    libraries = [path for path in mapped_files()
                 if os.path.basename(path).startswith("libSPT")
                 or path.startswith(folder + os.sep)]
    return {"package": folder, "libraries": libraries, "python": sys.executable}


def main(arguments: List[str]) -> int:
    if len(arguments) < 2:
        print("usage: run_race.py LOADED.json COMMAND [ARGUMENTS...]", file=sys.stderr)
        return 2
    record, command = pathlib.Path(arguments[0]), arguments[1:]
    status = 0
    sys.argv = ["spt"] + command
    try:
        runpy.run_module("spt", run_name="__main__", alter_sys=True)
    except SystemExit as done:
        status = done.code if isinstance(done.code, int) else (0 if done.code is None else 1)
    finally:
        package = sys.modules.get("spt")
        if package is not None and getattr(package, "__file__", None):
            found = loaded(pathlib.Path(package.__file__).parent)
            record.write_text(json.dumps(found, indent=1), encoding="utf-8")
    return status


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
