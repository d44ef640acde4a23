#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Speed against error per surface mode (`scene build --surface`, format/surface_mode.h): for
each scene, voxel resolution and mode, `voxlink scene build` (B/voxel, MB, build time, the normal
error it reports), `voxlink render-exact --compare` (the voxel scene and the original meshes
through the same float64 effects tracer: PSNR of the whole image, of the edge mask, and the share
of pixels whose first hit differs) and, unless --no-gl, `voxlink bench-render` (GL frames per
second at 512x512 and 1000x1000 over two turns of 12 frames, on this machine's GL: llvmpipe
without a GPU). Errors are of `--size` images (default 512x512) with shadow rays.

usage: surface_modes.py VOXLINK DATA_DIR [--resolutions 256,512] [--scenes dragon,bunny]
                        [--no-gl] [--size 256x256]

Prints one Markdown table per mode, then the commands that made every row. Build times are the
median of --build-repeats runs (default 3). Work files go to $VOXLINK_BENCH_DIR
(default /tmp/voxlink-bench)/surface-modes.
"""
import argparse
import json
import os
import re
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_timing import run_wall  # noqa: E402

parser = argparse.ArgumentParser()
parser.add_argument("voxlink")
parser.add_argument("data")
parser.add_argument("--resolutions", default="256,512")
parser.add_argument("--scenes", default="dragon")
parser.add_argument("--modes", default="mean,planes,triangles")
parser.add_argument("--size", default="512x512")
parser.add_argument("--build-repeats", type=int, default=3)
parser.add_argument("--fragment-angle", default=None)
parser.add_argument("--no-gl", action="store_true")
args = parser.parse_args()
data = os.path.abspath(args.data)
work = os.environ.get("VOXLINK_BENCH_DIR", "/tmp/voxlink-bench") + "/surface-modes"
os.makedirs(work, exist_ok=True)
MESHES = {"dragon": "mesh/stanford_dragon_decimated.ply", "bunny": "mesh/c3dtm_stanford-bunny.obj",
          "horse": "mesh/vtk_horse.ply", "fandisk": "mesh/c3dtm_fandisk.obj",
          "teapot": "mesh/c3dtm_teapot.obj"}


run = run_wall  # (stdout, seconds)



rows, commands = {m: [] for m in args.modes.split(",")}, []
for name in args.scenes.split(","):
    scene = {"objects": [{"type": "mesh", "file": os.path.join(data, MESHES[name])}],
             "lights": [{"position": [3, 4, 5]}],
             "camera": {"azimuth": 30, "elevation": 20, "up": "y"}}
    for res in [int(r) for r in args.resolutions.split(",")]:
        scene["grid"] = {"resolution": res}
        scene_path = f"{work}/{name}-{res}.scene.json"
        with open(scene_path, "w") as f:
            json.dump(scene, f)
        for mode in rows:
            vxl = f"{work}/{name}-{res}-{mode}.vxl"
            build = [args.voxlink, "scene", "build", scene_path, "-o", vxl, "--surface", mode]
            if args.fragment_angle and mode == "planes":
                build += ["--fragment-angle", args.fragment_angle]
            runs = [run(build) for _ in range(args.build_repeats)]
            out = runs[-1][0]
            commands.append(" ".join(build))
            voxels = int(re.search(r", (\d+) voxels \(", out).group(1))
            p95 = float(re.search(r"p95 ([\d.]+)", out).group(1))
            size = os.path.getsize(vxl)
            cmp = [args.voxlink, "render-exact", scene_path, "-o", f"{work}/exact.png", "--compare",
                   vxl, "--size", args.size, "--effects", "shadows"]
            text, _ = run(cmp)
            commands.append(" ".join(cmp))
            m = re.search(r"PSNR ([\d.inf]+) dB; first hit differs ([\d.]+) %.*?PSNR ([\d.inf-]+)"
                          r" dB there", text)
            fps = ["-", "-"]
            if not args.no_gl:
                bench = [args.voxlink, "bench-render", vxl, "--sizes", "512x512", "1000x1000",
                         "--no-dense", "--no-reference", "--frames-per-turn", "12"]
                text, _ = run(bench)
                commands.append(" ".join(bench))
                found = re.findall(r"\| (\d+)x(\d+) \| \d+ \| [\d.]+ \| [\d.]+ \| [\d.]+ \| ([\d.]+) \|",
                                   text)
                fps = [f for _, _, f in found[:2]] + ["-"] * (2 - len(found[:2]))
            rows[mode].append((name, res, voxels, size, statistics.median(s for _, s in runs), p95,
                               m.group(1), m.group(3), m.group(2), fps))
            print(f"{name} {res} {mode}: done", file=sys.stderr, flush=True)

for mode, table in rows.items():
    print(f"\n**{mode}**\n")
    print("| scene | resolution | voxels | B/voxel | MB | build s | normal p95 deg | PSNR dB |"
          " edge PSNR dB | first hit differs % | fps 512x512 | fps 1000x1000 |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for name, res, voxels, size, build, p95, psnr, edge, mismatch, fps in table:
        print(f"| {name} | {res} | {voxels} | {size / voxels:.2f} | {size / 1e6:.1f} | {build:.2f} |"
              f" {p95:.2f} | {psnr} | {edge} | {mismatch} | {fps[0]} | {fps[1]} |")
print("\nCommands:")
for c in commands:
    print("    " + c)
