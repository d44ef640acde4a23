#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Two builds of voxlink on the same command: speed and identical outputs (docs/kriging.md,
docs/benchmarks.md, "Libraries in place of hand-written code").

Usage: compare_binaries.py RUNS BEFORE AFTER -- COMMAND...
COMMAND is run RUNS times with each binary, alternating which goes first, {V} replaced by the
binary and {OUT} by an output prefix (/tmp/compare_before or /tmp/compare_after). Prints, per
run, whether every output file of BEFORE has a byte-identical twin from AFTER (SHA-256); then
the median wall time, the median CPU time (user + system, which a loaded machine inflates
far less than the wall time) and the median of the `time:` line (voxlink krige's solve) per
binary, and the load average.
"""
import glob
import hashlib
import os
import re
import resource
import statistics
import subprocess
import sys
import time


def digest(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def main():
    if len(sys.argv) < 6 or sys.argv[4] != "--":
        sys.exit(__doc__)
    runs = int(sys.argv[1])
    exes = {"before": sys.argv[2], "after": sys.argv[3]}
    command = sys.argv[5:]
    times = {k: {"wall": [], "cpu": [], "solve": []} for k in exes}
    for r in range(runs):
        for k in (["before", "after"] if r % 2 == 0 else ["after", "before"]):
            out = f"/tmp/compare_{k}"
            for f in glob.glob(out + "*"):
                os.remove(f)
            cmd = [a.replace("{V}", exes[k]).replace("{OUT}", out) for a in command]
            t0 = time.time()
            u0 = resource.getrusage(resource.RUSAGE_CHILDREN)
            p = subprocess.run(cmd, capture_output=True, text=True)
            wall = time.time() - t0
            u1 = resource.getrusage(resource.RUSAGE_CHILDREN)
            times[k]["cpu"].append(u1.ru_utime - u0.ru_utime + u1.ru_stime - u0.ru_stime)
            if p.returncode:
                sys.exit(f"{k} failed: {p.stderr}")
            times[k]["wall"].append(wall)
            m = re.search(r"^time: ([\d.e+-]+) s", p.stdout, re.M)
            if m:
                times[k]["solve"].append(float(m.group(1)))
        befores = sorted(glob.glob("/tmp/compare_before*"))
        same = all(
            os.path.exists(f.replace("compare_before", "compare_after"))
            and digest(f) == digest(f.replace("compare_before", "compare_after")) for f in befores)
        print(f"run {r}: outputs identical: {same} ({len(befores)} files)", flush=True)
    for k in exes:
        walls, solves, cpus = times[k]["wall"], times[k]["solve"], times[k]["cpu"]
        line = f"{k}: wall median {statistics.median(walls):.3f} s ({' '.join(f'{w:.3f}' for w in walls)})"
        line += f", CPU median {statistics.median(cpus):.3f} s ({' '.join(f'{c:.3f}' for c in cpus)})"
        if solves:
            line += f", solve median {statistics.median(solves):.3f} s"
        print(line)
    with open("/proc/loadavg") as f:
        print("load average", " ".join(f.read().split()[:3]))


if __name__ == "__main__":
    main()
