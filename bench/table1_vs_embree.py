#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""The paper's Table 1 columns on this machine beside the exact tracer: for each scene at 256
voxels (bricks of 8), 512 (8) and 1024 (16), `voxlink scene build`, then `voxlink bench-render`
(the GL ray tracer on this machine's GL, the paper's rotation protocol, plain or --effects all)
and `voxlink render-exact` (Embree 3 + the float64 effects tracer, CPU) for the same image size,
effects and the scene's own camera.

usage: table1_vs_embree.py VOXLINK SCENES_DIR DATA_DIR [--frames-per-turn N] [--quick]

Prints a Markdown table (docs/exact-tracer.md) and the commands. GL fps is bench-render's mean
over the rotation; the exact tracer's fps is 1 / the median of 3 renders of the scene's camera
view (one view, not the rotation: its time per frame hardly depends on the view here).
Work files go to $VOXLINK_BENCH_DIR (default /tmp/voxlink-bench)/table1.
"""
import json
import os
import re
import subprocess
import sys

from scene_paths import absolute_paths

voxlink, scenes_dir, data = sys.argv[1:4]
scenes_dir, data = os.path.abspath(scenes_dir), os.path.abspath(data)
quick = "--quick" in sys.argv
frames = sys.argv[sys.argv.index("--frames-per-turn") + 1] if "--frames-per-turn" in sys.argv \
    else "8"
work = os.environ.get("VOXLINK_BENCH_DIR", "/tmp/voxlink-bench") + "/table1"
os.makedirs(work, exist_ok=True)
GRIDS = [(256, 8), (512, 8)] if quick else [(256, 8), (512, 8), (1024, 16)]
SIZES = ["512x512", "1000x1000"]


def run(cmd):
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"failed: {' '.join(cmd)}\n{p.stdout}{p.stderr}")
    return p.stdout


def scenes():
    """(name, effects, scene) from samples/scenes: the dragon plain and ray traced, the paper's
    bunny scene (a glass bunny beside a mirror sphere on a mirror floor), the house with glass
    windows, and the Cornell box with a mirror and a glass sphere."""
    for name, effects in [("dragon", "none"), ("dragon", "all"), ("bunny-glass", "all"),
                          ("house", "all"), ("cornell-spheres", "all")]:
        path = os.path.join(scenes_dir, name + ".scene.json")
        with open(path) as f:
            yield name, effects, absolute_paths(json.load(f), scenes_dir)


rows, commands = [], []
for name, effects, scene in scenes():
    for res, brick in GRIDS:
        scene["grid"] = {"resolution": res, "brick": brick}
        scene_path = f"{work}/{name}-{res}.scene.json"
        with open(scene_path, "w") as f:
            json.dump(scene, f)
        vxl = f"{work}/{name}-{res}.vxl"
        build = [voxlink, "scene", "build", scene_path, "-o", vxl]
        run(build)
        bench = [voxlink, "bench-render", vxl, "--sizes", *SIZES, "--samplings", "voxel",
                 "--no-dense", "--no-reference", "--frames-per-turn", frames, "--effects",
                 effects]
        out = run(bench)
        header = re.search(r"(\d+) voxels = ([\d.]+) % of \d+, (\d+) of (\d+) bricks", out)
        mb = os.path.getsize(vxl) / 1e6
        fps = {}
        lines = [l for l in out.splitlines() if l.startswith("|")]
        column = [c.strip() for c in lines[0].strip("|").split("|")].index("FPS")
        for size in SIZES:
            line = next(l for l in lines if f"| {size} |" in l)
            fps[size] = [c.strip() for c in line.strip("|").split("|")][column]
        exact = {}
        for size in SIZES:
            cmd = [voxlink, "render-exact", scene_path, "-o", f"{work}/exact.png", "--size", size,
                   "--effects", effects, "--repeat", "3"]
            t = float(re.search(r"\): ([\d.]+) s\n", run(cmd)).group(1))
            exact[size] = 1.0 / t
            commands.append(" ".join(cmd))
        commands += [" ".join(build), " ".join(bench)]
        occupied = 100.0 * int(header.group(3)) / int(header.group(4))
        rows.append((name, effects, f"{res}[{brick}]", int(header.group(1)), occupied, mb, fps,
                     exact))
        print(f"{name} {effects} {res}: done\n{out}", file=sys.stderr, flush=True)

print("| scene | effects | grid[brick] | voxels | non-empty bricks % | MB | GL fps 512 / 1000 "
      "| exact fps 512 / 1000 |")
print("|---|---|---|---|---|---|---|---|")
for name, effects, grid, voxels, occupied, mb, fps, exact in rows:
    print(f"| {name} | {effects} | {grid} | {voxels:,} | {occupied:.1f} | {mb:.1f} | "
          f"{fps['512x512']} / {fps['1000x1000']} | {exact['512x512']:.1f} / "
          f"{exact['1000x1000']:.1f} |")
print("\nCommands:")
for c in commands:
    print("    " + c)
