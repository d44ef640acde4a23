#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Inputs for the library swaps' measurements (docs/benchmarks.md, "Libraries in place of
hand-written code"): a 192^3 float32 volume (normal(0, 300), seed 5, every 7th z slice times
1e-6 so that subnormal halves occur) as DIR/in.npy, and the same values as VTK XML image data
with the array appended raw (DIR/raw.vti) and inline base64 (DIR/inline.vti), UInt32 headers.

Usage: make_library_bench_inputs.py DIR   (Debian's python3, for NumPy)
"""
import base64
import os
import struct
import sys

import numpy as np


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    values = (np.random.default_rng(5).standard_normal((192, 192, 192)) * 300).astype(np.float32)
    values[::7] *= 1e-6
    np.save(os.path.join(out, "in.npy"), values)
    n = values.shape[0]
    extent = f"0 {n - 1} 0 {n - 1} 0 {n - 1}"
    data = values.astype("<f4").tobytes()
    counted = struct.pack("<I", len(data)) + data
    head = ('<?xml version="1.0"?>\n<VTKFile type="ImageData" version="0.1" '
            'byte_order="LittleEndian" header_type="UInt32">\n'
            f'<ImageData WholeExtent="{extent}" Origin="0 0 0" Spacing="1 1 1">\n'
            f'<Piece Extent="{extent}"><PointData Scalars="v">\n')
    with open(os.path.join(out, "raw.vti"), "wb") as f:
        f.write((head + '<DataArray type="Float32" Name="v" format="appended" offset="0"/>\n'
                 '</PointData></Piece></ImageData>\n<AppendedData encoding="raw">\n   _').encode())
        f.write(counted)
        f.write(b"\n</AppendedData>\n</VTKFile>\n")
    with open(os.path.join(out, "inline.vti"), "wb") as f:
        f.write((head + '<DataArray type="Float32" Name="v" format="binary">\n').encode())
        f.write(base64.b64encode(counted))
        f.write(b"\n</DataArray>\n</PointData></Piece></ImageData>\n</VTKFile>\n")


if __name__ == "__main__":
    main()
