#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""What voxelization costs: for each scene and voxel resolution, `voxlink scene build` (file size,
build time), then `voxlink render-exact --compare` renders the voxel scene and the original
meshes and spheres (Embree 3, the exact tracer a user would pick instead) with the same float64
effects tracer, camera and lights, plain and with every effect, and prints PSNR, the share of
pixels whose first hit differs, PSNR on the edge mask, and both tracers' times.

usage: voxelization_cost.py VOXLINK SCENES_DIR DATA_DIR [--quick] [--scenes A,B]
                            [--resolutions 64,128] [--size WxH] [--surface MODE] [--json FILE]

--surface MODE passes `--surface MODE` to `scene build` (bench/report.py loops over the modes
`scene build --help` lists); --json writes the rows for bench/report.py.

Prints a Markdown table (docs/exact-tracer.md) and the commands that made each row. Times are
medians of 3 renders (--repeat) and of 3 build runs (the VM's speed drifts).
Work files go to $VOXLINK_BENCH_DIR (default /tmp/voxlink-bench/voxelization-cost).
"""
import json
import os
import re
import statistics
import sys

from bench_timing import run_wall
from scene_paths import absolute_paths

voxlink, scenes_dir, data = sys.argv[1:4]
data = os.path.abspath(data)  # the scene files are written elsewhere
quick = "--quick" in sys.argv


def option(name, default):
    return sys.argv[sys.argv.index(name) + 1] if name in sys.argv else default


surface = option("--surface", None)
work = os.environ.get("VOXLINK_BENCH_DIR", "/tmp/voxlink-bench") + "/voxelization-cost"
if surface:
    work += "/" + surface
os.makedirs(work, exist_ok=True)
RESOLUTIONS = [int(r) for r in option("--resolutions", "256,512" if quick else
                                      "256,512,1024").split(",")]
ONLY = option("--scenes", None)
BUILD_REPEATS = 1 if quick else 3
RENDER_REPEATS = "1" if quick else "3"
SIZE = option("--size", "256x256")


run = run_wall  # (stdout, seconds)


def scenes():
    """(name, scene dict with absolute paths): the samples, and the bunny and the dragon alone."""
    for name in ["cornell-spheres", "bunny-molecule"]:
        if ONLY and name not in ONLY.split(","):
            continue
        path = os.path.join(scenes_dir, name + ".scene.json")
        with open(path) as f:
            yield name, absolute_paths(json.load(f), os.path.dirname(os.path.abspath(path)))
    for name, mesh in [("bunny", "mesh/c3dtm_stanford-bunny.obj"),
                       ("dragon", "mesh/stanford_dragon_decimated.ply")]:
        if ONLY and name not in ONLY.split(","):
            continue
        yield name, {"objects": [{"type": "mesh", "file": os.path.join(data, mesh)}],
                     "camera": {"azimuth": 30, "elevation": 20, "up": "y"}}


def compare(scene_path, vxl, effects):
    cmd = [voxlink, "render-exact", scene_path, "-o", f"{work}/exact.png", "--compare", vxl,
           "--size", SIZE, "--effects", effects, "--repeat", RENDER_REPEATS]
    out, _ = run(cmd)
    exact = float(re.search(r"\): ([\d.]+) s\n", out).group(1))
    voxel = float(re.search(r"float64 tracer ([\d.]+) s", out).group(1))
    m = re.search(r"PSNR ([\d.inf]+) dB; first hit differs ([\d.]+) %.*?PSNR ([\d.inf-]+) dB there",
                  out)
    return {"exact": exact, "voxel": voxel, "psnr": m.group(1), "mismatch": m.group(2),
            "edge_psnr": m.group(3), "cmd": " ".join(cmd)}


rows, commands = [], []
for name, scene in scenes():
    for res in RESOLUTIONS:
        scene.setdefault("grid", {})["resolution"] = res
        scene_path = f"{work}/{name}-{res}.scene.json"
        with open(scene_path, "w") as f:
            json.dump(scene, f)
        vxl = f"{work}/{name}-{res}.vxl"
        build = [voxlink, "scene", "build", scene_path, "-o", vxl] + \
            (["--surface", surface] if surface else [])
        times = [run(build)[1] for _ in range(BUILD_REPEATS)]
        commands.append(" ".join(build))
        size_mb = os.path.getsize(vxl) / 1e6
        plain = compare(scene_path, vxl, "none")
        effects = compare(scene_path, vxl, "all")
        commands += [plain["cmd"], effects["cmd"]]
        info = json.loads(run([voxlink, "info", "--json", "--no-vdb", vxl])[0])
        rows.append((name, res, size_mb, statistics.median(times), plain, effects,
                     info["bytes_per_voxel"]))
        print(f"{name} {res}: done", file=sys.stderr, flush=True)

print(f"| scene | voxels | file MB | build s | plain: PSNR dB / first hit differs % / edge PSNR dB"
      f" | plain: voxel s / exact s | all effects: PSNR dB / first hit differs % / edge PSNR dB"
      f" | all effects: voxel s / exact s | exact faster, plain / all |")
print("|---|---|---|---|---|---|---|---|---|")
for name, res, size, build, p, e, _ in rows:
    print(f"| {name} | {res} | {size:.1f} | {build:.2f} | {p['psnr']} / {p['mismatch']} / "
          f"{p['edge_psnr']} | {p['voxel']:.2f} / {p['exact']:.2f} | {e['psnr']} / "
          f"{e['mismatch']} / {e['edge_psnr']} | {e['voxel']:.2f} / {e['exact']:.2f} | "
          f"{p['voxel'] / p['exact']:.1f}x / {e['voxel'] / e['exact']:.1f}x |")
if option("--json", None):
    with open(option("--json", None), "w") as f:
        json.dump({"surface": surface, "size": SIZE, "rows": [
            {"scene": r[0], "resolution": r[1], "mb": r[2], "build_s": r[3], "plain": r[4],
             "effects": r[5], "bytes_per_voxel": r[6]} for r in rows],
            "commands": commands}, f, indent=1)
print("\nCommands:")
for c in commands:
    print("    " + c)
