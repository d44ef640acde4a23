#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Fails, naming file and line, when C++ outside base/parallel_for.* starts threads or calls a
# parallel library itself: every parallel path goes through base/parallel_for.h so that
# --threads bounds it (docs/parallelism.md). Tests and benchmarks may do as they like.
set -euo pipefail
cd "$(dirname "$0")/.."
# Threads that are not parallel work, each with its reason (docs/parallelism.md):
allowed=(
  viewer/app/reclassifier  # the window's background re-classification; its converter obeys the limit
  viewer/app/detail/reclassifier  # its header (internal to viewer/, so in detail/)
  viewer/app/mesh_promotion.cpp  # the window's background rebuild when a static mesh starts to move; its scene build obeys the limit
  mpi/mpi_rank_group.cpp   # one thread that waits for MPI messages while the rank works
)
pattern='tbb::|<tbb/|std::thread[^:_]|std::thread$|std::jthread|std::async|pthread_create|#pragma omp'
hits=$(git ls-files '*.h' '*.cpp' ':!:tests/' ':!:bench/' ':!:fuzz/' \
         ':!:base/parallel_for.h' ':!:base/parallel_for.cpp' |
       xargs grep -nE "$pattern" || true)
for path in "${allowed[@]}"; do
  hits=$(printf '%s\n' "$hits" | grep -v "^$path" || true)
done
hits=$(printf '%s\n' "$hits" | sed '/^$/d')
if [ -n "$hits" ]; then
  echo "check-parallel-paths: parallel code outside base/parallel_for.h:" >&2
  printf '%s\n' "$hits" >&2
  exit 1
fi
echo "check-parallel-paths: every parallel path goes through base/parallel_for.h"
