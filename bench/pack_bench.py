#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Packed files for sharing: size, packing speed and load time of `voxlink pack`, beside the
OpenVDB file of the same voxels (Blosc, what a user would share instead) and plain zstd of the
.vxl file (what a user would otherwise run), all made in this script on this machine.

usage: pack_bench.py VOXLINK UPSAMPLE VDB_PEER DATA_DIR [--cases foot256,foot1024] [--repeats N]
                     [--json FILE]

Prints a Markdown table (docs/benchmarks.md, "Packed files") and the commands behind it. Work
files go to $VOXLINK_BENCH_DIR (default /tmp/voxlink-bench), shared with convert_bench.py.
"""
import json
import os
import re
import statistics
import subprocess
import sys

from bench_timing import fresh, run, warm

voxlink, upsample, vdb_peer, data = sys.argv[1:5]
work = os.environ.get("VOXLINK_BENCH_DIR", "/tmp/voxlink-bench")
os.makedirs(work, exist_ok=True)


def option(name, default):
    return sys.argv[sys.argv.index(name) + 1] if name in sys.argv else default


REPEATS = int(option("--repeats", "3"))
CASES = option("--cases", "foot1024,foot256").split(",")
commands = []
results = []


def timed(make, output):
    """Median and minimum wall time of `make` (a command writing `output`) over REPEATS runs."""
    times = []
    for _ in range(REPEATS):
        fresh(output)
        times.append(run(make)[1])
    commands.append(" ".join(make))
    return statistics.median(times), min(times)


def load_seconds(cmd):
    times = [run(cmd)[1] for _ in range(REPEATS)]
    commands.append(" ".join(cmd))
    return statistics.median(times)


# pyopenvdb lives in the system Python (python3-openvdb).
VDB_LOAD = ("import sys, time, pyopenvdb\n"
            "t = time.perf_counter(); grids = pyopenvdb.readAll(sys.argv[1]); "
            "print(time.perf_counter() - t)")


def vdb_load_seconds(path):
    times = []
    for _ in range(REPEATS):
        out = subprocess.run(["/usr/bin/python3", "-c", VDB_LOAD, path], capture_output=True,
                             text=True, check=True).stdout
        times.append(float(out.strip()))
    commands.append(f"/usr/bin/python3 -c 'pyopenvdb.readAll({os.path.basename(path)})'")
    return statistics.median(times)


def case(name, raw, dims, threshold):
    vxl = os.path.join(work, name + ".vxl")
    vdb = os.path.join(work, name + ".vdb")
    warm(raw)
    subprocess.run([voxlink, "convert", raw, "--dims", ",".join(map(str, dims)), "--type", "u8",
                    "--threshold", str(threshold), "-o", vxl, "-q"], check=True,
                   capture_output=True)
    subprocess.run([vdb_peer, raw, *map(str, dims), str(threshold), vdb], check=True,
                   capture_output=True)
    info = subprocess.run([voxlink, "info", vxl, "--no-vdb", "--json"], capture_output=True,
                          text=True, check=True).stdout
    voxels = int(re.search(r'"voxels": (\d+)', info).group(1))
    vxl_bytes = os.path.getsize(vxl)
    dense_bytes = dims[0] * dims[1] * dims[2]
    warm(vxl)
    rows = []

    def row(label, path, make_seconds, load):
        size = os.path.getsize(path)
        rows.append((label, size, size / voxels, size / os.path.getsize(vdb), make_seconds,
                     load))

    row("`.vxl` (plain)", vxl, None, load_seconds([voxlink, "validate", vxl]))
    # Speed against size: the default, --fast, and higher zstd levels (what --level buys).
    for label, extra in (("`voxlink pack`", []), ("`voxlink pack --fast`", ["--fast"]),
                         ("`voxlink pack --level 3`", ["--level", "3"]),
                         ("`voxlink pack --level 9`", ["--level", "9"]),
                         ("`voxlink pack --level 19`", ["--level", "19"])):
        tag = "".join(e.lstrip("-") for e in extra)
        out = os.path.join(work, name + ("." + tag if tag else "") + ".packed.vxl")
        t = timed([voxlink, "pack", vxl, "-o", out, "-q", *extra], out)
        row(label, out, t, load_seconds([voxlink, "validate", out]))
    for level in ("1", "19"):
        zst = vxl + ".zst"
        t = timed(["zstd", "-" + level, "-T0", "-q", "-f", vxl, "-o", zst], zst)
        row(f"`zstd -{level} -T0` of the `.vxl`", zst, t,
            load_seconds(["zstd", "-d", "-q", "-f", "-T0", zst, "-o", "/dev/null"]))
    row("OpenVDB FloatGrid, Blosc (no gradients)", vdb, None, vdb_load_seconds(vdb))

    print(f"\n{name}: {voxels:,} stored voxels, plain .vxl {vxl_bytes / 1e6:.2f} MB, "
          f"dense source {dense_bytes / 1e6:.0f} MB")
    print("| file | MB | B/voxel | vs OpenVDB file | make s median (min) | MB/s of .vxl | "
          "MB/s of dense source | load s |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for label, size, bpv, vs, make, load in rows:
        if make:
            med, mn = make
            speed = f"{med:.2f} ({mn:.2f}) | {vxl_bytes / 1e6 / med:.0f} | " \
                    f"{dense_bytes / 1e6 / med:.0f}"
        else:
            speed = "- | - | -"
        print(f"| {label} | {size / 1e6:.2f} | {bpv:.3f} | {vs:.2f} | {speed} | {load:.2f} |")
        results.append({"case": name, "file": label, "bytes": size, "bytes_per_voxel": bpv,
                        "make_s": make[0] if make else None, "load_s": load})


foot = os.path.join(data, "ct/openscivis_lossy/foot_256x256x256_uint8_lossy.nrrd")
foot1024 = os.path.join(work, "foot1024.raw")
if "foot1024" in CASES and not os.path.exists(foot1024):
    subprocess.run([upsample, foot, "4", foot1024], check=True)
foot256 = os.path.join(work, "foot256.raw")
if not os.path.exists(foot256):
    subprocess.run([upsample, foot, "1", foot256], check=True)
print(f"CPU: {os.cpu_count()} cores; median of {REPEATS} runs, inputs in the page cache. "
      "Load: `voxlink validate` (read, unpack, validate every section; whole process), "
      "`zstd -d` to /dev/null, pyopenvdb.readAll (in-process, without Python's start).")
if "foot1024" in CASES:
    case("foot1024", foot1024, (1024, 1024, 1024), 60)
if "foot256" in CASES:
    case("foot256", foot256, (256, 256, 256), 60)
if option("--json", None):
    with open(option("--json", None), "w") as f:
        json.dump({"repeats": REPEATS, "rows": results, "commands": commands}, f, indent=1)
print("\nCommands:")
for c in dict.fromkeys(commands):
    print("   ", c)
