#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Times two voxlink builds on the same jobs, runs alternated, medians of 5, and compares the
# outputs byte for byte (docs/parallelism.md).
#   bench/parallel_before_after.sh BEFORE AFTER [FOOT1024_RAW]
# FOOT1024_RAW (the 1024^3 u8 foot, bench/upsample_volume.cpp; docs/benchmarks.md) adds its
# conversion on 2 threads, with the default slab and --slab 8. VOXLINK_BENCH_JOBS="job ..." runs
# only those jobs.
set -euo pipefail
before=$1; after=$2; foot1024=${3:-}
data=${VOXLINK_DATA_DIR:-$(cd "$(dirname "$0")/../.." && pwd)/shared/data}
scenes=$(cd "$(dirname "$0")/../samples/scenes" && pwd)
out=/tmp/bench-parallel; mkdir -p $out
declare -A jobs=(
  [convert-foot]="convert $data/ct/openscivis_lossy/foot_256x256x256_uint8_lossy.nrrd --threshold 60 -q -o"
  [convert-foot-slab8]="convert $data/ct/openscivis_lossy/foot_256x256x256_uint8_lossy.nrrd --threshold 60 --slab 8 -q -o"
  [scene-dragon512]="scene build $scenes/dragon.scene.json -q -o"
  [scene-bunny-molecule]="scene build $scenes/bunny-molecule.scene.json -q -o"
)
order="convert-foot convert-foot-slab8 scene-dragon512 scene-bunny-molecule"
if [ -n "$foot1024" ]; then
  big="convert $foot1024 --dims 1024,1024,1024 --type u8 --threshold 60 --threads 2"
  jobs[convert-foot1024-t2]="$big -q -o"
  jobs[convert-foot1024-t2-slab8]="$big --slab 8 -q -o"
  order="$order convert-foot1024-t2 convert-foot1024-t2-slab8"
  cat "$foot1024" > /dev/null  # page cache
fi
echo "uptime at start: $(uptime)"
for job in ${VOXLINK_BENCH_JOBS:-$order}; do
  declare -a tb=() ta=()
  for i in 1 2 3 4 5; do
    for which in before after; do
      bin=$before; [ $which = after ] && bin=$after
      s=$(date +%s.%N)
      $bin ${jobs[$job]} $out/$job.$which.vxl
      e=$(date +%s.%N)
      t=$(echo "$e - $s" | bc)
      if [ $which = before ]; then tb+=($t); else ta+=($t); fi
    done
  done
  mb=$(printf '%s\n' "${tb[@]}" | sort -n | sed -n 3p)
  ma=$(printf '%s\n' "${ta[@]}" | sort -n | sed -n 3p)
  same=$(cmp -s $out/$job.before.vxl $out/$job.after.vxl && echo identical || echo DIFFERENT)
  echo "$job: before ${tb[*]} (median $mb s); after ${ta[*]} (median $ma s); outputs $same"
done
echo "uptime at end: $(uptime)"
