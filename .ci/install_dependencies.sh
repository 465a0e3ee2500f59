#!/usr/bin/env bash
# Installs trigrav's build and test dependencies from Debian 12 packages, as root. Packages already
# present are skipped; apt-get update runs first whenever something has to be installed.
set -euo pipefail
packages=(
  build-essential cmake
  libeigen3-dev libceres-dev libsuitesparse-dev libgoogle-glog-dev libgflags-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  python3-matplotlib
  pybind11-dev python3-pybind11 python3-dev python3-numpy  # the Python module trigrav
  python3-pytest         # its tests
  python3-dask python3-distributed python3-tqdm  # the Dask triplet pipeline (ba/python/trigrav_pipeline)
  python3-opencv         # the Python KITTI example (SIFT); the module never uses it
  libopencv-dev          # KITTI tool only (SIFT features); the library never links it
  libopengv-dev          # optional peer rows in the comparisons; the library never links it
  libsqlite3-dev         # trigrav::colmap reads COLMAP databases
  colmap                 # CLI for the real-COLMAP tests and the experiment; the library never links it
  clang libclang-rt-14-dev  # libFuzzer and the sanitizer runtime for the hardening step
  clang-format           # the formatting check of the test suite (clang-format-14)
)
missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q 'install ok installed' ||
    missing+=("$package")
done
if ((${#missing[@]})); then
  echo "installing: ${missing[*]}"
  apt-get update
  DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}"
else
  echo "all dependencies present"
fi
