#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The rendering benchmark of docs/rendering-benchmark.md: converts real CT with a transfer
# function (pre-classification keeps what it shows), then runs `voxlink bench-render`: the
# paper's protocol (360 deg about y, then 360 deg about x) for the VoxLink ray tracer and the
# dense 3D-texture ray caster, interleaved frame by frame, each with its PSNR against the float64
# reference.
# usage: bench/render_bench.sh VOXLINK DATA_DIR OUT_DIR [FRAMES_PER_TURN] [SIZES...]
# BRICK=N (environment) sets the files' brick size, 8 (the converter's default) unless given;
# STEP=S passes --step S (trilinear step in voxels, default 0.5), SAMPLINGS="voxel trilinear"
# picks the sampling modes, DATASETS="foot tooth" the data sets (default all three), NO_DENSE=1
# leaves the dense caster out (bench/report.py sweeps steps with these).
set -euo pipefail
brick=${BRICK:-8}
read -ra samplings <<< "${SAMPLINGS:-voxel trilinear}"
datasets=" ${DATASETS:-lidc foot tooth} "
extra=(--step "${STEP:-0.5}")
[[ -n ${NO_DENSE:-} ]] && extra+=(--no-dense)
voxlink=$1
data=$2
out=$3
frames=${4:-6}
shift $(( $# < 4 ? $# : 4 ))
sizes=("${@:-512x512 1000x1000}")
[[ $# -eq 0 ]] && sizes=(512x512 1000x1000)
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"

run() {  # name source tf [convert options...]
  local name=$1 source=$2 tf=$3
  shift 3
  [[ $datasets == *" $name "* ]] || return 0
  if [[ ! -e $source ]]; then echo "skipped $name: $source missing"; return; fi
  "$voxlink" convert "$source" --tf "$tf" --brick "$brick" -o "$out/$name.vxl" -q "$@" | tee "$out/$name.convert.txt"
  "$voxlink" bench-render "$out/$name.vxl" --tf "$tf" --sizes "${sizes[@]}" \
      --frames-per-turn "$frames" --samplings "${samplings[@]}" "${extra[@]}" \
      --pictures "$out/$name" | tee "$out/$name.md"
}

run lidc "$data/ct/vtkjs_LIDC2/LIDC2.nhdr" "$here/tf/lidc-bone.tf.json"
run foot "$data/ct/openscivis_lossy/foot_256x256x256_uint8_lossy.nrrd" "$here/tf/foot-bone.tf.json"
run tooth "$data/ct/tooth_103x94x161_uint8.raw" "$here/tf/tooth.tf.json" --dims 103 94 161 --type u8
