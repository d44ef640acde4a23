#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Speed against error per surface mode (`scene build --surface`, format/surface_mode.h): for
each scene, voxel resolution and mode, `voxlink scene build` (B/voxel, MB, build time and peak
memory, the normal error it reports), `voxlink render-exact --compare` (the voxel scene and the
original meshes through the same float64 effects tracer: PSNR of the whole image, of the edge
mask, and the share of pixels whose first hit differs) and, unless --no-gl, `voxlink
bench-render` (GL frames per second at 512x512 and 1000x1000 over two turns of --frames-per-turn
frames, plain shading unless --gl-effects, on this machine's GL: llvmpipe without a GPU).

usage: surface_modes.py VOXLINK DATA_DIR [--scenes all|dragon,bunny,cornell-spheres,...]
                        [--resolutions 256,512,1024] [--modes mean,planes,triangles]
                        [--csv rows.csv [--resume]] [--markdown tables.md] [--no-gl]
                        [--size 512x512] [--build-repeats 3] [--frames-per-turn 12]

Scenes are the meshes of DATA_DIR alone (MESHES below: default camera, one light, images with
shadow rays) and the sample scenes of --samples (their own camera, lights and materials, the
grid's resolution replaced; images with every effect on; a scene with a CT volume keeps the
volume's grid and is measured once, at the first of --resolutions). `all` is every one of
both. Each measured row is appended to --csv as soon as it is done; with --resume the rows already there
are kept and skipped, so an interrupted run goes on where it stopped (else the CSV starts
anew); the Markdown tables (surface_tables.py) are written from the CSV at the end
(--tables-only: only that). A command that fails or runs past --timeout seconds is recorded
with its reason.
Work files go to $VOXLINK_BENCH_DIR (default /tmp/voxlink-bench)/surface-modes.
"""
import argparse
import csv
import glob
import json
import os
import re
import statistics
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from scene_paths import absolute_paths  # noqa: E402
from surface_tables import FIELDS, write_tables  # noqa: E402

MESHES = {"dragon": "mesh/stanford_dragon_decimated.ply", "bunny": "mesh/c3dtm_stanford-bunny.obj",
          "horse": "mesh/vtk_horse.ply", "fandisk": "mesh/c3dtm_fandisk.obj",
          "teapot": "mesh/c3dtm_teapot.obj"}


def parse_args():
    here = os.path.dirname(os.path.abspath(__file__))
    p = argparse.ArgumentParser()
    p.add_argument("voxlink")
    p.add_argument("data")
    p.add_argument("--samples", default=os.path.join(here, "..", "samples", "scenes"))
    p.add_argument("--scenes", default="dragon")
    p.add_argument("--resolutions", default="256,512")
    p.add_argument("--modes", default="mean,planes,triangles")
    p.add_argument("--size", default="512x512")
    p.add_argument("--build-repeats", type=int, default=3)
    p.add_argument("--fragment-angle", default=None)
    p.add_argument("--timeout", type=float, default=600, help="seconds per command")
    p.add_argument("--csv", default=None, help="rows, appended per row (default: work folder)")
    p.add_argument("--markdown", default=None, help="write the tables here (default: stdout)")
    p.add_argument("--frames-per-turn", default="12", help="bench-render's, two turns")
    p.add_argument("--resume", action="store_true", help="keep --csv's rows, measure the rest")
    p.add_argument("--tables-only", action="store_true",
                   help="write the tables of --csv, measure nothing")
    p.add_argument("--gl-effects", action="store_true",
                   help="GL fps with the image's effects (default: plain shading)")
    p.add_argument("--no-gl", action="store_true")
    return p.parse_args()


def run(cmd, timeout):
    """(ok, stdout + stderr, wall seconds, peak RSS MiB); ok is False with the reason's first
    line in the text when the command fails or times out."""
    start = time.monotonic()
    try:
        p = subprocess.run(["/usr/bin/time", "-f", "RSS %M"] + cmd, capture_output=True,
                           text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return False, f"killed after {timeout:.0f} s", time.monotonic() - start, 0.0
    seconds = time.monotonic() - start
    rss = re.findall(r"RSS (\d+)", p.stderr)
    rss_mib = int(rss[-1]) / 1024.0 if rss else 0.0
    text = p.stdout + re.sub(r"RSS \d+\n?", "", p.stderr)
    if p.returncode != 0:
        lines = [ln for ln in text.splitlines() if ln.strip() and "Command exited" not in ln]
        return False, (lines[-1] if lines else f"exit {p.returncode}"), seconds, rss_mib
    return True, text, seconds, rss_mib


def scene_files(args, work):
    """name -> (scene dict, effects) for every scene named by --scenes."""
    samples = {os.path.basename(f)[:-len(".scene.json")]: f
               for f in sorted(glob.glob(os.path.join(args.samples, "*.scene.json")))}
    # A sample scene may share a mesh's name (dragon): "sample:NAME" names the sample.
    names = (list(MESHES) + ["sample:" + n for n in samples] if args.scenes == "all"
             else args.scenes.split(","))
    out = {}
    for name in names:
        if name in MESHES:
            out[name] = ({"objects": [{"type": "mesh",
                                       "file": os.path.join(os.path.abspath(args.data),
                                                            MESHES[name])}],
                          "lights": [{"position": [3, 4, 5]}],
                          "camera": {"azimuth": 30, "elevation": 20, "up": "y"}}, "shadows")
        elif name.removeprefix("sample:") in samples:
            name = name.removeprefix("sample:")
            with open(samples[name]) as f:
                folder = os.path.dirname(os.path.abspath(samples[name]))
                scene = absolute_paths(json.load(f), folder)
            out["sample " + name] = (scene, "all")
            if any(o.get("type") == "volume" for o in scene.get("objects", [])):
                out["sample " + name] = (scene, "all", "volume")
        else:
            sys.exit(f"unknown scene {name}: not in {sorted(MESHES)} nor {args.samples}")
    return out


def measure(args, work, name, scene, effects, res, mode, commands):
    """One row (a dict of FIELDS)."""
    row = {k: "" for k in FIELDS}
    row.update(scene=name, resolution=res, mode=mode, effects=effects)
    scene = json.loads(json.dumps(scene))
    scene.setdefault("grid", {})["resolution"] = res
    stem = f"{work}/{name.replace(' ', '-')}-{res}"
    scene_path = f"{stem}.scene.json"
    with open(scene_path, "w") as f:
        json.dump(scene, f)
    vxl = f"{stem}-{mode}.vxl"
    build = [args.voxlink, "scene", "build", scene_path, "-o", vxl, "--surface", mode]
    if args.fragment_angle and mode == "planes":
        build += ["--fragment-angle", args.fragment_angle]
    commands.append(" ".join(build))
    runs = []
    for _ in range(args.build_repeats):
        ok, out, seconds, rss = run(build, args.timeout)
        if not ok:
            row["note"] = f"scene build: {out}"
            return row
        runs.append((out, seconds, rss))
    out = runs[-1][0]
    row["voxels"] = int(re.search(r", (\d+) voxels \(", out).group(1))
    row["surface_voxels"] = int(re.search(r"\((\d+) surface from", out).group(1))
    row["normal_p95"] = re.search(r"p95 ([\d.]+)", out).group(1)
    per_voxel = re.search(r"\(([\d.]+) per surface voxel", out)
    row["fragments_per_surface_voxel"] = per_voxel.group(1) if per_voxel else "1"
    row["bytes"] = os.path.getsize(vxl)
    row["build_s"] = f"{statistics.median(s for _, s, _ in runs):.2f}"
    row["build_rss_mib"] = f"{max(r for _, _, r in runs):.0f}"
    cmp = [args.voxlink, "render-exact", scene_path, "-o", f"{work}/exact.png", "--compare", vxl,
           "--size", args.size, "--effects", effects]
    commands.append(" ".join(cmp))
    ok, text, _, _ = run(cmp, args.timeout)
    m = re.search(r"PSNR ([\d.inf]+) dB; first hit differs ([\d.]+) %.*?PSNR ([\d.inf-]+)"
                  r" dB there", text) if ok else None
    if m:
        row.update(psnr=m.group(1), edge_psnr=m.group(3), first_hit_pct=m.group(2))
    else:
        row["note"] = f"render-exact: {text.strip().splitlines()[-1] if text.strip() else '?'}"
    if not args.no_gl:
        bench = [args.voxlink, "bench-render", vxl, "--sizes", "512x512", "1000x1000",
                 "--no-dense", "--no-reference", "--frames-per-turn", args.frames_per_turn]
        if args.gl_effects:
            bench += ["--effects", effects]
        commands.append(" ".join(bench))
        ok, text, _, _ = run(bench, args.timeout)
        found = re.findall(r"\| (\d+)x(\d+) \| \d+ \| [\d.]+ \| [\d.]+ \| [\d.]+ \| ([\d.]+) \|",
                           text) if ok else []
        if len(found) >= 2:
            row["fps_512"], row["fps_1000"] = found[0][2], found[1][2]
        else:
            row["note"] = (row["note"] + "; " if row["note"] else "") + f"bench-render: {text}"
    return row


def main():
    args = parse_args()
    work = os.environ.get("VOXLINK_BENCH_DIR", "/tmp/voxlink-bench") + "/surface-modes"
    os.makedirs(work, exist_ok=True)
    csv_path = args.csv or f"{work}/surface-modes.csv"
    done = set()
    if (args.resume or args.tables_only) and os.path.exists(csv_path):
        with open(csv_path) as f:
            done = {(r["scene"], r["resolution"].split()[0], r["mode"])
                    for r in csv.DictReader(f)}
    else:
        with open(csv_path, "w", newline="") as f:
            csv.DictWriter(f, FIELDS).writeheader()
    commands = []
    if args.tables_only:
        scenes, args.resolutions = {}, ""
    else:
        scenes = scene_files(args, work)
    # Resolution outermost: an interrupted run has every scene at the lower resolutions.
    resolutions = [int(r) for r in args.resolutions.split(",") if r]
    for res in resolutions:
        for name, (scene, effects, *volume) in scenes.items():
            # A scene with a volume takes the volume's grid (docs/scene.md: grid.resolution is
            # ignored): one row per mode, at the first resolution.
            if volume and res != resolutions[0]:
                continue
            for mode in args.modes.split(","):
                if (name, str(res), mode) in done:
                    continue
                row = measure(args, work, name, scene, effects, res, mode, commands)
                if volume:
                    row["resolution"] = f"{res} (ignored: the volume's grid)"
                with open(csv_path, "a", newline="") as f:
                    csv.DictWriter(f, FIELDS).writerow(row)
                print(f"{name} {res} {mode}: {row['note'] or 'done'}", file=sys.stderr, flush=True)
    with open(csv_path) as f:
        rows = list(csv.DictReader(f))
    text = write_tables(rows, args.modes.split(","))
    if commands:
        text += "\nCommands of the rows measured in this run:\n\n" + "".join(
            "    " + c + "\n" for c in commands)
    if args.markdown:
        with open(args.markdown, "w") as f:
            f.write(text)
    else:
        print(text)


if __name__ == "__main__":
    main()
