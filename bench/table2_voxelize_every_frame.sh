#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The paper's Table 2 on this machine (llvmpipe): the dragon, the house with glass windows and
# the glass-bunny scene voxelized every frame with the GL voxelizer (`scene build --voxelizer
# gl`, one process per frame, so context and shader set-up are included: an upper bound) plus a
# plain frame (`bench-render`, the paper's rotation protocol), at 256/512/1024 with bricks
# 4/8/16, as frames per second 1 / (voxelize + render). Table 1 is bench/table1_vs_embree.py.
# Usage: bash bench/table2_voxelize_every_frame.sh BUILD_DIR OUT_DIR [FRAMES_PER_TURN] [SIZE]
# (default 2 frames per turn, size 512x512). Prints a markdown table.
set -euo pipefail
build=${1:?build dir}
out=${2:?output dir}
turn=${3:-2}
shift $(( $# < 3 ? $# : 3 ))
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(512x512)
here=$(cd "$(dirname "$0")/.." && pwd)
voxlink="$build/cli/voxlink"
mkdir -p "$out"
scenes=(dragon house bunny-glass)

fps() {  # FILE SIZE [render options...] -> frames per second of the voxlink row
  local file=$1 size=$2
  shift 2
  "$voxlink" bench-render "$file" --sizes "$size" --frames-per-turn "$turn" --no-reference "$@" \
    2>/dev/null | awk -F'|' '$2 ~ /voxlink/ {gsub(/ /, "", $9); print $9}'
}

echo "## Table 2: GL voxelization every frame + a plain frame at ${sizes[0]} (FPS = 1 / (voxelize + render))"
echo
echo "| scene | resolution | brick 4 | brick 8 | brick 16 |"
echo "|---|---|---:|---:|---:|"
for scene in "${scenes[@]}"; do
  for res in 256 512 1024; do
    row="| $scene | $res |"
    for brick in 4 8 16; do
      file="$out/${scene}_gl_${res}_${brick}.vxl"
      voxelize=$("$voxlink" scene build "$here/samples/scenes/$scene.scene.json" -o "$file" \
        --resolution "$res" --brick "$brick" --voxelizer gl 2>/dev/null |
        sed -n 's/.*voxelize \([0-9.]*\) s.*/\1/p' | tail -1)
      render=$(fps "$file" "${sizes[0]}")
      row+=" $(awk -v v="$voxelize" -v r="$render" 'BEGIN{printf "%.2f", 1/(v + 1/r)}') |"
      rm -f "$file"
    done
    echo "$row"
  done
done
