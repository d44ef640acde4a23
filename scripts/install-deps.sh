#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Installs the Debian 12 packages for one or both jobs; run as root, safe to run again.
#   bash scripts/install-deps.sh sample        # the main job (scripts/run-sample.sh)
#   bash scripts/install-deps.sh sample tests  # everything: build all, run every test
# `sample` is what building the `voxlink` executable (CMake finds every library at configure
# time) and running it on samples/headsq need: the OpenVDB plugin for `info`'s peer, the
# OpenImageIO plugin for the PNG (OpenImageIO's CMake config also wants its tools' binaries),
# EGL on Mesa for the headless render, OpenBLAS/LAPACKE for Kriging, pugixml for the .vti/.vvd
# headers, nanoflann for Kriging's k-d tree, Imath for half floats. `tests` adds the test
# frameworks, tools the tests call, Python, ParaView, clang, R and Open MPI (the build enables
# MPI when it finds Open MPI; without it `voxlink` is the same program minus mpirun support).
# matplotlib and the zstd tool are for bench/report.py and its ctest (docs/report.md); scipy is
# for bench/neighbour_set_changes.py (docs/kriging.md). xdotool drags with the mouse in the viewer
# under Xvfb (tests/viewer/drag_smoke_test.sh).
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
sample=(
  build-essential cmake ninja-build pkg-config ccache
  zlib1g-dev nlohmann-json3-dev libcli11-dev
  libopenvdb-dev libboost-iostreams-dev libtbb-dev libblosc-dev
  libopenimageio-dev openimageio-tools
  libgdcm-dev
  libnifti2-dev
  libglfw3-dev libglm-dev libepoxy-dev libegl-dev libgl-dev libopengl-dev libgl1-mesa-dri
  libegl-mesa0
  libimgui-dev
  libfftw3-dev libzip-dev libzstd-dev
  libassimp-dev libembree-dev
  libopenblas-dev liblapacke-dev
  libpugixml-dev libnanoflann-dev libimath-dev
)
tests=(
  git ca-certificates time file
  libgtest-dev libgmock-dev libbenchmark-dev
  libgdcm-tools
  xvfb xauth xdotool
  python3 pybind11-dev python3-dev python3-numpy python3-pytest
  python3-venv python3-pip python3-setuptools python3-wheel
  python3-pydicom
  libopenmpi-dev openmpi-bin
  python3-openvdb libopenvdb-tools
  paraview python3-paraview
  clang-14 libclang-rt-14-dev clang-format-14
  r-cran-gstat
  python3-matplotlib zstd python3-scipy
)
if [ $# -eq 0 ]; then
  echo "usage: $0 sample [tests]" >&2
  exit 2
fi
packages=()
for set in "$@"; do
  case "$set" in
    sample) packages+=("${sample[@]}") ;;
    tests) packages+=("${tests[@]}") ;;
    *)
      echo "$0: unknown package set '$set' (sample, tests)" >&2
      exit 2
      ;;
  esac
done
apt-get update
apt-get install -y --no-install-recommends "${packages[@]}"
