# SPDX-License-Identifier: BSD-3-Clause
"""bench/trilinear_counters.py on the tooth CT at 64x64 (docs/rendering-trilinear-profile.md,
ninth session): its text anchors still match the shaders (the script stops otherwise), the
counts it reads back are consistent (every visible-cell pass is a pass and composites at least
one sample; a tile's slowest lane does at least the mean ray's work), and shaders without an
anchor stop it with a line naming the anchor.

usage: check_trilinear_counters.py WORK VOXLINK SHADER_DIR DATA_DIR
"""
import os
import shutil
import subprocess
import sys

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.join(here, "..", "..")
script = os.path.join(root, "bench", "trilinear_counters.py")
work, voxlink, shaders, data = sys.argv[1:5]
raw = os.path.join(data, "ct", "tooth_103x94x161_uint8.raw")
if not os.path.exists(raw):
    print(f"{raw}: no real data, skipped")
    sys.exit(77)
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
tf = os.path.join(root, "bench", "tf", "tooth.tf.json")
vxl = os.path.join(work, "tooth.vxl")


def check(condition, what):
    if not condition:
        sys.exit(f"FAILED: {what}")


def run(cmd):
    return subprocess.run(cmd, capture_output=True, text=True)


p = run([voxlink, "convert", raw, "--dims", "103", "94", "161", "--type", "u8", "--tf", tf,
         "-o", vxl, "-q"])
check(p.returncode == 0, f"convert: {p.stderr}")
p = run([sys.executable, script, voxlink, shaders, os.path.join(work, "counts"),
         f"{vxl}:{tf}", "--size", "64x64"])
check(p.returncode == 0, f"trilinear_counters.py: {p.stdout}{p.stderr}")
row = next((l for l in p.stdout.splitlines() if l.startswith("| tooth.vxl")), None)
check(row is not None, f"no tooth row in {p.stdout}")
cells = [c.strip() for c in row.strip("|").split("|")]
rays, passes, visible, other, samples, per_visible = (float(c) for c in cells[1:7])
tile_passes, tile_samples = (float(c) for c in cells[7].split(" / "))
print(row)
check(rays > 0, "no ray met the tooth")
check(visible > 0, "no visible-cell pass: the counts were not written")
check(visible <= passes and other >= 0, "more visible-cell passes than passes")
check(samples >= visible and per_visible >= 1.0, "a visible-cell pass composited no sample")
check(tile_passes >= passes and tile_samples >= samples, "a tile's slowest lane below the mean")

broken = os.path.join(work, "broken-shaders")
shutil.copytree(shaders, broken)
path = os.path.join(broken, "voxlink_trilinear.glsl")
with open(path) as f:
    text = f.read()
with open(path, "w") as f:
    f.write(text.replace("void traceTrilinear(", "void traceTrilinearRenamed("))
p = run([sys.executable, script, voxlink, broken, os.path.join(work, "broken"), f"{vxl}:{tf}",
         "--size", "16x16"])
check(p.returncode != 0 and "traceTrilinear" in p.stderr,
      f"shaders without an anchor were not refused by name: {p.stderr}")
print("ok")
