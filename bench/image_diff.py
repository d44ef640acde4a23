#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Where a voxel image differs from the exact one (`render-exact --compare X.vxl --voxel-output
V.png -o E.png`): counts the differing pixels by kind and writes a colour-coded diff image.
Pure Python (8-bit RGB/RGBA PNG, no interlace), so it runs where numpy and Pillow do not.

usage: image_diff.py EXACT.png VOXEL.png DIFF.png [--threshold 0.1]

Background is the colour of the top-left pixel of the exact image. Kinds, and their colour in
DIFF.png (grey: the exact image, dimmed, where the two agree within the threshold):
  extra  (red):    the voxel image shows a surface where the exact one shows background
  miss   (blue):   the exact image shows a surface where the voxel one shows background
  shade  (yellow): both show a surface, colours differ by more than the threshold (max channel)
The squared error of each kind, as a share of the image's total, says which kind costs the PSNR.
"""
import argparse
import struct
import sys
import zlib


def read_png(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        sys.exit(f"{path}: not a PNG")
    pos, idat, width = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or colour not in (2, 6) or interlace:
                sys.exit(f"{path}: IHDR: only 8-bit RGB/RGBA, not interlaced")
            channels = 3 if colour == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw, stride = zlib.decompress(idat), width * channels
    rows, prev = [], bytearray(stride)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b, c = prev[i], prev[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[x * channels:x * channels + 3]) for x in range(width)])
        prev = line
    return width, height, rows


def write_png(path, width, height, rows):
    raw = b"".join(b"\x00" + bytes(v for px in row for v in px) for row in rows)
    chunk = lambda kind, body: (struct.pack(">I", len(body)) + kind + body +
                                struct.pack(">I", zlib.crc32(kind + body)))
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("exact")
    parser.add_argument("voxel")
    parser.add_argument("diff")
    parser.add_argument("--threshold", type=float, default=0.1)
    args = parser.parse_args()
    w, h, exact = read_png(args.exact)
    w2, h2, voxel = read_png(args.voxel)
    if (w, h) != (w2, h2):
        sys.exit(f"{args.voxel}: IHDR: {w2}x{h2}, the exact image is {w}x{h}")
    background = exact[0][0]
    counts = {"extra": 0, "miss": 0, "shade": 0}
    error = {"extra": 0.0, "miss": 0.0, "shade": 0.0, "agree": 0.0}
    colours = {"extra": (255, 0, 0), "miss": (0, 0, 255), "shade": (255, 255, 0)}
    out = []
    for y in range(h):
        row = []
        for x in range(w):
            e, v = exact[y][x], voxel[y][x]
            sq = sum(((a - b) / 255.0) ** 2 for a, b in zip(e, v)) / 3
            if max(abs(a - b) for a, b in zip(e, v)) / 255.0 <= args.threshold:
                error["agree"] += sq
                row.append(tuple(c // 3 for c in e))
                continue
            kind = ("extra" if e == background else "miss" if v == background else "shade")
            counts[kind] += 1
            error[kind] += sq
            row.append(colours[kind])
        out.append(row)
    write_png(args.diff, w, h, out)
    total = sum(error.values()) or 1.0
    print(f"{args.voxel} against {args.exact}: {w}x{h}, background {background}, threshold {args.threshold}")
    for kind in ("extra", "miss", "shade"):
        print(f"  {kind}: {counts[kind]} pixels ({100 * counts[kind] / (w * h):.3f} %), "
              f"{100 * error[kind] / total:.1f} % of the squared error")
    print(f"  within the threshold: {100 * error['agree'] / total:.1f} % of the squared error")


if __name__ == "__main__":
    main()
