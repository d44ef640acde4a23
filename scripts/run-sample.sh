#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The main job on the bundled sample, from a fresh Debian 12 machine (as root):
# installs packages, builds, converts samples/headsq, prints the footprint report, validates
# the file and renders a PNG headless (EGL on Mesa's llvmpipe: no GPU or display needed),
# measuring it against the float64 reference renderer. Results go to ./out/.
set -euo pipefail
cd "$(dirname "$0")/.."
# Only what this job needs (scripts/run-tests.sh installs and builds the rest): the packages to
# build the executable, which builds with the plugins it loads (OpenVDB for info's peer, GDCM
# for DICOM inputs, OpenImageIO for the PNG); no tests, benchmarks or Python module.
bash scripts/install-deps.sh sample
VOXLINK_TARGETS=voxlink bash scripts/build.sh \
  -DVOXLINK_BUILD_TESTS=OFF -DVOXLINK_BUILD_BENCH=OFF -DVOXLINK_BUILD_PYTHON=OFF
mkdir -p out
voxlink=build/cli/voxlink
$voxlink convert samples/headsq/headsq.nrrd --tf samples/headsq/skin-bone.tf.json -o out/headsq.vxl
$voxlink info out/headsq.vxl
$voxlink validate out/headsq.vxl
# headsq's slices run from the top of the head down, hence --up -z.
$voxlink render out/headsq.vxl -o out/headsq.png --size 512x512 --sampling trilinear --camera 200,15 --up -z --reference
echo "rendered out/headsq.png"
