#!/usr/bin/env bash
# Installs every Debian 12 package the build, the tests and the samples need.
# Run as root on a fresh machine; safe to run again.
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
packages=(
  build-essential cmake ninja-build pkg-config git ca-certificates
  zlib1g-dev nlohmann-json3-dev libcli11-dev libgtest-dev libgmock-dev libbenchmark-dev
  libopenvdb-dev libboost-iostreams-dev libtbb-dev libblosc-dev
  libopenimageio-dev openimageio-tools
  libgdcm-dev
  libgdcm-tools
  libnifti2-dev
  libglfw3-dev libglm-dev libepoxy-dev libegl-dev libgl-dev libgl1-mesa-dri libegl-mesa0
  libimgui-dev xvfb xauth
  python3 time ccache
  pybind11-dev python3-dev python3-numpy python3-pytest
  python3-openvdb libopenvdb-tools
  paraview python3-paraview
  clang-14 libclang-rt-14-dev clang-format-14
  libfftw3-dev libzip-dev libzstd-dev
  libopenblas-dev liblapacke-dev
  libassimp-dev libembree-dev
  r-cran-gstat
)
apt-get update
apt-get install -y --no-install-recommends "${packages[@]}"
