#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Builds the libFuzzer targets (fuzz/, clang 14, ASan + UBSan) in ./build-fuzz and runs each for
# SECONDS (default 60). Seeds come from ../shared/data (fuzz/make_seeds.py) and the kept crash
# inputs in tests/data/fuzz-regressions; new corpus entries stay in build-fuzz/fuzz-corpus.
# FUZZ_TARGETS="nrrd vti" picks targets. A crash, leak, timeout or out-of-memory input is left in
# build-fuzz/fuzz-artifacts/<target>/ and makes the script fail. One line per target reports
# executions, coverage (libFuzzer's cov:) and findings; logs are in build-fuzz/fuzz-logs.
# FUZZ_KEEP_GOING=1 runs libFuzzer's fork mode, which keeps fuzzing after a finding (long runs).
# FUZZ_CI=1 (what scripts/run-tests.sh uses) makes the run repeatable: every target starts from
# the seeds and kept inputs only (a fresh corpus folder, so earlier runs do not change it),
# replays all of them first, then mutates with the fixed seed FUZZ_SEED (default 1) for SECONDS;
# the time only decides how long a prefix of that fixed input sequence runs, so a finding is a
# real one that the same command reproduces. Its per-input timeout is 120 s instead of 25 s, so
# a loaded CI machine does not report a slow input as a hang.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
build=build-fuzz
data_dir=${VOXLINK_DATA_DIR:-../shared/data}
launcher=()
if command -v ccache > /dev/null; then
  export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$(dirname "$PWD")}"
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
mkdir -p "$build"
# -O1 and line tables: quick to build on 2 cores, fast enough to fuzz, reports name lines. No
# viewer (GL) and no tests: the targets need the readers, format/ and geostat only.
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" \
  -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 \
  -DVOXLINK_FUZZ=ON -DVOXLINK_BUILD_TESTS=OFF -DVOXLINK_BUILD_VIEWER=OFF -DVOXLINK_DATA_DIR="$(realpath -m "$data_dir")" \
  "${launcher[@]}" > "$build/configure.log" 2>&1 || { cat "$build/configure.log"; exit 1; }
# The .vxl seeds are converted by the normal build's voxlink when there is one (CI builds it
# first); otherwise by a sanitized one built here.
voxlink=${VOXLINK_EXE:-build/cli/voxlink}
fuzz_targets=(voxlink_fuzzers)
if [[ ! -x "$voxlink" ]]; then
  voxlink="$build/cli/voxlink"
  fuzz_targets+=(voxlink)
fi
cmake --build "$build" -j "$(nproc)" --target "${fuzz_targets[@]}"

rm -rf "$build/fuzz-seeds"
if [[ -d "$data_dir" ]]; then
  python3 fuzz/make_seeds.py "$data_dir" "$build/fuzz-seeds" "$voxlink"
else
  echo "fuzz.sh: $data_dir missing: fuzzing from the kept regression inputs only" >&2
fi

# Leaks inside libraries that are not ours (Mesa, OpenImageIO) are suppressed by library.
export LSAN_OPTIONS=suppressions=$(realpath scripts/sanitizers/lsan.supp):print_suppressions=0
targets=${FUZZ_TARGETS:-$(cat "$build/fuzz/targets.txt")}
ci=${FUZZ_CI:-0}
corpus_root="$build/fuzz-corpus"
seed_args=()
input_timeout=25
if [[ $ci == 1 ]]; then
  corpus_root="$build/fuzz-ci-corpus"
  rm -rf "$corpus_root"
  seed_args=(-seed="${FUZZ_SEED:-1}")
  input_timeout=120
elif [[ -n "${FUZZ_SEED:-}" ]]; then
  seed_args=(-seed="$FUZZ_SEED")
fi
mkdir -p "$build/fuzz-logs"
failed=()
printf '%-18s %8s %12s %8s %6s  %s\n' target seconds execs cov ft findings
for t in $targets; do
  corpus="$corpus_root/$t"
  artifacts="$build/fuzz-artifacts/$t"
  mkdir -p "$corpus" "$artifacts"
  dirs=("$corpus")
  for extra in "$build/fuzz-seeds/$t" "tests/data/fuzz-regressions/$t"; do
    [[ -d "$extra" ]] && dirs+=("$extra")
  done
  log="$build/fuzz-logs/$t.log"
  # 2 GB per input: a header asking for more must be refused, not allocated. GDCM runs first in
  # the DICOM guard's forked child (libFuzzer's limits apply there too), where a damaged file can
  # make it allocate more before it gives up; our own reads are bounded below that.
  # libpng (image_stack, through OpenImageIO) allocates a chunk's stated length, up to 2 GB,
  # before it finds the file too short.
  limit=2048
  [[ $t == dicom ]] && limit=8192
  [[ $t == image_stack ]] && limit=4096
  rc=0
  keep_going=()
  if [[ -n "${FUZZ_KEEP_GOING:-}" ]]; then
    keep_going=(-fork=1 -ignore_crashes=1 -ignore_ooms=1 -ignore_timeouts=1)
  fi
  "$build/fuzz/fuzz_$t" -max_total_time="$seconds" -timeout=$input_timeout -rss_limit_mb=$limit \
    -malloc_limit_mb=$limit \
    -max_len=65536 -print_final_stats=1 -artifact_prefix="$artifacts/" "${seed_args[@]}" \
    "${keep_going[@]}" "${dirs[@]}" \
    > "$log" 2>&1 || rc=$?
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  [[ -n "$execs" ]] || execs=$(grep -o '^#[0-9]*' "$log" | tail -1 | tr -d '#')
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | cut -d' ' -f2 || true)
  ft=$(grep -o 'ft: [0-9]*' "$log" | tail -1 | cut -d' ' -f2 || true)
  # Slow units (over 10 s) are kept beside the findings but are not failures.
  findings=$(find "$artifacts" -type f ! -name 'slow-unit-*' | wc -l)
  printf '%-18s %8s %12s %8s %6s  %s\n' "$t" "$seconds" "${execs:-?}" "${cov:-?}" "${ft:-?}" \
    "$findings"
  if [[ $rc -ne 0 || $findings -ne 0 ]]; then
    failed+=("$t")
    grep -m3 -E 'ERROR|SUMMARY|runtime error' "$log" >&2 || tail -5 "$log" >&2
  fi
done
if [[ ${#failed[@]} -ne 0 ]]; then
  echo "fuzz.sh: findings in: ${failed[*]} (inputs in $build/fuzz-artifacts, logs in $build/fuzz-logs)" >&2
  exit 1
fi
