"""Run inside the GUI at the end of the test script (gui_pick_spt.xml), in its Python shell:
keep what the GUI shows and the state the user set.

Environment: SPT_GUI_OUTPUT (directory for window.xwd, view.png and state.json) and
SPT_GUI_FRAMEBUFFER (the screen file of the Xvfb started with -fbdir).
"""

import json
import os
import pathlib
import shutil

from paraview import simple

output = pathlib.Path(os.environ["SPT_GUI_OUTPUT"])
# The whole window first, as drawn: Xvfb keeps its screen as an X window dump.
shutil.copy(os.environ["SPT_GUI_FRAMEBUFFER"], output / "window.xwd")

display = simple.GetDisplayProperties()
view = simple.GetActiveView()
active = display.GetClientSideObject().GetActiveRepresentation()
mapper = active.GetActiveVolumeMapper() if hasattr(active, "GetActiveVolumeMapper") else None
state = {
    "representation": display.SMProxy.GetProperty("Representation").GetElement(0),
    "RepetitionLevel": int(display.RepetitionLevel),
    "Seed": int(display.Seed),
    "mapper_class": mapper.GetClassName() if mapper else None,
}
(output / "state.json").write_text(json.dumps(state, indent=1))
simple.SaveScreenshot(str(output / "view.png"), view, ImageResolution=[300, 300])
