#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Configures and builds VoxLink in ./build (Release). Extra arguments go to cmake.
# VOXLINK_TARGETS="voxlink voxlink_vdb" builds only those targets (default: all). Options such
# as VOXLINK_BUILD_TESTS stay in ./build's cache: pass them again to change them back.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)
launcher=()
if command -v ccache > /dev/null; then
  # Paths below the checkout's parent are hashed relative, so clones anywhere share the cache.
  export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$(dirname "$PWD")}"
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" "$@"
targets=()
if [ -n "${VOXLINK_TARGETS:-}" ]; then
  read -ra names <<< "$VOXLINK_TARGETS"
  targets=(--target "${names[@]}")
fi
cmake --build build -j "$jobs" "${targets[@]}"
