# SPDX-License-Identifier: BSD-3-Clause
"""ParaView reader plugin for VoxLink (.vxl) files, on the `voxlink` Python module.

Load it in ParaView with Tools > Manage Plugins > Load New (this file), or in pvpython with
LoadPlugin("voxlink_reader.py", ns=globals()); `voxlink` must be importable (PYTHONPATH, see
docs/python.md). A .vxl file loads as vtkImageData over the source grid with point arrays
"values" (the source's type, removed voxels 0), "kept" (1 where a voxel is stored),
"vtkGhostType" (removed voxels marked hidden, so they are blanked) and the vector "gradient"
(decoded unit gradients, (0,0,0) where removed or zero).
"""
import numpy as np
from paraview.util.vtkAlgorithm import (VTKPythonAlgorithmBase, smdomain, smhint, smproperty,
                                        smproxy)
from vtkmodules.util import numpy_support
from vtkmodules.vtkCommonDataModel import vtkDataSetAttributes, vtkImageData

import voxlink


def _point_array(name, values):
    array = numpy_support.numpy_to_vtk(np.ascontiguousarray(values), deep=1)
    array.SetName(name)
    return array


@smproxy.reader(name="VoxLinkReader", label="VoxLink sparse volume", extensions="vxl",
                file_description="VoxLink files")
class VoxLinkReader(VTKPythonAlgorithmBase):
    def __init__(self):
        VTKPythonAlgorithmBase.__init__(self, nInputPorts=0, nOutputPorts=1,
                                        outputType="vtkImageData")
        self._path = None
        self._file = None

    @smproperty.stringvector(name="FileName")
    @smdomain.filelist()
    @smhint.filechooser(extensions="vxl", file_description="VoxLink files")
    def SetFileName(self, path):
        if path != self._path:
            self._path = path
            self._file = None
            self.Modified()

    def _open(self):
        if self._file is None:
            self._file = voxlink.open(self._path)  # validated: raises voxlink.Error otherwise
        return self._file

    def RequestInformation(self, request, in_info, out_info):
        f = self._open()
        info = out_info.GetInformationObject(0)
        nx, ny, nz = f.dims
        info.Set(self.GetExecutive().WHOLE_EXTENT(), 0, nx - 1, 0, ny - 1, 0, nz - 1)
        info.Set(vtkImageData.SPACING(), *f.spacing)
        info.Set(vtkImageData.ORIGIN(), *f.origin)
        return 1

    def RequestData(self, request, in_info, out_info):
        f = self._open()
        out = vtkImageData.GetData(out_info, 0)
        out.SetDimensions(*f.dims)
        out.SetSpacing(*f.spacing)
        out.SetOrigin(*f.origin)
        ijk, _, gradients = f.voxels()
        nx, ny, _ = f.dims
        flat = ijk[:, 0] + nx * (ijk[:, 1].astype(np.int64) + ny * ijk[:, 2].astype(np.int64))
        points = nx * ny * f.dims[2]
        kept = np.zeros(points, np.uint8)
        kept[flat] = 1
        ghosts = np.where(kept == 1, 0, vtkDataSetAttributes.HIDDENPOINT).astype(np.uint8)
        gradient = np.zeros((points, 3), np.float32)
        gradient[flat] = gradients
        data = out.GetPointData()
        data.SetScalars(_point_array("values", f.to_dense(fill=0).ravel()))
        data.AddArray(_point_array("kept", kept))
        data.AddArray(_point_array(vtkDataSetAttributes.GhostArrayName(), ghosts))
        data.SetVectors(_point_array("gradient", gradient))
        return 1
