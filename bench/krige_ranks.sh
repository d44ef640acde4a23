#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# docs/scale.md: `voxlink krige` (or any krige/grf command line) on 1, 2 and 4 MPI ranks
# (oversubscribed past the machine's cores), wall time and peak RSS per rank (/usr/bin/time), and
# whether every rank count wrote the bytes the plain process wrote.
#   bash bench/krige_ranks.sh VOXLINK OUT_DIR NAME.npy|NAME.nhdr ARGS...
# ARGS is the command line after `voxlink` without -o (e.g. krige walker.csv --value V ...).
set -euo pipefail
voxlink=$1 out=$2 name=$3
shift 3
mpirun=(mpirun -q --oversubscribe)
[ "$(id -u)" = 0 ] && mpirun+=(--allow-run-as-root)
mkdir -p "$out/plain"
/usr/bin/time -f "plain: %e s wall, peak RSS %M KiB" "$voxlink" "$@" -q -o "$out/plain/$name"
for ranks in 1 2 4; do
  rm -rf "$out/ranks"; mkdir -p "$out/ranks"; sync
  start=$(date +%s.%N)
  "${mpirun[@]}" -n "$ranks" /usr/bin/time -f "  rank: %e s wall, peak RSS %M KiB" \
    "$voxlink" "$@" -q -o "$out/ranks/$name"
  end=$(date +%s.%N)
  echo "$ranks ranks: $(echo "$end - $start" | bc) s wall under mpirun (start-up included)"
  same=yes
  for f in "$out"/plain/*; do cmp -s "$f" "$out/ranks/$(basename "$f")" || same=no; done
  echo "  same bytes as the plain process: $same ($(ls "$out/plain" | tr '\n' ' '))"
done
rm -rf "$out/plain" "$out/ranks"
