#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""How often a grid node's k-nearest set equals the previous node's as local kriging walks its
bricks (docs/kriging-speed-log.md, branch krige-32c): row by row from each row's start, and back
and forth (rows alternating along x), on the Walker Lake job of docs/kriging.md (470 samples,
the 260 x 300 grid at spacing 1 from (1, 1), bricks of 16 x 16 nodes). A node whose set equals
the previous one's needs no ranking and no cache lookup. Also counts the steps that the
triangle inequality alone would prove unchanged (the previous node's (k+1)-th distance more
than twice the step beyond its k-th): the test local kriging uses instead is exact, and counts
every kept set.

Usage: brick_walk_kept_sets.py [DATA_DIR] [-k K] [--brick B]
(default DATA_DIR ../shared/data; needs numpy and scipy: Debian's python3).
"""
import argparse
import csv
import os

import numpy as np
from scipy.spatial import cKDTree


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("data", nargs="?", default="../shared/data")
    ap.add_argument("-k", type=int, default=32)
    ap.add_argument("--brick", type=int, default=16)
    a = ap.parse_args()
    with open(os.path.join(a.data, "geostat/gstat_csv/walker.csv")) as f:
        rows = list(csv.DictReader(f))
    tree = cKDTree(np.array([[float(r["X"]), float(r["Y"])] for r in rows]))
    nx, ny, b = 260, 300, a.brick
    for back_and_forth in (False, True):
        same = steps = proved = 0
        for by in range(0, ny, b):
            for bx in range(0, nx, b):
                xs = list(range(bx + 1, min(bx + b, nx) + 1))
                nodes = []
                for row, y in enumerate(range(by + 1, min(by + b, ny) + 1)):
                    line = xs[::-1] if back_and_forth and row % 2 else xs
                    nodes += [(x, y) for x in line]
                at = np.array(nodes, dtype=float)
                distance, nearest = tree.query(at, a.k + 1)
                sets = [frozenset(n[: a.k]) for n in nearest]
                steps += len(sets) - 1
                same += sum(s == p for s, p in zip(sets[1:], sets))
                step = np.hypot(*(at[1:] - at[:-1]).T)
                proved += int(np.sum(distance[:-1, a.k] - distance[:-1, a.k - 1] > 2 * step))
        walk = "back and forth" if back_and_forth else "row by row"
        print(f"{walk}: {same} of {steps} steps keep the {a.k}-nearest set "
              f"({100 * same / steps:.1f} %); the triangle margin proves {proved} "
              f"({100 * proved / steps:.1f} %)")


if __name__ == "__main__":
    main()
