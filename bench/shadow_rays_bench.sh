#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Shadow rays, speed against error (docs/shadows.md): converts the foot, the tooth and the LIDC
# chest with their bench transfer functions (as bench/render_bench.sh does), then for each and
# both sampling modes runs voxlink_bench_shadow_rays (bench/shadow_rays_bench.cpp): GL frames
# without shadows, with per-sample and with per-voxel shadow rays, and the per-voxel still frame
# (the cache reused), interleaved, median ms and
# ratios from the same run, and PSNRs against both float64 references. Prints one table.
# usage: bench/shadow_rays_bench.sh VOXLINK BENCH_TOOL DATA_DIR OUT_DIR [SIZE] [FRAMES_PER_TURN]
# DATASETS="foot tooth lidc" picks the data sets, SAMPLINGS="voxel trilinear" the modes.
set -euo pipefail
voxlink=$1
tool=$2
data=$3
out=$4
size=${5:-256x256}
perTurn=${6:-4}
datasets=" ${DATASETS:-foot tooth lidc} "
read -ra samplings <<< "${SAMPLINGS:-voxel trilinear}"
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"

echo "shadow rays at $size, $perTurn views per turn (2 turns), median ms; $(date -u +%FT%TZ); load: $(uptime | sed 's/.*load average/load average/')"
echo "none / per-sample / per-voxel: GL frame without shadows, with a shadow ray per sample, with the per-voxel cache (its fill included);"
echo "still: the per-voxel frame again from the same view (the viewer's still frame, a zoom or a pan: the cache reused, no fill);"
echo "PSNR (dB, first view) of each GL frame against the float64 per-sample (ref-S) and per-voxel (ref-V) references;"
echo "ref-V vs ref-S: the per-voxel model's own error; V vs S: the two GL frames; ref ms: the two references' render times."
echo
echo "| data | sampling | size | views | none ms | per-sample ms | per-voxel ms | still ms | per-sample / none | per-voxel / none | still / none | per-sample / per-voxel | none vs ref-S | per-sample vs ref-S | per-sample vs ref-V | per-voxel vs ref-S | per-voxel vs ref-V | ref-V vs ref-S | V vs S | ref-S / ref-V ms | cache MiB |"
echo "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"

run() {  # name source tf [convert options...]
  local name=$1 source=$2 tf=$3
  shift 3
  [[ $datasets == *" $name "* ]] || return 0
  if [[ ! -e $source ]]; then echo "skipped $name: $source missing"; return; fi
  "$voxlink" convert "$source" --tf "$tf" -o "$out/$name.vxl" -q "$@"
  for sampling in "${samplings[@]}"; do
    "$tool" "$name" "$out/$name.vxl" "$tf" "$sampling" "$size" "$perTurn"
  done
}

run foot "$data/ct/openscivis_lossy/foot_256x256x256_uint8_lossy.nrrd" "$here/tf/foot-bone.tf.json"
run tooth "$data/ct/tooth_103x94x161_uint8.raw" "$here/tf/tooth.tf.json" --dims 103 94 161 --type u8
run lidc "$data/ct/vtkjs_LIDC2/LIDC2.nhdr" "$here/tf/lidc-bone.tf.json"
