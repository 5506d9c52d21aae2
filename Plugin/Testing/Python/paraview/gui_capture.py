"""Run inside the GUI by the test script (gui_pick_methods.xml), in its Python shell, after each
method was picked: keep what the GUI shows and the state the user set.

SPT_GUI_STEP (set in the shell before this runs: spt, havs or pbvr) names the files:
window_STEP.xwd, view_STEP.png and state_STEP.json in SPT_GUI_OUTPUT. SPT_GUI_FRAMEBUFFER is the
screen file of the Xvfb started with -fbdir.
"""

import json
import os
import pathlib
import shutil
import traceback

from paraview import simple

import spt  # noqa: F401 -- wraps the plugin's mappers as their own classes (GetKBufferSize, ...)

step = globals().get("SPT_GUI_STEP", "spt")
output = pathlib.Path(os.environ["SPT_GUI_OUTPUT"])
# The whole window first, as drawn: Xvfb keeps its screen as an X window dump.
shutil.copy(os.environ["SPT_GUI_FRAMEBUFFER"], output / f"window_{step}.xwd")


def capture():
    display = simple.GetDisplayProperties()
    view = simple.GetActiveView()
    active = display.GetClientSideObject().GetActiveRepresentation()
    mapper = active.GetActiveVolumeMapper() if hasattr(active, "GetActiveVolumeMapper") else None
    names = {"spt": ("RepetitionLevel", "Seed"), "havs": ("KBufferSize",),
             "pbvr": ("PBVRRepetitionLevel", "PBVRSeed")}[step]
    state = {
        "representation": display.SMProxy.GetProperty("Representation").GetElement(0),
        # What the representation combo box lists.
        "representation_types": list(display.GetProperty("Representation").Available),
        "settings": {name: int(display.SMProxy.GetProperty(name).GetElement(0))
                     for name in names},
        "mapper_class": mapper.GetClassName() if mapper else None,
        "mapper_settings": {name: int(getattr(mapper, "Get" + name.replace("PBVR", ""))())
                            for name in names} if mapper else {},
    }
    (output / f"state_{step}.json").write_text(json.dumps(state, indent=1))
    simple.SaveScreenshot(str(output / f"view_{step}.png"), view, ImageResolution=[300, 300])


# The shell would keep an error to itself: leave it where the test finds it.
try:
    capture()
except Exception:
    (output / f"error_{step}.txt").write_text(traceback.format_exc())
