"""The tests' scenes and their exact references, made once per test process."""

from functools import lru_cache

from spt import render, scenes

from conftest import load_or_skip


@lru_cache(maxsize=None)
def scene(name: str) -> scenes.Scene:
    """A scene of spt.scenes; a skip when its data set is not in SPT_DATA_DIR."""
    if name != "default":
        load_or_skip(name)
    return scenes.scene(name)


@lru_cache(maxsize=None)
def reference(name: str, size: int):
    """The exact reference image of the scene at size x size pixels."""
    s = scene(name)
    return render.reference(s.grid, s.property, s.view, (size, size)).image
