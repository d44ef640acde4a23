# SPDX-License-Identifier: BSD-3-Clause
# Run by the ParaView GUI at start-up (`paraview --script`, test_paraview.py): loads the reader
# plugin as a user would from the Python shell, then, whenever a proxy is registered (the
# reader when the open dialog picks the file, its representation after Apply), writes what the
# GUI's pipeline holds to $VOXLINK_OUT as JSON. The file is opened by the recorded GUI events
# in paraview_gui_open.xml, not by this script.
import inspect
import json
import os

# Debian 12's ParaView 5.11 imports inspect.getargspec, which Python 3.11 removed (docs/paraview.md).
if not hasattr(inspect, "getargspec"):
    inspect.getargspec = inspect.getfullargspec

from paraview import servermanager, simple  # noqa: E402

simple.LoadPlugin(os.environ["VOXLINK_PLUGIN"], ns=globals())


def report(*_):
    try:
        sources = simple.GetSources()
    except Exception:  # registrations during start-up, before the pipeline exists
        return
    for (name, _), source in sources.items():
        if source.GetXMLName() != "VoxLinkReader":
            continue
        # Only once Apply made a representation: servermanager.GetRepresentation finds one,
        # it never makes one (simple.GetDisplayProperties would, and show the data itself).
        shown = [v.GetXMLName() for v in simple.GetViews()
                 if (rep := servermanager.GetRepresentation(source, v)) and rep.Visibility]
        if not shown:
            continue
        info = source.GetDataInformation()
        points = info.GetPointDataInformation()
        out = {"name": name, "proxy": source.GetXMLName(), "class": info.GetDataClassName(),
               "points": info.GetNumberOfPoints(),
               "arrays": sorted(points.GetArrayInformation(i).GetName()
                                for i in range(points.GetNumberOfArrays())),
               "shown_in": shown}
        with open(os.environ["VOXLINK_OUT"], "w") as f:
            json.dump(out, f)


servermanager.vtkSMProxyManager.GetProxyManager().GetActiveSessionProxyManager().AddObserver(
    "RegisterEvent", report)
