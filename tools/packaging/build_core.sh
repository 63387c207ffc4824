#!/usr/bin/env bash
# Builds only the native module _core, for one environment's Python, into build-packages/ENV/:
#
#   tools/packaging/build_core.sh host      Debian 12 here: Python 3.11
#   tools/packaging/build_core.sh trixie    the trixie chroot (tools/blender_chroot.sh): Python 3.13
#   tools/packaging/build_core.sh sid       the sid chroot: Python 3.14
#
# Prints the module's path. JOBS=N build jobs (default: the number of cores).
set -euo pipefail
[ $# -eq 1 ] || { sed -n '2,8p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
env=$1
root=$(cd "$(dirname "$0")/../.." && pwd)
build=build-packages/$env
in_env=()
if [ "$env" = host ]; then "$root/tools/install_deps.sh"; else in_env=("$root/tools/blender_chroot.sh" "$env" run --); fi
cd "$root"
"${in_env[@]}" nice cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DPython_EXECUTABLE=/usr/bin/python3 \
  -DRADIOSITY_BUILD_TESTS=OFF -DRADIOSITY_BLENDER_TESTS=OFF >&2
"${in_env[@]}" nice cmake --build "$build" -j "${JOBS:-$(nproc)}" --target _core >&2
ls "$root/$build"/addon/bake_radiosity/_core.*.so
