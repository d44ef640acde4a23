#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# docs/scale.md: `voxlink convert --batch` of the volumes bench/make_resampled_batch.py made, in
# one plain process and on 2 and 4 MPI ranks (one thread each, oversubscribed past the
# machine's cores); prints each run's summary line (wall, busy and busiest-rank seconds) and
# peak RSS per rank.
#   bash bench/scale_batch.sh VOXLINK BATCH_DIR OUT_DIR THRESHOLD
set -euo pipefail
voxlink=$1 batch=$2 out=$3 threshold=$4
mpirun=(mpirun -q --oversubscribe)
[ "$(id -u)" = 0 ] && mpirun+=(--allow-run-as-root)
mkdir -p "$out"
cat "$batch"/*.nrrd > /dev/null  # page cache
run() {
  local name=$1
  shift
  rm -rf "$out/$name"
  "$@" --batch "$batch/list.txt" --out-dir "$out/$name" --threshold "$threshold" > "$out/$name.jsonl"
  echo "$name: $(tail -1 "$out/$name.jsonl")"
}
run plain /usr/bin/time -f "  plain: peak RSS %M KiB" "$voxlink" convert
for ranks in 2 4; do
  run "ranks$ranks" "${mpirun[@]}" -n "$ranks" /usr/bin/time -f "  rank: peak RSS %M KiB" \
    "$voxlink" convert --threads 1
done
for ranks in 2 4; do
  diff -rq "$out/plain" "$out/ranks$ranks" > /dev/null && echo "ranks$ranks: same bytes as plain"
done
