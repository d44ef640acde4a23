#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Two builds' in-process Table 2 frame (bench-render --animate: the animated dragon re-voxelized
# on the GPU + a plain frame) in one run, alternating A and B so that both see the same load;
# per build the median over the rounds of each run's frame median, frame p95, voxelize and render
# medians (ms), and B's FPS over A's.
# Usage: bash bench/animate_ab.sh BUILD_A BUILD_B [ROUNDS] [SIZE] [FRAMES] [RESOLUTION] [BRICK]
#        [SCENE] (defaults 5 rounds, 512x512, 30 frames, 256, 4,
#        samples/scenes/dragon-animated.scene.json).
set -euo pipefail
a=${1:?build dir A}
b=${2:?build dir B}
rounds=${3:-5}
size=${4:-512x512}
frames=${5:-30}
res=${6:-256}
brick=${7:-4}
here=$(cd "$(dirname "$0")/.." && pwd)
scene=${8:-$here/samples/scenes/dragon-animated.scene.json}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "## $(basename "$scene" .scene.json) at $res, brick $brick, $size, $frames frames, $rounds rounds A/B"
echo "load before: $(uptime | sed 's/.*load average: //')"
for ((r = 1; r <= rounds; ++r)); do
  for side in A B; do
    build=$a
    [ "$side" = B ] && build=$b
    # | resolution | brick | size | triangles | MB | build s | vox | render | median | p95 | FPS |
    "$build/cli/voxlink" bench-render --animate "$scene" --resolutions "$res" --bricks "$brick" \
      --sizes "$size" --frames "$frames" | grep "^| $res | $brick |" |
      awk -F'|' '{gsub(/ /, ""); print $8, $9, $10, $11}' >> "$tmp/$side"
  done
done
echo "load after: $(uptime | sed 's/.*load average: //')"
echo
echo "| build | frame median ms | frame p95 ms | voxelize ms | render ms | FPS (1 / frame median) |"
echo "|---|---:|---:|---:|---:|---:|"
median() { sort -n | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
for side in A B; do
  build=$a
  [ "$side" = B ] && build=$b
  frame=$(awk '{print $3}' "$tmp/$side" | median)
  p95=$(awk '{print $4}' "$tmp/$side" | median)
  vox=$(awk '{print $1}' "$tmp/$side" | median)
  ren=$(awk '{print $2}' "$tmp/$side" | median)
  echo "| $side ($build) | $frame | $p95 | $vox | $ren | $(awk -v f="$frame" 'BEGIN{printf "%.1f", 1000 / f}') |"
  echo "$frame" > "$tmp/$side.frame"
done
echo
awk -v fa="$(cat "$tmp/A.frame")" -v fb="$(cat "$tmp/B.frame")" \
  'BEGIN{printf "B / A FPS: %.2f\n", fa / fb}'
