#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The paper's Table 2 in one process beside the per-process upper bound, in the same run: the
# animated dragon (samples/scenes/dragon-animated.scene.json, or SCENE: e.g. the moving protein
# of samples/scenes/protein-animated.scene.json) at 256/512 with bricks 4/8/16 (or BRICKS).
#   per process: `scene build --voxelizer gl` of the whole scene (its "voxelize" time) + a plain
#                frame from `bench-render` (as bench/table2_voxelize_every_frame.sh), FPS =
#                1 / (voxelize + render)
#   in process:  `bench-render --animate`: only the dragon re-voxelized on the GPU per frame +
#                the frame, FPS = 1 / median frame time
#   static frame: the same scene frozen at time 0, built whole and drawn as a static file (ms)
# Usage: bash bench/table2_in_process.sh BUILD_DIR OUT_DIR [SIZE] [FRAMES] [SCENE] [BRICKS]
# (default 512x512, 30, the animated dragon, "4 8 16").
set -euo pipefail
build=${1:?build dir}
out=${2:?output dir}
size=${3:-512x512}
frames=${4:-30}
here=$(cd "$(dirname "$0")/.." && pwd)
voxlink="$build/cli/voxlink"
scene=${5:-$here/samples/scenes/dragon-animated.scene.json}
bricks=${6:-4 8 16}
name=$(basename "$scene" .scene.json)
mkdir -p "$out"
echo "## Table 2, $name at $size: per-process upper bound vs in process (load: $(uptime | sed 's/.*load average: //'))"
echo
echo "| resolution | brick | per process FPS | in process FPS | in process frame p95 ms | voxelize ms | render ms | ratio | static scene frame ms |"
echo "|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
for res in 256 512; do
  for brick in $bricks; do
    file="$out/${name}_${res}_${brick}.vxl"
    voxelize=$("$voxlink" scene build "$scene" -o "$file" --resolution "$res" --brick "$brick" \
      --voxelizer gl 2>/dev/null | sed -n 's/.*voxelize \([0-9.]*\) s.*/\1/p' | tail -1)
    render=$("$voxlink" bench-render "$file" --sizes "$size" --frames-per-turn 2 --no-reference \
      2>/dev/null | awk -F'|' '$2 ~ /voxlink/ {gsub(/ /, "", $9); print $9}')
    rm -f "$file"
    perProcess=$(awk -v v="$voxelize" -v r="$render" 'BEGIN{printf "%.2f", 1/(v + 1/r)}')
    # | resolution | brick | size | triangles | MB | build s | vox | render | median | p95 | FPS |
    row=$("$voxlink" bench-render --animate "$scene" --resolutions "$res" --bricks "$brick" \
      --sizes "$size" --frames "$frames" 2>"$out/animate.err" | grep "^| $res | $brick |" || true)
    if [ -z "$row" ]; then  # e.g. the brick pool does not fit one storage buffer
      echo "| $res | $brick | $perProcess | - ($(tr -d '\n' < "$out/animate.err")) | | | | | |"
      continue
    fi
    inProcess=$(echo "$row" | awk -F'|' '{gsub(/ /, "", $12); print $12}')
    p95=$(echo "$row" | awk -F'|' '{gsub(/ /, "", $11); print $11}')
    vox=$(echo "$row" | awk -F'|' '{gsub(/ /, "", $8); print $8}')
    ren=$(echo "$row" | awk -F'|' '{gsub(/ /, "", $9); print $9}')
    still=$(echo "$row" | awk -F'|' '{gsub(/ /, "", $14); print $14}')
    ratio=$(awk -v a="$inProcess" -v b="$perProcess" 'BEGIN{printf "%.2f", a/b}')
    echo "| $res | $brick | $perProcess | $inProcess | $p95 | $vox | $ren | $ratio | $still |"
  done
done
