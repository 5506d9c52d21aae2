"""Start-up script of the GUI test (paraview --script): load the plugin and show the mesh.

Environment: SPT_PARAVIEW_PLUGIN (SPT.so) and SPT_GUI_DATA (a legacy .vtk file). The test
script (gui_pick_methods.xml) then picks "Volume (SPT)", "Volume (HAVS-like)" and "Volume (PBVR)"
in the GUI itself.
"""

import os

from paraview import simple

simple.LoadPlugin(os.environ["SPT_PARAVIEW_PLUGIN"], remote=False)
reader = simple.LegacyVTKReader(registrationName="mesh.vtk",
                                FileNames=[os.environ["SPT_GUI_DATA"]])
display = simple.Show(reader)
simple.ColorBy(display, ("POINTS", "field"))
display.RescaleTransferFunctionToDataRange(False, True)
# Few passes while the representation is switched; the panel then sets its own.
display.RepetitionLevel = 4
display.PBVRRepetitionLevel = 4
view = simple.GetActiveView()
view.OrientationAxesVisibility = 0
simple.ResetCamera(view)
simple.Render(view)
