#!/usr/bin/env bash
# Builds the project and runs its tests inside a Debian chroot with that release's Blender
# (tools/blender_chroot.sh makes the chroot once and caches it):
#
#   tools/run_blender_tests_in.sh SUITE [CTEST ARGS...]     e.g. trixie (Blender 4.3), sid (5.x)
#
# The build goes to build-SUITE/ in this worktree (kept between runs: a warm run only rebuilds
# what changed). CTEST ARGS default to the whole suite; e.g. `-R blender_` runs only the tests
# inside Blender. Environment:
#   EMBREE=3   build against Debian 12's Embree 3 (extracted into the chroot's /opt/embree3,
#              build-SUITE-embree3/), for checking that _core does not bind to Blender's Embree 4
#   JOBS=N     build and test jobs (default: the number of cores)
#   TARGET=T   build only target T (e.g. addon_zip, enough for the tests inside Blender)
#   CACHED_BUILD=1  build inside the chroot instead, in /var/cache/bake-radiosity-build/<this
#              worktree's path, hashed> (kept with the chroot between runs on this machine: CI)
# Prints the time each phase took. Needs root (chroot).
set -euo pipefail
[ $# -ge 1 ] || { sed -n '2,16p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
suite=$1; shift
root=$(cd "$(dirname "$0")/.." && pwd)
chroot_tool=$root/tools/blender_chroot.sh
jobs=${JOBS:-$(nproc)}
build=build-$suite
extra=()
if [ "${EMBREE:-}" = 3 ]; then
  build=build-$suite-embree3
  extra=(-DRADIOSITY_EMBREE_VERSION=3 -Dembree_DIR=/opt/embree3/usr/lib/x86_64-linux-gnu/cmake/embree-3.13.5)
fi

phase_start=$(date +%s)
phase() { local now; now=$(date +%s); echo "== $1: $(( now - phase_start )) s" >&2; phase_start=$now; }

"$chroot_tool" "$suite"
phase "chroot ready ($("$chroot_tool" "$suite" path))"

if [ "${CACHED_BUILD:-}" = 1 ]; then
  # CMake ties a build directory to its source path: one directory per checkout path.
  build=/var/cache/bake-radiosity-build/$build-$(printf '%s' "$root" | sha1sum | cut -c1-12)
  echo "build directory (inside the chroot): $build" >&2
fi

if [ "${EMBREE:-}" = 3 ]; then
  dir=$("$chroot_tool" "$suite" path)
  if [ ! -f "$dir/opt/embree3/usr/include/embree3/rtcore.h" ]; then
    debs=${BAKE_RADIOSITY_CHROOTS:-/var/cache/bake-radiosity}/debs
    mkdir -p "$debs"
    ls "$debs"/libembree3-3_3.*.deb "$debs"/libembree-dev_3.*.deb >/dev/null 2>&1 \
      || (cd "$debs" && apt-get download libembree3-3 libembree-dev)  # the host's (Debian 12's) Embree 3
    rm -rf "$dir/opt/embree3.partial"
    for deb in "$debs"/libembree3-3_3.*.deb "$debs"/libembree-dev_3.*.deb; do dpkg-deb -x "$deb" "$dir/opt/embree3.partial"; done
    mv "$dir/opt/embree3.partial" "$dir/opt/embree3"
  fi
  phase "Embree 3 in /opt/embree3"
fi

# The same configure as tools/build.sh, for the chroot's /usr/bin/python3 (the Python its Blender runs).
"$chroot_tool" "$suite" run -- nice cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release \
  -DPython_EXECUTABLE=/usr/bin/python3 "${extra[@]}" >/dev/null
"$chroot_tool" "$suite" run -- nice cmake --build "$build" -j "$jobs" ${TARGET:+--target "$TARGET"}
phase "build ($build)"

status=0
"$chroot_tool" "$suite" run -- /bin/sh -c 'cd "$1" && shift && exec nice ctest --output-on-failure "$@"' sh \
  "$build" -j "$jobs" "$@" || status=$?
phase "tests"
exit $status
