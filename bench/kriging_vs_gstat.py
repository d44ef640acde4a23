#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""voxlink krige against R's gstat on the same job, in the same run (docs/kriging.md).

Walker Lake: 470 samples of V -> the 260 x 300 grid, spherical(nugget 22144, psill 70207.9,
range 35.085), ordinary kriging, globally and with the 32 nearest samples (gstat's nmax).
Times gstat's krige() call alone (R's start-up and CSV reading excluded) and voxlink's kriging
(the `time:` line: the grid solve) plus voxlink's whole process (start-up, reading, writing);
medians of several runs. Then compares every node's estimate and variance with gstat's:
|ours - gstat| / max(|gstat|, 1e-6 x scale), scale = the sill for variances and the samples'
standard deviation for estimates; nodes whose k-th and (k+1)-th nearest samples are equally
far are left out (either neighbour set is right) and counted.

--drift linear|quadratic runs universal kriging instead (gstat's V ~ X + Y, or with
I(X^2) + I(X*Y) + I(Y^2)). --neighbours 8,32,0 picks the neighbourhood sizes (0: all samples;
default 32,0). Both sides' RMSE against the exhaustive grid (walker.exh.csv, the true V at
every node) is printed too; --json FILE writes the rows for bench/report.py. VOXLINK_RSCRIPT
names the Rscript to run (default: Rscript on PATH).

Usage: kriging_vs_gstat.py VOXLINK [DATA_DIR] [--runs N] [--gstat-runs N] [--threads N]
                           [--drift none|linear|quadratic] [--neighbours K,...] [--json FILE]
"""
import json
import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_timing import run  # noqa: E402

NUGGET, PSILL, RANGE = 22144.0, 70207.9, 35.085
TRENDS = {"none": "1", "linear": "X + Y", "quadratic": "X + Y + I(X^2) + I(X*Y) + I(Y^2)"}


def gstat(script, samples, nmax, runs, out, drift):
    cmd = [os.environ.get("VOXLINK_RSCRIPT", "Rscript"), script, samples, "V", "Sph", repr(NUGGET), repr(PSILL), repr(RANGE),
           str(nmax), str(runs), out, TRENDS[drift]]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"gstat failed: {' '.join(cmd)}\n{p.stdout}{p.stderr}")
    return [float(s) for s in re.findall(r"seconds ([\d.]+)", p.stdout)]


def voxlink(exe, samples, k, threads, out, drift):
    cmd = [exe, "krige", samples, "--value", "V", "--variogram",
           f"sph:nugget={NUGGET},psill={PSILL},range={RANGE}", "-k", str(k), "--dims", "260,300",
           "--origin", "1,1", "--spacing", "1,1", "--threads", str(threads), "--drift", drift,
           "-o", out]
    stdout, wall, rss = run(cmd)
    return float(re.search(r"^time: ([\d.e+-]+) s", stdout, re.M).group(1)), wall, rss, stdout


def tie_nodes(samples_xy, k):
    """Nodes whose k-th and (k+1)-th nearest samples are equally far (1e-12 relative)."""
    gx, gy = np.meshgrid(np.arange(1, 261.0), np.arange(1, 301.0))
    nodes = np.stack([gx.ravel(), gy.ravel()], axis=1)
    ties = np.zeros(len(nodes), dtype=bool)
    for s in range(0, len(nodes), 4000):
        d = np.sqrt(((nodes[s:s + 4000, None, :] - samples_xy[None, :, :]) ** 2).sum(axis=2))
        part = np.partition(d, (k - 1, k), axis=1)
        kth, next_ = part[:, k - 1], part[:, k]
        ties[s:s + 4000] = next_ - kth <= 1e-12 * np.maximum(kth, 1.0)
    return ties


def exhaustive_v(data):
    """The true V at the 260 x 300 nodes, in the grid's order (x fastest, then y)."""
    t = np.genfromtxt(os.path.join(data, "geostat/gstat_csv/walker.exh.csv"), delimiter=",",
                      names=True)
    truth = np.full((300, 260), np.nan)
    truth[t["y"].astype(int) - 1, t["x"].astype(int) - 1] = t["V"]
    return truth.ravel()


def rmse(estimate, truth):
    return float(np.sqrt(np.mean((estimate - truth) ** 2)))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("voxlink")
    ap.add_argument("data", nargs="?", default="../shared/data")
    ap.add_argument("--runs", type=int, default=7)
    ap.add_argument("--gstat-runs", type=int, default=3)
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--drift", choices=sorted(TRENDS), default="none")
    ap.add_argument("--neighbours", default="32,0")
    ap.add_argument("--json")
    a = ap.parse_args()
    neighbours = [int(k) for k in a.neighbours.split(",")]
    truth = exhaustive_v(a.data)
    rows = []
    samples = os.path.join(a.data, "geostat/gstat_csv/walker.csv")
    script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "gstat_krige_timed.R")
    table = np.genfromtxt(samples, delimiter=",", names=True)
    table = table[~np.isnan(table["V"])]
    xy = np.stack([table["X"], table["Y"]], axis=1)
    sd = float(np.std(table["V"]))
    sill = NUGGET + PSILL
    print(f"Walker Lake: {len(xy)} samples -> 260 x 300 = 78000 nodes, spherical(nugget={NUGGET},"
          f" psill={PSILL}, range={RANGE}), "
          f"{'ordinary kriging' if a.drift == 'none' else 'universal kriging, gstat V ~ ' + TRENDS[a.drift]}; voxlink --threads {a.threads} "
          f"(0: all {os.cpu_count()} cores), gstat one R process")
    print(f"{'neighbours':>10} {'gstat_s':>8} {'voxlink_s':>9} {'ratio':>7} {'process_s':>9} "
          f"{'ratio':>7} {'max_rel_pred':>12} {'max_rel_var':>11} {'compared':>8} {'ties':>5}"
          f" {'rmse_vs_true':>12} {'gstat_rmse':>10}"
          f"   (voxlink runs, s)")
    with tempfile.TemporaryDirectory() as tmp:
        for k in neighbours:
            gcsv = os.path.join(tmp, f"gstat_{k}.csv")
            g_times = gstat(script, samples, k, a.gstat_runs, gcsv, a.drift)
            out = os.path.join(tmp, f"v{k}.nhdr")
            runs = [voxlink(a.voxlink, samples, k, a.threads, out, a.drift) for _ in range(a.runs)]
            solve = statistics.median(r[0] for r in runs)
            wall = statistics.median(r[1] for r in runs)
            g = np.genfromtxt(gcsv, delimiter=",", names=True)
            pred = np.fromfile(os.path.join(tmp, f"v{k}.raw"), dtype="<f8")
            var = np.fromfile(os.path.join(tmp, f"v{k}_variance.raw"), dtype="<f8")
            keep = ~tie_nodes(xy, k) if k else np.ones(len(pred), dtype=bool)
            rel_p = np.abs(pred - g["pred"]) / np.maximum(np.abs(g["pred"]), 1e-6 * sd)
            rel_v = np.abs(var - g["var"]) / np.maximum(np.abs(g["var"]), 1e-6 * sill)
            g_med = statistics.median(g_times)
            rows.append({"neighbours": k, "gstat_s": g_med, "voxlink_s": solve,
                         "process_s": wall, "max_rel_pred": float(rel_p[keep].max()),
                         "max_rel_var": float(rel_v[keep].max()), "ties": int((~keep).sum()),
                         "rmse": rmse(pred, truth), "gstat_rmse": rmse(g["pred"], truth)})
            print(f"{k if k else 'all':>10} {g_med:8.3f} {solve:9.4f} {g_med / solve:7.1f} "
                  f"{wall:9.3f} {g_med / wall:7.1f} {rel_p[keep].max():12.2e} "
                  f"{rel_v[keep].max():11.2e} {int(keep.sum()):8d} {int((~keep).sum()):5d}"
                  f" {rows[-1]['rmse']:12.2f} {rows[-1]['gstat_rmse']:10.2f}"
                  f"   ({' '.join(f'{r[0]:.4f}' for r in runs)}; gstat "
                  f"{' '.join(f'{t:.2f}' for t in g_times)})")

    if a.json:
        with open(a.json, "w") as f:
            json.dump(rows, f, indent=1)


if __name__ == "__main__":
    main()
