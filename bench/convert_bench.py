#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Conversion benchmark: speed, memory, footprint and error of `voxlink convert`, against the
same job done with OpenVDB (copyFromDense + Blosc write), run in this script on this machine.

usage: convert_bench.py VOXLINK UPSAMPLE VDB_PEER DATA_DIR [--quick] [--grf N] [--cases A,B]
                        [--json FILE]

--grf N runs the random-field cases (value types and error bounds) on an N^3 field, also with
--quick (default 512, left out by --quick); --cases keeps only the named cases; --json writes
the rows for bench/report.py.

Prints a Markdown table (paste into docs/benchmarks.md) and the commands that made each row.
Work files go to $VOXLINK_BENCH_DIR (default /tmp/voxlink-bench): the 1024^3 input is 1 GiB.
"""
import json
import os
import re
import statistics
import subprocess
import sys

from bench_timing import fresh, run, warm

voxlink, upsample, vdb_peer, data = sys.argv[1:5]
quick = "--quick" in sys.argv


def option(name, default=None):
    return sys.argv[sys.argv.index(name) + 1] if name in sys.argv else default


grf_dims = int(option("--grf", "0" if quick else "512"))
only = option("--cases")
only = set(only.split(",")) if only else None
work = os.environ.get("VOXLINK_BENCH_DIR", "/tmp/voxlink-bench")
os.makedirs(work, exist_ok=True)
REPEATS = 1 if quick else 3


def info(vxl):
    out = subprocess.run([voxlink, "info", "--json", vxl], capture_output=True, text=True, check=True).stdout
    return json.loads(out)


def meta_errors(convert_stdout):
    m = re.search(r"error mean ([\d.]+) max ([\d.]+) deg", convert_stdout)
    return (float(m.group(1)), float(m.group(2))) if m else (float("nan"), float("nan"))


rows = []
commands = []


def bench_convert(name, source, open_args, keep_args, peer=None):
    if only is not None and name not in only:
        return
    if os.path.isfile(source):
        warm(source)
    out_vxl = os.path.join(work, name + ".vxl")
    # Not -q: the gradient errors come from the summary line.
    cmd = [voxlink, "convert", source, *open_args, *keep_args, "-o", out_vxl]
    times, rss, stdout = [], 0.0, ""
    for _ in range(REPEATS):
        fresh(out_vxl)
        stdout, t, r = run(cmd)
        times.append(t)
        rss = max(rss, r)
    commands.append(" ".join(cmd))
    rep = info(out_vxl)
    mean, worst = meta_errors(stdout)
    row = {
        "name": name,
        "dims": "x".join(str(d) for d in rep["dims"]) + f" [{rep['brick_size']}]",
        "type": rep["source_type"],
        "keep": " ".join(keep_args),
        "occ": 100 * rep["occupancy"],
        "bricks": 100 * rep["bricks_nonempty_fraction"],
        "sec": statistics.median(times),
        "sec_min": min(times),
        "rss": rss,
        "mb": rep["bytes_total"] / 1e6,
        "bpv": rep["bytes_per_voxel"],
        "dense": 1 / rep["ratio_vs_dense"],
        "vdb_bpv": rep["peer"]["bytes_per_voxel"],
        "stored": rep["value_type"],
        "verr": rep["value_error"]["max_abs"],
        "gmean": mean,
        "gmax": worst,
        "peer_sec": None,
    }
    if peer:
        peer_out = os.path.join(work, name + ".vdb")
        peer_cmd = [vdb_peer, source, *peer, peer_out]
        warm(source)
        fresh(peer_out)
        out, t, r = run(peer_cmd)
        commands.append(" ".join(peer_cmd))
        row["peer_sec"] = t
        row["peer_rss"] = r
        row["peer_line"] = out.strip()
    rows.append(row)


# The 1024^3 case: the lossy foot preview upsampled 4x per axis by trilinear interpolation.
foot = os.path.join(data, "ct/openscivis_lossy/foot_256x256x256_uint8_lossy.nrrd")
foot1024 = os.path.join(work, "foot1024.raw")
if not os.path.exists(foot1024):
    subprocess.run([upsample, foot, "4", foot1024], check=True)
raw1024 = ["--dims", "1024,1024,1024", "--type", "u8"]
if not quick and (only is None or "foot1024" in only):
    bench_convert("foot1024", foot1024, raw1024, ["--threshold", "60"], ["1024", "1024", "1024", "60"])
foot256 = os.path.join(work, "foot256.raw")
if not os.path.exists(foot256):
    subprocess.run([upsample, foot, "1", foot256], check=True)
bench_convert("foot256", foot256, ["--dims", "256,256,256", "--type", "u8"], ["--threshold", "60"],
              ["256", "256", "256", "60"])

# Every real CT file, with a threshold that removes air and background, chosen from
# `voxlink stats FILE` (the histogram's background peak ends below it).
CASES = [
    ("headsq", "ct/vtk_headsq/quarter.nhdr", [], ["--threshold", "500"]),
    ("headsq-dicom", "ct/slicer_CTHeadAxialDicom", [], ["--threshold", "500"]),
    ("tooth", "ct/tooth_103x94x161_uint8.raw", ["--dims", "103,94,161", "--type", "u8"], ["--threshold", "100"]),
    ("walnut", "ct/voreen_walnut/walnut.vvd", [], ["--threshold", "5600"]),
    ("LIDC2", "ct/vtkjs_LIDC2/LIDC2.nhdr", [], ["--threshold", "100"]),
    ("engine", "ct/openscivis_lossy/engine_256x256x128_uint8_lossy.nrrd", [], ["--threshold", "100"]),
    ("carp", "ct/openscivis_lossy/carp_128x128x256_uint16_lossy.nrrd", [], ["--threshold", "1250"]),
    ("stag_beetle", "ct/openscivis_lossy/stag_beetle_416x208x124_uint16_lossy.nrrd", [], ["--threshold", "400"]),
]
for name, rel, open_args, keep in CASES:
    path = os.path.join(data, rel)
    if os.path.exists(path):
        bench_convert(name, path, open_args, keep)
    else:
        print(f"(skipped {name}: {path} missing)", file=sys.stderr)

# The paper's geostatistics case (section 6.2): a 512^3 N(0,1) field in double precision, of
# which only the values outside the 95 % interval are kept; stored as f32 (default) and at two
# error bounds that let the converter pick u16 and u8.
if grf_dims:
    g = f"grf{grf_dims}"
    grf = os.path.join(work, g + ".nhdr")
    if not os.path.exists(grf):
        subprocess.run([voxlink, "grf", "--dims", ",".join([str(grf_dims)] * 3), "--variogram",
                        "exp:range=32", "--seed", "7", "-o", grf], check=True,
                       stdout=subprocess.DEVNULL)
    keep = ["--keep-outside", "-1.96,1.96"]
    bench_convert(g, grf, [], keep)
    bench_convert(g + "-f16", grf, [], keep + ["--value-type", "f16"])
    bench_convert(g + "-e1e-3", grf, [], keep + ["--error-bound", "1e-3"])
    bench_convert(g + "-e0.02", grf, [], keep + ["--error-bound", "0.02"])
    bench_convert(g + "-b16", grf, [], keep + ["--error-bound", "1e-3", "--brick", "16"])

cpu = subprocess.run(["sh", "-c", "grep -m1 'model name' /proc/cpuinfo | cut -d: -f2; nproc"],
                     capture_output=True, text=True).stdout.split("\n")
print(f"\nmachine: {cpu[0].strip()}, {cpu[1].strip()} cores; median of {REPEATS} runs from page cache\n")
print("| case | resolution [brick] | source | keep | non-empty voxels % | non-empty bricks % | convert s (min) | "
      "peak RSS MiB | total MB | B/voxel | vs dense | OpenVDB FloatGrid B/voxel | stored, max abs value error | "
      "gradient error mean/max deg | OpenVDB job s | speed-up |")
print("|" + "---|" * 16)
for r in rows:
    peer = f"{r['peer_sec']:.2f}" if r["peer_sec"] else "-"
    speed = f"{r['peer_sec'] / r['sec']:.1f}x" if r["peer_sec"] else "-"
    print(f"| {r['name']} | {r['dims']} | {r['type']} | {r['keep']} | {r['occ']:.2f} | {r['bricks']:.1f} | "
          f"{r['sec']:.2f} ({r['sec_min']:.2f}) | {r['rss']:.0f} | {r['mb']:.2f} | {r['bpv']:.3f} | {r['dense']:.1f}x smaller | "
          f"{r['vdb_bpv']:.3f} | {r['stored']}, {r['verr']:.3g} | {r['gmean']:.3f} / {r['gmax']:.3f} | {peer} | {speed} |")
for r in rows:
    if r.get("peer_line"):
        print(f"\nOpenVDB peer, {r['name']} (peak RSS {r['peer_rss']:.0f} MiB): {r['peer_line']}")
if option("--json"):
    with open(option("--json"), "w") as f:
        json.dump({"repeats": REPEATS, "rows": rows, "commands": commands}, f, indent=1)
print("\ncommands:")
for c in commands:
    print("    " + c)
