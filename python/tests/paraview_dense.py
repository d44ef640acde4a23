# SPDX-License-Identifier: BSD-3-Clause
# Run by pvpython (test_paraview.py): opens a dense file `voxlink export` wrote (NRRD, or a
# detached .nhdr header with its .raw) with ParaView's own readers, no plugin, and prints its
# shape, spacing, origin, scalar type and the values at the given voxels as JSON.
import json
import sys

from paraview import servermanager, simple

path, probes = sys.argv[1], json.loads(sys.argv[2])
reader = simple.OpenDataFile(path)
reader.UpdatePipeline()
data = servermanager.Fetch(reader)
scalars = data.GetPointData().GetScalars()
print(json.dumps({"proxy": reader.GetXMLName(), "class": data.GetClassName(),
                  "dims": list(data.GetDimensions()), "spacing": list(data.GetSpacing()),
                  "origin": list(data.GetOrigin()), "type": scalars.GetDataTypeAsString(),
                  "sample": [scalars.GetTuple1(data.ComputePointId(list(p))) for p in probes]}))
