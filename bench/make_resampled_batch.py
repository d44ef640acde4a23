#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Makes a batch of CT volumes for `voxlink convert --batch` (docs/scale.md): every CT in
../shared/data listed below, resampled (nearest neighbour) to COUNT different sizes between
0.25x and 1x per axis, written as raw-encoded NRRD files, plus the list file.

    python3 bench/make_resampled_batch.py DATA_DIR OUT_DIR COUNT_PER_VOLUME
"""
import gzip
import os
import sys

import numpy as np

# path under DATA_DIR, dims (x, y, z), numpy type; NRRD files are read from their own header.
SOURCES = [
    ("ct/openscivis_lossy/foot_256x256x256_uint8_lossy.nrrd", None, None),
    ("ct/openscivis_lossy/engine_256x256x128_uint8_lossy.nrrd", None, None),
    ("ct/openscivis_lossy/carp_128x128x256_uint16_lossy.nrrd", None, None),
    ("ct/openscivis_lossy/stag_beetle_416x208x124_uint16_lossy.nrrd", None, None),
    ("ct/tooth_103x94x161_uint8.raw", (103, 94, 161), np.uint8),
    ("ct/voreen_walnut/walnut.raw", (128, 96, 114), np.dtype("<u2")),
    ("volume/neghip_64x64x64_uint8.raw", (64, 64, 64), np.uint8),
    ("volume/voreen_nucleon/nucleon.raw", (41, 41, 41), np.uint8),
]
TYPES = {"uint8": np.uint8, "uint16": np.dtype("<u2"), "unsigned short": np.dtype("<u2")}


def read_nrrd(path):
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"\n\n")
    fields = {}
    for line in data[:end].decode().splitlines()[1:]:
        if line.startswith("#") or ":" not in line:
            continue
        key, value = line.split(":", 1)
        fields[key.strip()] = value.strip()
    body = data[end + 2:]
    if fields["encoding"] == "gzip":
        body = gzip.decompress(body)
    dims = [int(v) for v in fields["sizes"].split()]
    return np.frombuffer(body, TYPES[fields["type"]]).reshape(dims[::-1])


def write_nrrd(path, volume):
    kind = "uint8" if volume.dtype == np.uint8 else "uint16"
    z, y, x = volume.shape
    with open(path, "wb") as f:
        f.write(f"NRRD0004\ntype: {kind}\ndimension: 3\nsizes: {x} {y} {z}\n"
                f"endian: little\nencoding: raw\n\n".encode())
        f.write(np.ascontiguousarray(volume).tobytes())


def main():
    data_dir, out_dir, count = sys.argv[1], sys.argv[2], int(sys.argv[3])
    os.makedirs(out_dir, exist_ok=True)
    names = []
    for rel, dims, dtype in SOURCES:
        path = os.path.join(data_dir, rel)
        if dims is None:
            volume = read_nrrd(path)
        else:
            volume = np.fromfile(path, dtype).reshape(dims[::-1])
        stem = os.path.basename(rel).split(".")[0]
        for i in range(count):
            scale = 0.25 + 0.75 * i / max(1, count - 1)
            index = [np.minimum((np.arange(max(1, round(n * scale))) / scale).astype(int), n - 1)
                     for n in volume.shape]
            resampled = volume[np.ix_(*index)]
            name = f"{stem}_{i:03d}.nrrd"
            write_nrrd(os.path.join(out_dir, name), resampled)
            names.append(name)
    with open(os.path.join(out_dir, "list.txt"), "w") as f:
        f.write("\n".join(names) + "\n")
    print(f"{len(names)} volumes in {out_dir}")


if __name__ == "__main__":
    main()
