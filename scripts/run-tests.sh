#!/usr/bin/env bash
# Installs packages, builds and runs every test (GoogleTest via ctest), from a fresh Debian 12
# machine as root. GL tests render headless on Mesa's llvmpipe through EGL; no GPU or display.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j "$(nproc)"
