#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Walker Lake's exhaustive U as a 260 x 300 grid for `voxlink krige --external-drift-grid`.

Usage: walker_u_grid.py walker.exh.csv OUT.npy
Writes NumPy 1.0, float64, shape (300, 260): node (x, y) at [y - 1][x - 1], the krige grid of
--dims 260,300 --origin 1,1 --spacing 1,1. Standard library only.
"""
import csv
import struct
import sys


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    grid = [float("nan")] * (260 * 300)
    with open(sys.argv[1], newline="") as f:
        for row in csv.DictReader(f):
            grid[(int(row["y"]) - 1) * 260 + int(row["x"]) - 1] = float(row["U"])
    missing = sum(1 for v in grid if v != v)
    if missing:
        sys.exit(f"{sys.argv[1]}: {missing} of the 78000 nodes have no U")
    header = "{'descr': '<f8', 'fortran_order': False, 'shape': (300, 260), }"
    header += " " * (63 - (10 + len(header)) % 64) + "\n"
    with open(sys.argv[2], "wb") as out:
        out.write(b"\x93NUMPY\x01\x00" + struct.pack("<H", len(header)) + header.encode())
        out.write(struct.pack("<78000d", *grid))


if __name__ == "__main__":
    main()
