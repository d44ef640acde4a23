#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Stress run, not part of CI: a generated 10-million-triangle torus through `voxlink scene build`
# with each voxelizer, printing wall time and peak RSS (GNU time) for each.
#   bash bench/large_mesh_run.sh VOXLINK GENERATOR [TRIANGLES] [RESOLUTION] [WORKDIR]
set -euo pipefail
voxlink=$1
generator=$2
triangles=${3:-10000000}
resolution=${4:-1024}
work=${5:-${TMPDIR:-/tmp}/voxlink-large-mesh}
mkdir -p "$work"
trap 'rm -f "$work/torus.ply" "$work/torus.scene.json" "$work"/torus-*.vxl' EXIT
"$generator" "$work/torus.ply" "$triangles"
echo '{"objects": [{"type": "mesh", "file": "torus.ply"}]}' > "$work/torus.scene.json"
echo "load average $(cut -d' ' -f1-3 /proc/loadavg), $(nproc) cores"
for voxelizer in exact gl; do
  /usr/bin/time -f "$voxelizer: %e s wall, %U s user, %M KB peak RSS" \
    "$voxlink" scene build "$work/torus.scene.json" -o "$work/torus-$voxelizer.vxl" \
    --resolution "$resolution" --voxelizer "$voxelizer" --progress
done
