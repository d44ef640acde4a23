#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# VoxLink's GL ray tracer against ParaView's volume ray caster at matched settings
# (docs/rendering-benchmark.md, "Against ParaView"): each CT volume converted with its transfer
# function, exported dense for ParaView (`voxlink export`, the same kept values), then in turn
# `voxlink bench-render` (voxel and trilinear sampling, PSNR against the float64 reference,
# GPU memory) and bench/paraview_render_bench.py in pvpython (trilinear, step 0.5 voxels,
# shading on, the same camera orbit). Prints one summary table at the end.
# Early ray termination as ParaView's: VTK 5.11's vtkOpenGLGPUVolumeRayCastMapper stops a ray once
# its accumulated opacity exceeds g_opacityThreshold = 1 - 1/255; voxlink gets the same threshold.
# usage: bench/render_vs_paraview.sh VOXLINK DATA_DIR OUT_DIR [FRAMES_PER_TURN] [SIZE]
# OCCUPANCY=1 runs the occupancy sweep instead: the tooth CT kept at thresholds that keep about
# 1 %, 6 %, 20 % and 50 % of its voxels, each shown with a ramp TF over what it keeps.
# DATASETS picks the CT volumes (default "foot lidc tooth", issue 29's three; also engine, carp
# and beetle: the engine block, 11 % kept, and two 16-bit scans, 2.4 % and 3.8 % kept).
# BENCH_FLAGS (environment) adds options to bench-render, e.g. --no-reference (no PSNR, faster).
# pvpython needs an X display: the script starts its own Xvfb (display 180 + a free number).
set -euo pipefail
voxlink=$(realpath "$1")
data=$2
out=$3
frames=${4:-6}
size=${5:-1000x1000}
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"
out=$(realpath "$out")

display=180
while [[ -e /tmp/.X11-unix/X$display ]]; do display=$((display + 1)); done
Xvfb ":$display" -screen 0 1280x1024x24 -nolisten tcp >"$out/xvfb.log" 2>&1 &
xvfb=$!
trap 'kill $xvfb 2>/dev/null || true' EXIT
sleep 2

paraview_termination=$(awk 'BEGIN {printf "%.9f", 1 - 1 / 255}')
summary="$out/summary.md"
{
  echo "| data | voxels kept | file MB | GPU MiB | voxlink voxel ms | voxlink trilinear ms | ParaView ms | voxel speed-up | trilinear speed-up | PSNR voxel / trilinear dB |"
  echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---|"
} >"$summary"

# Column $2 (1-based, after the leading '|') of the bench-render row for sampling $1.
column() { grep "^| voxlink | $1 " "$3" | awk -F'|' -v c="$2" '{gsub(/ /, "", $(c + 1)); print $(c + 1)}'; }

run() {  # name source tf [convert options...]
  local name=$1 source=$2 tf=$3
  shift 3
  if [[ ! -e $source ]]; then echo "skipped $name: $source missing"; return; fi
  "$voxlink" convert "$source" --tf "$tf" -o "$out/$name.vxl" -q "$@"
  "$voxlink" export "$out/$name.vxl" -o "$out/$name.nrrd" -q
  # shellcheck disable=SC2086
  "$voxlink" bench-render "$out/$name.vxl" --tf "$tf" --sizes "$size" --no-dense ${BENCH_FLAGS:-} \
      --termination-alpha "$paraview_termination" \
      --frames-per-turn "$frames" --pictures "$out/$name" | tee "$out/$name.md"
  DISPLAY=":$display" pvpython --no-mpi "$here/paraview_render_bench.py" "$out/$name.nrrd" "$tf" \
      --size "$size" --frames-per-turn "$frames" --picture "$out/$name/paraview.png" \
      2>"$out/$name.paraview.err" | tee "$out/$name.paraview.txt"
  local kept voxel tri pv mib mb
  kept=$(grep -o '[0-9]* voxels = [0-9.]* %' "$out/$name.md" | head -1)
  voxel=$(column voxel 5 "$out/$name.md")
  tri=$(column trilinear 5 "$out/$name.md")
  mib=$(column trilinear 11 "$out/$name.md")
  pv=$(grep -o 'mean [0-9.]*' "$out/$name.paraview.txt" | awk '{print $2}')
  mb=$(awk -v b="$(stat -c %s "$out/$name.vxl")" 'BEGIN {printf "%.2f", b / 1e6}')
  awk -v n="$name" -v k="$kept" -v mb="$mb" -v mib="$mib" -v v="$voxel" -v t="$tri" -v p="$pv" \
      -v pv_="$(column voxel 9 "$out/$name.md")" -v pt="$(column trilinear 9 "$out/$name.md")" \
      'BEGIN {printf "| %s | %s | %s | %s | %.0f | %.0f | %.0f | %.1fx | %.1fx | %s / %s |\n",
              n, k, mb, mib, v, t, p, p / v, p / t, pv_, pt}' >>"$summary"
}

if [[ ${OCCUPANCY:-0} == 1 ]]; then
  for threshold in 240 200 156 80; do
    tf="$out/tooth-$threshold.tf.json"
    printf '{"format": "voxlink-transfer-function", "version": 1, "name": "tooth >= %s",\n "opacity": [[%s, 0.0], [%s, 0.02], [255, 0.5]],\n "color": [[%s, 0.9, 0.75, 0.6], [255, 1.0, 1.0, 0.95]]}\n' \
        "$threshold" "$((threshold - 1))" "$threshold" "$threshold" >"$tf"
    run "tooth-$threshold" "$data/ct/tooth_103x94x161_uint8.raw" "$tf" --dims 103 94 161 --type u8
  done
else
  datasets=" ${DATASETS:-foot lidc tooth} "
  picked() { [[ $datasets == *" $1 "* ]]; }
  scivis=$data/ct/openscivis_lossy
  if picked foot; then run foot "$scivis/foot_256x256x256_uint8_lossy.nrrd" "$here/tf/foot-bone.tf.json"; fi
  if picked lidc; then run lidc "$data/ct/vtkjs_LIDC2/LIDC2.nhdr" "$here/tf/lidc-bone.tf.json"; fi
  if picked tooth; then
    run tooth "$data/ct/tooth_103x94x161_uint8.raw" "$here/tf/tooth.tf.json" --dims 103 94 161 --type u8
  fi
  if picked engine; then run engine "$scivis/engine_256x256x128_uint8_lossy.nrrd" "$here/tf/engine.tf.json"; fi
  if picked carp; then run carp "$scivis/carp_128x128x256_uint16_lossy.nrrd" "$here/tf/carp-bone.tf.json"; fi
  if picked beetle; then
    run beetle "$scivis/stag_beetle_416x208x124_uint16_lossy.nrrd" "$here/tf/stag-beetle.tf.json"
  fi
fi
echo
echo "load: $(uptime)"
cat "$summary"
