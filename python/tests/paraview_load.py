# SPDX-License-Identifier: BSD-3-Clause
# Run by pvpython (test_paraview.py): loads the reader plugin, opens a .vxl through ParaView's
# own file-type lookup, prints what the output holds as JSON and renders a contour to a PNG.
import inspect
import json
import sys

# Debian 12's ParaView 5.11 imports inspect.getargspec, which Python 3.11 removed; the plugin
# loader needs it back (docs/paraview.md).
if not hasattr(inspect, "getargspec"):
    inspect.getargspec = inspect.getfullargspec

from paraview import simple, servermanager  # noqa: E402

plugin, vxl, png = sys.argv[1:4]
simple.LoadPlugin(plugin, ns=globals())
# The file types ParaView's open dialog offers come from its reader factory.
session = servermanager.ActiveConnection.Session
types = servermanager.vtkSMProxyManager.GetProxyManager().GetReaderFactory().GetSupportedFileTypes(
    session)
dialog_filters = [t for t in types.split(";;") if t.startswith("VoxLink")]
reader = simple.OpenDataFile(vxl)
reader.UpdatePipeline()
data = servermanager.Fetch(reader)
points = data.GetPointData()
arrays = {}
for i in range(points.GetNumberOfArrays()):
    a = points.GetArray(i)
    arrays[a.GetName()] = {"components": a.GetNumberOfComponents(),
                           "range": list(a.GetRange(-1 if a.GetNumberOfComponents() > 1 else 0))}
sample = [data.GetPointData().GetArray("values").GetTuple1(data.ComputePointId(list(p)))
          for p in json.loads(sys.argv[4])]
result = {"dialog_filters": dialog_filters, "proxy": reader.GetXMLName(), "class": data.GetClassName(),
                  "dims": list(data.GetDimensions()), "spacing": list(data.GetSpacing()),
                  "origin": list(data.GetOrigin()), "arrays": arrays,
                  "scalars": points.GetScalars().GetName(),
                  "vectors": points.GetVectors().GetName(), "sample": sample}
view = simple.CreateRenderView()
view.ViewSize = [128, 128]
view.OrientationAxesVisibility = 0
contour = simple.Contour(Input=reader, ContourBy=["POINTS", "values"], Isosurfaces=[60])
simple.Show(contour, view)
view.CameraPosition = [600, -300, 300]
view.CameraFocalPoint = [128, 128, 128]
view.CameraViewUp = [0, 0, 1]
simple.ResetCamera(view)
simple.Render(view)
simple.SaveScreenshot(png, view, ImageResolution=[128, 128])

# Pixels of the screenshot that differ from its corner (the background): the foot is drawn.
from vtkmodules.vtkIOImage import vtkPNGReader  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402

png_reader = vtkPNGReader()
png_reader.SetFileName(png)
png_reader.Update()
pixels = vtk_to_numpy(png_reader.GetOutput().GetPointData().GetScalars())
result["image_pixels"] = int(len(pixels))
result["foreground_pixels"] = int((abs(pixels.astype(int) - pixels[0].astype(int)).max(axis=1) > 8).sum())
print(json.dumps(result))
