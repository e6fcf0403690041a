#!/usr/bin/env bash
# Unpacks Debian 12's own VTK 9.1 (not installed: its packages conflict with
# ParaView's through python3-vtk9) into build-deps/vtk-9.1/, so that the module
# can be built and tested against the oldest VTK it supports, with that VTK's
# default vtkSMPTools backend (TBB). Needs root (or sudo) for apt.
#
#   bash scripts/fetch-vtk91.sh        # prints the VTK_DIR to configure with
#
# Then: LD_LIBRARY_PATH=build-deps/vtk-9.1/usr/lib/x86_64-linux-gnu for the
# build (GoogleTest lists the tests by running them) and the tests; sourcing
# scripts/vtk91-env.sh does both and sets PYTHONPATH.
# Packages: libvtk9.1 (the libraries), libvtk9-dev (headers, CMake config),
# vtk9 (the wrapping tools the config names) and python3-vtk9 (its Python
# targets, which the config checks for); libtbb-dev, which that VTK's TBB
# backend needs, is installed for real (no conflict) by install-deps.sh.
# Already unpacked: nothing is fetched.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

prefix="$PWD/build-deps/vtk-9.1"
vtk_dir="$prefix/usr/lib/x86_64-linux-gnu/cmake/vtk-9.1"
if [ -f "$vtk_dir/vtk-config.cmake" ] && [ -f "$prefix/.complete" ]; then
  echo "$vtk_dir"
  exit 0
fi

# (The project's packages, libtbb-dev among them, for that VTK's TBB backend.)
bash scripts/install-deps.sh >&2
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi

debs="$PWD/build-deps/debs"
rm -rf "$prefix" "$debs"
mkdir -p "$prefix" "$debs"
packages=(libvtk9.1 libvtk9-dev vtk9 python3-vtk9)
# (apt-get download writes to the current directory, as the _apt user when it
# can: a root-owned directory only draws a warning.)
if ! (cd "$debs" && apt-get download "${packages[@]}" >&2 2>/dev/null); then
  $SUDO apt-get update -q >&2
  (cd "$debs" && apt-get download "${packages[@]}" >&2)
fi
for deb in "$debs"/*.deb; do
  dpkg-deb -x "$deb" "$prefix"
done
rm -rf "$debs"
test -f "$vtk_dir/vtk-config.cmake"
touch "$prefix/.complete"
echo "$vtk_dir"
