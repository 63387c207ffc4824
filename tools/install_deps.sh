#!/usr/bin/env bash
# Installs everything Bake Radiosity needs to build, test and bake on Debian (12 "bookworm").
# Safe to run again: apt-get skips what is already there.
set -euo pipefail
packages=(
  build-essential cmake
  pybind11-dev python3-dev python3-numpy
  libglm-dev libtbb-dev libembree-dev libopenvdb-dev libboost-iostreams-dev python3-openvdb
  googletest libgtest-dev libbenchmark-dev
  blender xvfb xauth xdotool
  flake8 clang-format
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  sudo=""; [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -q
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
