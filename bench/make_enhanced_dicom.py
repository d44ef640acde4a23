#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Writes an uncompressed Enhanced CT multi-frame file of X x Y x Z u16 voxels (per-frame plane
positions, shared orientation and pixel measures), for the multi-frame memory benchmark.
Usage: make_enhanced_dicom.py OUT X Y Z"""
import os
import struct
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "fuzz"))
from make_seeds import dicom_element as e  # noqa: E402


def main(out, x, y, z):
    us = lambda g, el, v: e(g, el, b"US", struct.pack("<H", v))
    frames = [e(0x0020, 0x9113, b"SQ", [e(0x0020, 0x0032, b"DS", "0\\0\\%g" % k)]) for k in range(z)]
    shared = (e(0x0020, 0x9116, b"SQ", [e(0x0020, 0x0037, b"DS", "1\\0\\0\\0\\1\\0")]) +
              e(0x0028, 0x9110, b"SQ", [e(0x0028, 0x0030, b"DS", "0.5\\0.5")]))
    meta_body = e(0x0002, 0x0001, b"OB", b"\0\1") + e(0x0002, 0x0010, b"UI", "1.2.840.10008.1.2.1")
    meta = e(0x0002, 0x0000, b"UL", struct.pack("<I", len(meta_body))) + meta_body
    body = (e(0x0008, 0x0016, b"UI", "1.2.840.10008.5.1.4.1.1.2.1") + e(0x0008, 0x0060, b"CS", "CT") +
            e(0x0020, 0x000E, b"UI", "1.2.3.4.5.7") + us(0x28, 0x2, 1) +
            e(0x0028, 0x0004, b"CS", "MONOCHROME2") + e(0x0028, 0x0008, b"IS", str(z)) +
            us(0x28, 0x10, y) + us(0x28, 0x11, x) + us(0x28, 0x100, 16) + us(0x28, 0x101, 16) +
            us(0x28, 0x102, 15) + us(0x28, 0x103, 0) + e(0x5200, 0x9229, b"SQ", [shared]) +
            e(0x5200, 0x9230, b"SQ", frames))
    row = bytes(range(256)) * (2 * x // 256 + 1)
    with open(out, "wb") as f:
        f.write(bytes(128) + b"DICM" + meta + body)
        f.write(struct.pack("<HH", 0x7FE0, 0x0010) + b"OW\0\0" + struct.pack("<I", 2 * x * y * z))
        for _ in range(y * z):
            f.write(row[:2 * x])


if __name__ == "__main__":
    main(sys.argv[1], *(int(v) for v in sys.argv[2:5]))
