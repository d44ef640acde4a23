#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Speed-up of the VoxLink ray tracer over the dense ray caster as the kept fraction shrinks:
# the LIDC chest CT classified at rising thresholds, rendered with the ct-bone preset stretched
# over what each file keeps (so the TF shows exactly the kept values), voxel and trilinear
# sampling, the paper's protocol at 512x512 (docs/rendering-benchmark.md).
# usage: bench/render_sparsity_sweep.sh VOXLINK DATA_DIR OUT_DIR [FRAMES_PER_TURN]
# BRICK=N (environment) sets the files' brick size, 8 (the converter's default) unless given.
set -euo pipefail
brick=${BRICK:-8}
voxlink=$1
data=$2
out=$3
frames=${4:-6}
source="$data/ct/vtkjs_LIDC2/LIDC2.nhdr"
if [[ ! -e $source ]]; then echo "skipped: $source missing"; exit 0; fi
mkdir -p "$out"
for threshold in 20 41 100 160; do
  "$voxlink" convert "$source" --threshold "$threshold" --brick "$brick" -o "$out/lidc-$threshold.vxl" -q | tee "$out/lidc-$threshold.convert.txt"
  "$voxlink" bench-render "$out/lidc-$threshold.vxl" --tf-preset ct-bone --sizes 512x512 \
      --frames-per-turn "$frames" | tee "$out/lidc-$threshold.md"
done
