#!/usr/bin/env bash
# Installs every Debian 12 package needed to build and test ASM for VTK/ParaView.
# Safe to run again: packages already present are skipped. Needs root (or sudo).
set -euo pipefail

PKGS=(
  # toolchain
  build-essential cmake ninja-build pkg-config
  # ParaView 5.11 with its own VTK 9.2, Python bindings, Eigen, GoogleTest
  paraview paraview-dev python3-paraview libeigen3-dev libgtest-dev googletest
  # packages paraview-dev's CMake config needs but does not pull in
  qtbase5-dev qttools5-dev libqt5svg5-dev qtxmlpatterns5-dev-tools libqt5opengl5-dev
  libhdf5-openmpi-dev libnetcdf-dev libgdal-dev libboost-dev libutfcpp-dev
  libdouble-conversion-dev libtiff-dev libtheora-dev libglew-dev libgl2ps-dev
  libavcodec-dev libavformat-dev libavutil-dev libswscale-dev
  libopenmpi-dev python3-mpi4py libxt-dev
  # libFuzzer target (scripts/fuzz.sh): clang with its sanitizer/fuzzer runtimes
  clang-14 libclang-rt-14-dev
  # the format check (scripts/check-format.sh, CTest format.ClangFormat)
  clang-format-14
  # headless runs of pvpython / pvbatch / paraview
  xvfb xauth libgl1-mesa-dri   # Xvfb + Mesa llvmpipe (software OpenGL) for the gui tests
  # header-only CGAL: the CGAL peers of the quality benchmark (Benchmarks/)
  libcgal-dev
  # TBB, the vtkSMPTools backend of Debian's own VTK 9.1 (scripts/fetch-vtk91.sh)
  libtbb-dev
)

missing=()
for p in "${PKGS[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PKGS[@]} packages already installed"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install-deps: installing ${#missing[@]} packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
