#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""How many samples enter a node's k-nearest set from one node to the next along x, on the 3-D
goal run's grid (docs/kriging.md, "Where a 3-D node's time goes"): it sizes what updating the
previous node's Cholesky factor would cost against factoring afresh.

Usage: neighbour_set_changes.py [SAMPLES_CSV] [--dims D] [--extent E] [-k K] [--pairs N]
(defaults: /tmp/voxlink-krige-scale/samples200000.csv from krige_scale.py, 216 nodes over
[0, 127] per axis, k 32, 2000 random node pairs; needs numpy and scipy: Debian's python3).
"""
import argparse

import numpy as np
from scipy.spatial import cKDTree


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("samples", nargs="?", default="/tmp/voxlink-krige-scale/samples200000.csv")
    ap.add_argument("--dims", type=int, default=216)
    ap.add_argument("--extent", type=float, default=127)
    ap.add_argument("-k", type=int, default=32)
    ap.add_argument("--pairs", type=int, default=2000)
    a = ap.parse_args()
    points = np.loadtxt(a.samples, delimiter=",", skiprows=1, usecols=(0, 1, 2))
    tree = cKDTree(points)
    step = a.extent / (a.dims - 1)
    rng = np.random.default_rng(1)
    nodes = np.stack([rng.integers(0, a.dims - 1, a.pairs), rng.integers(0, a.dims, a.pairs),
                      rng.integers(0, a.dims, a.pairs)], 1) * step
    _, before = tree.query(nodes, a.k)
    _, after = tree.query(nodes + [step, 0, 0], a.k)
    entering = np.array([len(set(b) - set(p)) for b, p in zip(after, before)])
    print(f"{len(points)} samples, {a.k} nearest, node step {step:.4f} along x, {a.pairs} pairs")
    print(f"samples entering per step: mean {entering.mean():.2f}, median {np.median(entering):.0f}, "
          f"same set {100 * (entering == 0).mean():.1f} %")
    print("histogram (0, 1, ..., 8 or more):", np.bincount(np.minimum(entering, 8), minlength=9))


if __name__ == "__main__":
    main()
