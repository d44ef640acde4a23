#!/bin/bash
# SPDX-License-Identifier: BSD-3-Clause
# Peak memory and time of reading a large uncompressed Enhanced CT multi-frame file: `voxlink
# stats` and `voxlink convert` (frames decoded one at a time; the GDCM guard's child included,
# as GNU time counts waited-for descendants) against `gdcmconv --raw`, which decodes the whole
# image with GDCM as a user of GDCM alone would. Median of N runs (default 5).
# Usage: bench/dicom_multiframe_memory.sh [BUILD_DIR] [N]
set -euo pipefail
build=${1:-build}
runs=${2:-5}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
python3 "$(dirname "$0")/make_enhanced_dicom.py" "$work/big.dcm" 512 512 240
bytes=$(stat -c %s "$work/big.dcm")
median() { sort -n | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
measure() {  # name, command...: prints "name median_s median_rss_mb"
  local name=$1; shift
  local times=() rss=()
  for _ in $(seq "$runs"); do
    out=$(/usr/bin/time -f "%e %M" "$@" 2>&1 >/dev/null | tail -1)
    times+=("${out% *}"); rss+=("${out#* }")
  done
  printf '%-34s %10s %14s\n' "$name" "$(printf '%s\n' "${times[@]}" | median)" \
    "$(printf '%s\n' "${rss[@]}" | median | awk '{printf "%.1f", $1 / 1024}')"
}
echo "input: 512x512x240 u16 Enhanced CT, $((bytes / 1000000)) MB, $runs runs, medians"
printf '%-34s %10s %14s\n' "command" "seconds" "peak RSS MB"
measure "voxlink stats" "$build/cli/voxlink" stats "$work/big.dcm"
measure "voxlink convert --threshold 128" "$build/cli/voxlink" convert "$work/big.dcm" \
  --threshold 128 -o "$work/big.vxl"
measure "gdcmconv --raw (peer)" gdcmconv --raw "$work/big.dcm" "$work/raw.dcm"
