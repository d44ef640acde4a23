#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Frames with shadow rays against the float64 reference (issue 29) on the three CT volumes of
# bench/render_vs_paraview.sh, converted with their bench/tf transfer functions: bench-render
# --shadows (VoxLink and the dense caster, voxel and trilinear sampling) and, for comparison,
# the same without shadows. Prints bench-render's rows (PSNR of the first frame, ms per frame).
# usage: bench/shadow_accuracy.sh VOXLINK DATA_DIR [SIZE] [FRAMES_PER_TURN]
set -euo pipefail
voxlink=$(realpath "$1")
data=$2
size=${3:-256x256}
turn=${4:-2}
tf=$(cd "$(dirname "$0")" && pwd)/tf
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$voxlink" convert "$data/ct/openscivis_lossy/foot_256x256x256_uint8_lossy.nrrd" \
  --tf "$tf/foot-bone.tf.json" -o "$tmp/foot.vxl" -q
"$voxlink" convert "$data/ct/tooth_103x94x161_uint8.raw" --dims 103 94 161 --type u8 \
  --tf "$tf/tooth.tf.json" -o "$tmp/tooth.vxl" -q
"$voxlink" convert "$data/ct/vtkjs_LIDC2/LIDC2.nhdr" --tf "$tf/lidc-bone.tf.json" \
  -o "$tmp/lidc.vxl" -q
echo "$voxlink, $size, load before: $(uptime | sed 's/.*load average: //')"
for name in foot tooth lidc; do
  tfile=$tf/$name$([[ $name == tooth ]] || echo -bone).tf.json
  for shadows in --shadows ""; do
    echo "$name ${shadows:-no shadows}:"
    "$voxlink" bench-render "$tmp/$name.vxl" --tf "$tfile" --sizes "$size" \
      --frames-per-turn "$turn" $shadows 2>&1 | grep -E '^\| (voxlink|dense) |^voxlink:' || true
  done
done
echo "load after: $(uptime | sed 's/.*load average: //')"
