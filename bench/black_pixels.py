#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Pixels black in a voxel image where the exact image is lit: every RGB channel of VOXEL.png
under 0.02 and some channel of EXACT.png over 0.1 (rays that leave the scene through a surface,
docs/surface-modes.md, "Rays through the red wall"). Prints the count and the first 60 (x, y).

usage: black_pixels.py EXACT.png VOXEL.png
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from image_diff import read_png  # noqa: E402


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    w, h, exact = read_png(sys.argv[1])
    vw, vh, voxel = read_png(sys.argv[2])
    if (w, h) != (vw, vh):
        sys.exit("the images differ in size")
    where = [(x, y) for y in range(h) for x in range(w)
             if max(voxel[y][x][:3]) < 0.02 * 255 and max(exact[y][x][:3]) > 0.1 * 255]
    print(len(where), where[:60])


if __name__ == "__main__":
    main()
