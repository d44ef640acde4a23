#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Local kriging at scale (docs/kriging.md): samples of a generated 3-D Gaussian random field
with a known covariance, kriged onto a large 3-D grid with the same model.

1. `voxlink grf` makes an N^3 field with exponential(psill 1, practical range R voxels);
2. S distinct voxels chosen at random (fixed seed) are the samples (x, y, z, v) in a CSV;
3. `voxlink krige -k K` krige them onto a D^3 grid spanning the field, timed with /usr/bin/time
   (wall time and peak resident memory), output discarded afterwards;
4. optionally R's gstat on the first slices of the same grid (same samples, model, nmax), to
   compare the time per node.

`--krige-model sph` krigs with a spherical model of the same range instead (the field stays
exponential): a compactly supported covariance, which global kriging solves per node on the
samples within the range (docs/kriging.md); gstat then uses "Sph" too.

Usage: krige_scale.py VOXLINK [--field 128] [--range 16] [--samples 200000] [--dims 216]
       [--neighbours 32] [--gstat-slices 0] [--krige-model exp|sph]
       [--dir /tmp/voxlink-krige-scale]
"""
import argparse
import os
import re
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_timing import run  # noqa: E402

GSTAT = r"""
suppressPackageStartupMessages(library(gstat))
a <- commandArgs(trailingOnly = TRUE)
d <- read.csv(a[1])
s <- as.numeric(a[3]); n <- as.integer(a[4]); slices <- as.integer(a[5])
g <- expand.grid(x = (0:(n - 1)) * s, y = (0:(n - 1)) * s, z = (0:(slices - 1)) * s)
m <- if (a[7] == "sph") vgm(1, "Sph", as.numeric(a[2]), 0) else vgm(1, "Exp", as.numeric(a[2]) / 3, 0)
t <- system.time(k <- krige(v ~ 1, ~x + y + z, d, newdata = g, model = m,
                            nmax = as.integer(a[6]), debug.level = 0))
cat("seconds", t[["elapsed"]], "nodes", nrow(g), "\n")
"""


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("voxlink")
    ap.add_argument("--field", type=int, default=128)
    ap.add_argument("--range", type=float, default=16)
    ap.add_argument("--samples", type=int, default=200000)
    ap.add_argument("--dims", type=int, default=216)
    ap.add_argument("--neighbours", type=int, default=32)
    ap.add_argument("--gstat-slices", type=int, default=0)
    ap.add_argument("--krige-model", choices=("exp", "sph"), default="exp")
    ap.add_argument("--dir", default="/tmp/voxlink-krige-scale")
    a = ap.parse_args()
    os.makedirs(a.dir, exist_ok=True)
    field = os.path.join(a.dir, f"field{a.field}.npy")
    model = f"exp:psill=1,range={a.range}"
    if not os.path.exists(field):
        run([a.voxlink, "grf", "--dims", f"{a.field},{a.field},{a.field}", "--variogram", model,
             "--seed", "3", "-o", field])
    values = np.load(field)  # (z, y, x)
    rng = np.random.default_rng(7)
    picked = rng.choice(values.size, size=a.samples, replace=False)
    z, y, x = np.unravel_index(picked, values.shape)
    csv = os.path.join(a.dir, f"samples{a.samples}.csv")
    with open(csv, "w") as f:
        f.write("x,y,z,v\n")
        np.savetxt(f, np.stack([x, y, z, values[z, y, x]], axis=1), fmt="%d,%d,%d,%.17g")
    krige_model = f"{a.krige_model}:psill=1,range={a.range}"
    spacing = (a.field - 1) / (a.dims - 1)
    out = os.path.join(a.dir, "k.npy")
    nodes = a.dims ** 3
    stdout, wall, rss = run([a.voxlink, "krige", csv, "--x", "x", "--y", "y", "--z", "z",
                             "--value", "v", "--variogram", krige_model, "-k", str(a.neighbours),
                             "--dims", f"{a.dims},{a.dims},{a.dims}", "--origin", "0,0,0",
                             "--spacing", f"{spacing!r},{spacing!r},{spacing!r}", "-o", out])
    solve = float(re.search(r"^time: ([\d.e+-]+) s", stdout, re.M).group(1))
    kriged = np.load(out)
    finite = bool(np.isfinite(kriged).all())
    for f in (out, os.path.join(a.dir, "k_variance.npy")):
        os.remove(f)
    kriged_with = f", kriged with {krige_model}" if a.krige_model != "exp" else ""
    print(f"{a.samples} samples of a {a.field}^3 field ({model}{kriged_with}) -> {a.dims}^3 = {nodes} nodes, "
          f"{a.neighbours} neighbours, {os.cpu_count()} cores")
    print(f"voxlink: kriging {solve:.2f} s ({solve / nodes * 1e6 * os.cpu_count():.2f} us per "
          f"node per core), process {wall:.2f} s, peak RSS {rss:.0f} MiB, all finite: {finite}")
    print("  " + "\n  ".join(line for line in stdout.splitlines()
                              if line.startswith(("systems", "worst", "compact", "peak"))))
    if a.gstat_slices:
        script = os.path.join(a.dir, "gstat_scale.R")
        with open(script, "w") as f:
            f.write(GSTAT)
        t0 = time.time()
        p = subprocess.run(["Rscript", script, csv, str(a.range), repr(spacing), str(a.dims),
                            str(a.gstat_slices), str(a.neighbours), a.krige_model], capture_output=True,
                           text=True)
        if p.returncode != 0:
            sys.exit(f"gstat failed after {time.time() - t0:.0f} s:\n{p.stdout}{p.stderr}")
        secs, count = re.search(r"seconds ([\d.]+) nodes (\d+)", p.stdout).groups()
        per_node = float(secs) / int(count)
        print(f"gstat: {count} nodes ({a.gstat_slices} slices) in {float(secs):.2f} s: "
              f"{per_node * 1e6:.1f} us per node on one core; the {nodes} nodes would take "
              f"~{per_node * nodes:.0f} s")


if __name__ == "__main__":
    main()
