#!/usr/bin/env bash
# Configures and builds the product and its tests into build/ (or $BUILD_DIR) for the Python that
# Blender runs. RADIOSITY_BUILD_LAB=ON adds the benchmarks and chart programs (lab/).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD_DIR:-$root/build}
"$root/tools/install_deps.sh"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DPython_EXECUTABLE=/usr/bin/python3 \
  -DRADIOSITY_BUILD_LAB="${RADIOSITY_BUILD_LAB:-OFF}" >/dev/null
cmake --build "$build" -j "$(nproc)"
