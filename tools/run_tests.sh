#!/usr/bin/env bash
# Builds and runs every test: C++ (GoogleTest), the Python binding, and the tests inside Blender.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD_DIR:-$root/build}
"$root/tools/build.sh"
cd "$build"
ctest --output-on-failure -j "$(nproc)" "$@"
