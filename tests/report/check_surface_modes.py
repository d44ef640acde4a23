# SPDX-License-Identifier: BSD-3-Clause
"""bench/surface_modes.py end to end on small grids (docs/surface-modes.md): a mesh alone and a
sample scene with a CT volume, every mode; the CSV rows, the exact tracer's refusal of the volume
scene recorded as the row's reason, --resume measuring nothing twice, and the goal marks.

usage: check_surface_modes.py WORK VOXLINK DATA_DIR
"""
import csv
import os
import subprocess
import sys

here = os.path.dirname(os.path.abspath(__file__))
bench = os.path.join(here, "..", "..", "bench")
sys.path.insert(0, bench)
from surface_tables import goals  # noqa: E402

work, voxlink, data = sys.argv[1:4]
if not os.path.isdir(os.path.join(data, "mesh")):
    print(f"{data}: no real data, skipped")
    sys.exit(77)
os.makedirs(work, exist_ok=True)
rows_csv, tables = os.path.join(work, "rows.csv"), os.path.join(work, "tables.md")
command = [sys.executable, os.path.join(bench, "surface_modes.py"), voxlink, data,
           "--scenes", "teapot,foot-bunny", "--resolutions", "24", "--build-repeats", "1",
           "--size", "32x32", "--no-gl", "--csv", rows_csv, "--markdown", tables]
env = dict(os.environ, VOXLINK_BENCH_DIR=work)


def check(condition, what):
    if not condition:
        sys.exit(f"FAILED: {what}")


first = subprocess.run(command, env=env, capture_output=True, text=True)
check(first.returncode == 0, f"the first run: {first.stdout}{first.stderr}")
with open(rows_csv) as f:
    rows = {(r["scene"], r["mode"]): r for r in csv.DictReader(f)}
check(len(rows) == 6, f"6 rows (2 scenes x 3 modes), got {sorted(rows)}")
for mode in ("mean", "planes", "triangles"):
    teapot, foot = rows[("teapot", mode)], rows[("sample foot-bunny", mode)]
    check(teapot["psnr"] and not teapot["note"], f"teapot {mode} measured: {teapot}")
    check(int(teapot["bytes"]) > 0 and int(teapot["voxels"]) > 0, f"teapot {mode} size")
    check(not foot["psnr"] and foot["note"].startswith("render-exact:") and "volume" in
          foot["note"], f"the volume scene's refusal is the row's reason: {foot['note']}")
    check(int(foot["bytes"]) > 0, f"foot-bunny {mode} was still built and sized")
check(rows[("teapot", "mean")]["fragments_per_surface_voxel"] == "1", "mean keeps one fragment")
check(float(rows[("teapot", "planes")]["fragments_per_surface_voxel"]) > 1,
      "planes keep more than one fragment per voxel somewhere on a teapot at 24 voxels")
check(float(rows[("teapot", "triangles")]["psnr"]) >= 50,
      f"triangles within 50 dB of the exact image: {rows[('teapot', 'triangles')]['psnr']}")
with open(tables) as f:
    text = f.read()
check(all(f"**{m}**" in text for m in ("mean", "planes", "triangles")), "a table per mode")

again = subprocess.run(command + ["--resume"], env=env, capture_output=True, text=True)
check(again.returncode == 0 and "done" not in again.stderr, f"--resume re-measured: {again.stderr}")
with open(rows_csv) as f:
    check(len(list(csv.DictReader(f))) == 6, "--resume kept the 6 rows and added none")

planes = {"mode": "planes", "psnr": "36.1", "edge_psnr": "24.9", "normal_p95": "1.50"}
check(goals(planes) == "not met: edges 24.9 < 25", f"goal marks: {goals(planes)}")
check(goals(dict(planes, edge_psnr="inf")) == "met", "an exact edge mask meets the goal")
check(goals({"mode": "triangles", "psnr": "49.9"}) == "not met: whole 49.9 < 50", "triangles")
check(goals({"mode": "mean", "psnr": "20"}) == "-", "mean has no goal")
print("surface_modes.py: 6 rows, refusal recorded, resume and goals as expected")
