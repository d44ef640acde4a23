#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Issue 26 item 8 on a shared 2-core machine: how much faster `voxlink convert --threads 2` is
# than `--threads 1`, against what two copies of a pure compute loop gain over one in the same
# run (the share of the second core the machine gives at that moment); the goal is conv_x >= 90 %
# of loop_x (conv_of_loop). Rounds alternate the four
# runs; prints each round and the medians.
#   bash bench/two_core_speedup.sh VOXLINK RAW N THRESHOLD [ROUNDS]
set -euo pipefail
voxlink=$1 raw=$2 n=$3 threshold=$4 rounds=${5:-5}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
cat "$raw" > /dev/null  # page cache
now() { date +%s.%N; }
# A loop of about a second of one core: the same work once, then twice at the same time.
spin() { awk 'BEGIN { s = 0; for (i = 0; i < 2e7; ++i) s += i % 7; print s > "/dev/null" }'; }
convert() {
  "$voxlink" convert "$raw" --dims "$n,$n,$n" --type u8 --threshold "$threshold" \
    --threads "$1" -q -o "$out/v.vxl"
}
printf '%-6s %10s %10s %10s %10s %9s %9s %7s\n' round loop1_s loop2_s conv1_s conv2_s loop_x conv_x conv_of_loop
for ((r = 1; r <= rounds; ++r)); do
  a=$(now); spin; b=$(now); spin & spin & wait; c=$(now)
  convert 1; d=$(now); convert 2; e=$(now)
  awk -v r="$r" -v l1="$(echo "$b - $a" | bc)" -v l2="$(echo "$c - $b" | bc)" \
      -v c1="$(echo "$d - $c" | bc)" -v c2="$(echo "$e - $d" | bc)" 'BEGIN {
    lx = 2 * l1 / l2; cx = c1 / c2
    printf "%-6d %10.3f %10.3f %10.3f %10.3f %9.2f %9.2f %6.0f%%\n", r, l1, l2, c1, c2, lx, cx, 100 * cx / lx
  }'
done | tee "$out/rounds.txt"
sort -n -k6 "$out/rounds.txt" | awk '{ lx[NR] = $6 } END { printf "median loop speed-up %.2fx\n", lx[int((NR + 1) / 2)] }'
sort -n -k7 "$out/rounds.txt" | awk '{ cx[NR] = $7 } END { printf "median convert speed-up %.2fx\n", cx[int((NR + 1) / 2)] }'
