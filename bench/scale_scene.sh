#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# docs/scale.md: `voxlink scene build` of a generated torus (bench/large_mesh.cpp) on 1, 2 and 4
# MPI ranks (oversubscribed past the machine's cores): rank 0's summary line (load, voxelize,
# merge), wall time and peak RSS per rank (/usr/bin/time, labelled with the rank), and whether
# every rank count wrote the bytes the plain process wrote.
#   bash bench/scale_scene.sh VOXLINK GENERATOR TRIANGLES RESOLUTION WORKDIR
set -euo pipefail
voxlink=$1 generator=$2 triangles=$3 resolution=$4 work=$5
mpirun=(mpirun -q --oversubscribe)
[ "$(id -u)" = 0 ] && mpirun+=(--allow-run-as-root)
mkdir -p "$work"
trap 'rm -f "$work/torus.ply" "$work/torus.scene.json" "$work"/torus-*.vxl' EXIT
"$generator" "$work/torus.ply" "$triangles"
echo '{"objects": [{"type": "mesh", "file": "torus.ply"}]}' > "$work/torus.scene.json"
args=(scene build "$work/torus.scene.json" --resolution "$resolution")
echo "load average $(cut -d' ' -f1-3 /proc/loadavg), $(nproc) cores"
/usr/bin/time -f "plain: %e s wall, %U s user + %S s sys CPU, peak RSS %M KiB" "$voxlink" "${args[@]}" \
  -o "$work/torus-plain.vxl"
for ranks in 1 2 4; do
  start=$(date +%s.%N)
  "${mpirun[@]}" -n "$ranks" sh -c \
    'exec /usr/bin/time -f "  rank $OMPI_COMM_WORLD_RANK: %e s wall, %U s user + %S s sys CPU, peak RSS %M KiB" "$@"' sh \
    "$voxlink" "${args[@]}" -o "$work/torus-$ranks.vxl"
  end=$(date +%s.%N)
  echo "$ranks ranks: $(echo "$end - $start" | bc) s wall under mpirun (start-up included)"
  cmp "$work/torus-plain.vxl" "$work/torus-$ranks.vxl" && echo "  same bytes as the plain process"
  rm -f "$work/torus-$ranks.vxl"
done
echo "load average $(cut -d' ' -f1-3 /proc/loadavg) at the end"
