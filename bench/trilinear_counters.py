#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Where a trilinear frame's passes go, per ray (docs/rendering-trilinear-profile.md, ninth
session): renders each file through a copy of shaders/ whose trilinear loop counts its passes,
its visible-cell passes and its composited samples, and writes the three counts into the
pixel in place of the colour; reads them back from the PNG and prints one table row per file.

llvmpipe runs 8 rays (a 4x2 tile) in one SIMD vector, so a tile costs what its slowest lane
does: the "tile" columns are the slowest lane's counts, and "tile passes" their sum over the
image, the number that follows the frame's time.

usage: trilinear_counters.py VOXLINK SHADER_DIR OUT_DIR FILE.vxl:TF.json... [--size WxH]
                             [--termination-alpha A]

Counts are clamped at 1020 and read back within 2 (8-bit PNG). The copy is made with exact
text anchors in voxlink_trilinear.glsl and render_main.glsl: if the shaders change under them,
the script stops naming the anchor.
"""
import argparse
import os
import shutil
import subprocess
import sys

import matplotlib.image
import numpy as np

SCALE = 1020.0  # counts per unit of colour: 4 counts per 8-bit step

PATCHES = {
    "voxlink_trilinear.glsl": [
        ("void traceTrilinear(",
         "uint gPasses = 0u, gVisible = 0u, gSamples = 0u;\nvoid traceTrilinear("),
        ("  for (int i = 0; i < limit; ++i) {\n",
         "  for (int i = 0; i < limit; ++i) {\n    ++gPasses;\n"),
        ("    for (;;) {\n      compositeSample(",
         "    ++gVisible;\n    for (;;) {\n      ++gSamples;\n      compositeSample("),
    ],
    "render_main.glsl": [
        ("  imageStore(uTarget, ivec2(pixel), vec4(color + transmittance * uBackground, "
         "1.0 - transmittance));\n",
         # The display pass encodes sRGB: the counts are decoded first so the PNG holds them
         # linearly.
         "  vec3 c = min(vec3(gPasses, gVisible, gSamples), vec3(%.1f)) / %.1f;\n"
         "  c = mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), "
         "greaterThan(c, vec3(0.04045)));\n"
         "  imageStore(uTarget, ivec2(pixel), vec4(c, 1.0));\n" % (SCALE, SCALE)),
    ],
}


def counting_copy(shaders, out):
    copy = os.path.join(out, "shaders")
    shutil.rmtree(copy, ignore_errors=True)
    shutil.copytree(shaders, copy)
    for name, patches in PATCHES.items():
        path = os.path.join(copy, name)
        with open(path) as f:
            text = f.read()
        for anchor, replacement in patches:
            if text.count(anchor) != 1:
                sys.exit(f"trilinear_counters: {name}: anchor not found once: {anchor.strip()!r}")
            text = text.replace(anchor, replacement)
        with open(path, "w") as f:
            f.write(text)
    return copy


def tile_max(x):
    h, w = x.shape[0] // 2 * 2, x.shape[1] // 4 * 4
    return x[:h, :w].reshape(h // 2, 2, w // 4, 4).max(axis=(1, 3))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("voxlink")
    ap.add_argument("shaders")
    ap.add_argument("out")
    ap.add_argument("files", nargs="+", help="FILE.vxl:TF.json")
    ap.add_argument("--size", default="256x256")
    ap.add_argument("--termination-alpha", default="0.996078431")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    env = dict(os.environ, VOXLINK_SHADER_DIR=counting_copy(a.shaders, a.out))
    print(f"trilinear, {a.size}, default camera, rays stop at opacity {a.termination_alpha}; "
          "per ray that meets the volume's box; tile = a 4x2 tile's slowest lane\n")
    print("| file | rays | passes / ray | visible-cell passes / ray | other passes / ray | "
          "samples / ray | samples / visible pass | tile: passes / samples | tile passes |")
    print("|---|---:|---:|---:|---:|---:|---:|---|---:|")
    for item in a.files:
        vxl, tf = item.rsplit(":", 1)
        png = os.path.join(a.out, os.path.splitext(os.path.basename(vxl))[0] + ".png")
        cmd = [a.voxlink, "render", vxl, "--tf", tf, "--sampling", "trilinear", "--size", a.size,
               "--termination-alpha", a.termination_alpha, "-o", png]
        p = subprocess.run(cmd, capture_output=True, text=True, env=env)
        if p.returncode != 0:
            sys.exit(f"trilinear_counters: failed: {' '.join(cmd)}\n{p.stderr}")
        counts = np.rint(matplotlib.image.imread(png)[..., :3] * SCALE).astype(np.int64)
        passes, visible, samples = counts[..., 0], counts[..., 1], counts[..., 2]
        ray = passes > 0
        if not ray.any():
            sys.exit(f"trilinear_counters: no ray met {vxl}'s box")
        tiles = tile_max(passes)
        met = tiles > 0
        per_visible = samples[ray].sum() / max(visible[ray].sum(), 1)
        print(f"| {os.path.basename(vxl)} | {ray.sum()} | {passes[ray].mean():.1f} | "
              f"{visible[ray].mean():.1f} | {(passes - visible)[ray].mean():.1f} | "
              f"{samples[ray].mean():.1f} | {per_visible:.2f} | "
              f"{tiles[met].mean():.1f} / {tile_max(samples)[met].mean():.1f} | {tiles.sum()} |")


if __name__ == "__main__":
    main()
