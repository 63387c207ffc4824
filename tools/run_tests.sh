#!/usr/bin/env bash
# Builds, checks the Python style (.flake8) and runs every test: C++ (GoogleTest), the Python
# binding, and the tests inside Blender.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD_DIR:-$root/build}
"$root/tools/build.sh"
"$root/tools/check_style.sh"
cd "$build"
ctest --output-on-failure -j "$(nproc)" "$@"
