#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Two voxlink builds' trilinear (or voxel) frames on the three CT volumes of bench/render_vs_paraview.sh
# (converted as it converts them, ray termination at its 1 - 1/255), alternating A and B per
# round so that both see the same load (docs/rendering-trilinear-profile.md). Prints per data
# set the median ms of each build and the median of the per-round ratios A / B.
# usage: bench/trilinear_ab.sh VOXLINK_A SHADERS_A VOXLINK_B DATA_DIR [ROUNDS] [SIZE] [SAMPLING]
#        SHADERS_A: a shaders/ directory for A (VOXLINK_SHADER_DIR), or - for its built-in ones;
#        SAMPLING: trilinear (default) or voxel.
# AB_ARGS="--shadows" passes extra options to every bench-render run (docs/viewer.md, shadows).
# AB_CPU=1 times each run by the CPU seconds (user + sys) it took as a whole, not by its frames'
# wall-clock ms: on the shared 2-core machine, wall time swung 2-3x with other engineers' load
# while CPU seconds varied by 2 % (docs/rendering-trilinear-profile.md, seventh session). The
# CPU figure includes loading and the shader compile, the same for both builds.
set -euo pipefail
a=$(realpath "$1")
shaders_a=$2
b=$(realpath "$3")
data=$4
rounds=${5:-5}
size=${6:-1000x1000}
sampling=${7:-trilinear}
tf=$(cd "$(dirname "$0")" && pwd)/tf
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
termination=$(awk 'BEGIN {printf "%.9f", 1 - 1 / 255}')
"$b" convert "$data/ct/openscivis_lossy/foot_256x256x256_uint8_lossy.nrrd" --tf "$tf/foot-bone.tf.json" -o "$tmp/foot.vxl" -q
"$b" convert "$data/ct/vtkjs_LIDC2/LIDC2.nhdr" --tf "$tf/lidc-bone.tf.json" -o "$tmp/lidc.vxl" -q
"$b" convert "$data/ct/tooth_103x94x161_uint8.raw" --tf "$tf/tooth.tf.json" -o "$tmp/tooth.vxl" -q \
  --dims 103 94 161 --type u8
frame() {  # binary shader-dir name -> ms per frame (CPU seconds of the run with AB_CPU=1)
  local env=()
  [[ $2 != - ]] && env=(VOXLINK_SHADER_DIR="$(realpath "$2")")
  local run=(env "${env[@]}" "$1" bench-render "$tmp/$3.vxl" --tf "$tf/$3$( [[ $3 == tooth ]] || echo -bone).tf.json"
    --sizes "$size" --frames-per-turn 1 --no-dense --no-reference --samplings "$sampling"
    --termination-alpha "$termination" ${AB_ARGS:-})
  if [[ ${AB_CPU:-0} == 1 ]]; then
    local TIMEFORMAT='%U %S'
    { time "${run[@]}" >/dev/null 2>&1; } 2>&1 | awk '{print $1 + $2}'
  else
    "${run[@]}" | grep "^| voxlink | $sampling " | awk -F'|' '{gsub(/ /, "", $6); print $6}'
  fi
}
unit=ms
[[ ${AB_CPU:-0} == 1 ]] && unit="s CPU"
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
echo "$sampling, $size, $rounds rounds; load before: $(uptime | sed 's/.*load average: //')"
for ((r = 1; r <= rounds; ++r)); do
  for name in foot lidc tooth; do
    ta=$(frame "$a" "$shaders_a" "$name")
    tb=$(frame "$b" - "$name")
    echo "$name round $r: A $ta $unit, B $tb $unit"
    echo "$ta $tb" >>"$tmp/$name.times"
  done
done
echo "load after: $(uptime | sed 's/.*load average: //')"
echo
echo "| data | rounds | A $unit median | B $unit median | median of per-round A / B | range |"
echo "|---|---:|---:|---:|---:|---:|"
for name in foot lidc tooth; do
  f=$tmp/$name.times
  awk -v n="$name" -v r="$rounds" -v ma="$(awk '{print $1}' "$f" | median)" \
      -v mb="$(awk '{print $2}' "$f" | median)" -v mr="$(awk '{print $1 / $2}' "$f" | median)" \
      -v lo="$(awk '{print $1 / $2}' "$f" | sort -g | head -1)" -v hi="$(awk '{print $1 / $2}' "$f" | sort -g | tail -1)" \
      'BEGIN {printf "| %s | %d | %.4g | %.4g | %.2fx | %.2f-%.2f |\n", n, r, ma, mb, mr, lo, hi}'
done
