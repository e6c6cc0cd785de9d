#!/bin/sh
# SPDX-License-Identifier: BSD-3-Clause
# Installs every Debian 12 package lic3d needs to build, run and test.
# Idempotent: apt-get skips what is already installed. Run as root (or with sudo).
set -eu

packages="
  ca-certificates cmake ninja-build g++ pkg-config help2man
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers
  glslang-tools glslang-dev
  libglm-dev libglfw3-dev libimgui-dev libstb-dev fonts-dejavu-core
  libcli11-dev nlohmann-json3-dev zlib1g-dev libpng-dev libpugixml-dev libgtest-dev
  xvfb xauth
  clang-14 libclang-rt-14-dev clang-format-14
  ffmpeg
  lintian
  libopenvdb-dev
  pybind11-dev python3-dev python3-numpy
  paraview paraview-dev python3-paraview openmpi-bin libopenmpi-dev libdouble-conversion-dev
"

missing=""
for p in $packages; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done

if [ -n "$missing" ]; then
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update
  # shellcheck disable=SC2086
  $sudo apt-get install -y --no-install-recommends $missing
fi
