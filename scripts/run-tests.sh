#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Installs packages, builds and runs every test (GoogleTest via ctest), from a fresh Debian 12
# machine as root. It first checks clang-format and builds with -Werror. Then it pip-installs
# the Python module into a venv and uses it from outside the checkout. GL tests render headless
# on Mesa's llvmpipe through EGL; no GPU or display.
# The fuzz regression inputs replay in this suite (fuzz_regression_tests). Then the same suite
# runs under ASan + UBSan + LeakSanitizer (build-asan) and every fuzz target runs a short,
# repeatable, fixed-seed run (build-fuzz; times in docs/fuzzing.md); VOXLINK_FUZZ_SECONDS sets
# its length per target, VOXLINK_SANITIZE_AND_FUZZ=0 leaves both out.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh sample tests
# Style and warnings are part of the test: unformatted code or a compiler warning fails the run.
bash scripts/check-format.sh
# Everything, also where scripts/run-sample.sh configured ./build without tests.
bash scripts/build.sh -DVOXLINK_WERROR=ON \
  -DVOXLINK_BUILD_TESTS=ON -DVOXLINK_BUILD_BENCH=ON -DVOXLINK_BUILD_PYTHON=ON
ctest --test-dir build --output-on-failure -j "$(nproc)"
# `pip install --no-build-isolation .` into a venv, used from another folder (docs/python.md).
VOXLINK_CMAKE_ARGS=-DVOXLINK_WERROR=ON bash scripts/test-pip-install.sh
if [ "${VOXLINK_SANITIZE_AND_FUZZ:-1}" = 1 ]; then
  bash scripts/sanitize-tests.sh
  FUZZ_CI=1 bash scripts/fuzz.sh "${VOXLINK_FUZZ_SECONDS:-20}"
fi
