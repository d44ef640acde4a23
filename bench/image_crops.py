#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""The same box cut from several images of one view, side by side in one small PNG (for the
docs: the exact image beside voxel images), with each crop's PSNR against the first one.
Pure Python, like image_diff.py (whose PNG reader and writer it uses).

usage: image_crops.py OUT.png X Y W H IMAGE... [--scale 2] [--gap 4]
"""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from image_diff import read_png, write_png  # noqa: E402


def psnr(a, b):
    sq = sum(((p - q) / 255.0) ** 2 for ra, rb in zip(a, b) for pa, pb in zip(ra, rb)
             for p, q in zip(pa, pb))
    mse = sq / (3 * len(a) * len(a[0]))
    return float("inf") if mse == 0 else -10 * math.log10(mse)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("out")
    p.add_argument("box", type=int, nargs=4, metavar="X Y W H")
    p.add_argument("images", nargs="+")
    p.add_argument("--scale", type=int, default=2)
    p.add_argument("--gap", type=int, default=4)
    args = p.parse_args()
    x, y, w, h = args.box
    crops = []
    for path in args.images:
        width, height, rows = read_png(path)
        if x < 0 or y < 0 or x + w > width or y + h > height:
            sys.exit(f"{path}: the box {x} {y} {w} {h} is outside its {width}x{height} pixels")
        crops.append([row[x:x + w] for row in rows[y:y + h]])
    for path, crop in zip(args.images, crops):
        print(f"{path}: PSNR {psnr(crops[0], crop):.2f} dB against {args.images[0]} in the box")
    s, gap = args.scale, args.gap
    white = (255, 255, 255)
    out = []
    for r in range(h * s):
        line = []
        for i, crop in enumerate(crops):
            if i:
                line += [white] * gap
            line += [px for px in crop[r // s] for _ in range(s)]
        out.append(line)
    write_png(args.out, len(out[0]), len(out), out)


if __name__ == "__main__":
    main()
