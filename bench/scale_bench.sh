#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# docs/scale.md: `voxlink convert` of one raw u8 volume on 1, 2 and 4 MPI ranks (oversubscribed
# past the machine's cores), wall time and peak RSS per rank (/usr/bin/time), and whether every
# rank count wrote the bytes the plain process wrote.
#   bash bench/scale_bench.sh VOXLINK RAW N THRESHOLD OUT_DIR [threads per rank]
set -euo pipefail
voxlink=$1 raw=$2 n=$3 threshold=$4 out=$5 threads=${6:-0}
mpirun=(mpirun -q --oversubscribe)
[ "$(id -u)" = 0 ] && mpirun+=(--allow-run-as-root)
args=(convert "$raw" --dims "$n,$n,$n" --type u8 --threshold "$threshold" --threads "$threads" -q)
mkdir -p "$out"
cat "$raw" > /dev/null  # page cache
rm -f "$out/plain.vxl"; sync
/usr/bin/time -f "plain: %e s wall, peak RSS %M KiB" "$voxlink" "${args[@]}" -o "$out/plain.vxl"
for ranks in 1 2 4; do
  rm -f "$out/ranks$ranks.vxl"; sync
  start=$(date +%s.%N)
  "${mpirun[@]}" -n "$ranks" /usr/bin/time -f "  rank: %e s wall, peak RSS %M KiB" \
    "$voxlink" "${args[@]}" -o "$out/ranks$ranks.vxl"
  end=$(date +%s.%N)
  echo "$ranks ranks: $(echo "$end - $start" | bc) s wall under mpirun (start-up included)"
  cmp "$out/plain.vxl" "$out/ranks$ranks.vxl" && echo "  same bytes as the plain process"
  rm -f "$out/ranks$ranks.vxl"
done
rm -f "$out/plain.vxl"
