#!/usr/bin/env bash
# A Debian chroot with a distribution Blender and the build dependencies, for running the build and
# the tests against a newer Blender than the host's (trixie: Blender 4.3, sid: Blender 5.x).
#
#   tools/blender_chroot.sh SUITE                 create the chroot unless it is there and complete
#   tools/blender_chroot.sh SUITE run -- CMD...   run CMD inside it (creating it first if needed), with
#                                                 /proc, /sys, /dev and this worktree mounted
#   tools/blender_chroot.sh SUITE path            print the chroot's directory
#   tools/blender_chroot.sh SUITE remove          delete the chroot
#
# The chroot is made once and cached outside the repository, in
# ${BAKE_RADIOSITY_CHROOTS:-/var/cache/bake-radiosity}/chroot-SUITE. It is built in
# chroot-SUITE.partial and renamed only when everything is installed, with a stamp naming the
# package list, so an interrupted run leaves no chroot that looks usable: the next run starts over.
# A changed package list (below) rebuilds it. Packages come from the mirror the host's apt uses
# (or $DEBIAN_MIRROR).
#
# Every mount is made in a private mount namespace (unshare -m) that dies with the command, so
# nothing stays mounted after the command ends, fails or is killed. Needs root.
set -euo pipefail

usage() { sed -n '2,10p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
[ $# -ge 1 ] || usage
suite=$1; shift
case $suite in trixie|sid|forky|testing|unstable) ;; *) echo "unknown suite: $suite" >&2; usage ;; esac
action=${1:-create}; [ $# -eq 0 ] || shift

root_dir=$(cd "$(dirname "$0")/.." && pwd)
cache=${BAKE_RADIOSITY_CHROOTS:-/var/cache/bake-radiosity}
dir=$cache/chroot-$suite
partial=$dir.partial

packages=(
  blender python3-numpy python3-cattr python3-requests xvfb xauth xdotool
  build-essential cmake pybind11-dev python3-dev libglm-dev libtbb-dev libembree-dev
  libopenvdb-dev libboost-iostreams-dev python3-openvdb googletest libgtest-dev
  ca-certificates
)
stamp_text="bake-radiosity chroot v1: ${packages[*]}"
stamp=.bake-radiosity-complete

[ "$(id -u)" -eq 0 ] || { echo "blender_chroot.sh needs root (debootstrap, chroot, mount)" >&2; exit 1; }

host_mirror() {
  if [ -n "${DEBIAN_MIRROR:-}" ]; then echo "$DEBIAN_MIRROR"; return; fi
  local m
  m=$(grep -hsE '^(URIs:|deb )' /etc/apt/sources.list /etc/apt/sources.list.d/*.sources /etc/apt/sources.list.d/*.list \
      | grep -oE 'https?://[^ ]+/debian/?( |$)' | grep -v security | head -n1 | tr -d ' ')
  echo "${m:-http://deb.debian.org/debian}"
}

complete() { [ -f "$1/$stamp" ] && [ "$(cat "$1/$stamp")" = "$stamp_text" ]; }

# Runs "$@" (a shell snippet's arguments) inside chroot $1 in a private mount namespace with the
# pseudo file systems and, if $2 is non-empty, the worktree mounted at its own path.
in_chroot() {
  local target=$1 bind=$2; shift 2
  unshare --mount --propagation private -- /bin/bash -euo pipefail -c '
    target=$1 bind=$2; shift 2
    mount -t proc proc "$target/proc"
    mount -t sysfs sysfs "$target/sys"
    mount --rbind /dev "$target/dev"
    mount -t tmpfs tmpfs "$target/dev/shm"
    if [ -n "$bind" ]; then mkdir -p "$target$bind"; mount --bind "$bind" "$target$bind"; fi
    cp -L /etc/resolv.conf "$target/etc/resolv.conf" 2>/dev/null || true
    exec chroot "$target" /usr/bin/env -i PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
      HOME=/root LANG=C.UTF-8 TERM="${TERM:-dumb}" DEBIAN_FRONTEND=noninteractive "$@"
  ' in_chroot "$target" "$bind" "$@"
}

create() {
  mkdir -p "$cache"
  exec 9>"$cache/chroot-$suite.lock"
  flock 9
  if complete "$dir"; then return 0; fi
  if [ -e "$dir" ]; then echo "chroot $dir is incomplete or outdated: making it again" >&2; rm -rf --one-file-system "$dir"; fi
  rm -rf --one-file-system "$partial"
  command -v debootstrap >/dev/null || { apt-get update -q && DEBIAN_FRONTEND=noninteractive apt-get install -y -q debootstrap; }
  local mirror start; mirror=$(host_mirror); start=$(date +%s)
  echo "debootstrap $suite from $mirror into $partial" >&2
  debootstrap --variant=minbase --components=main "$suite" "$partial" "$mirror" >&2
  # sid's Release file can be past its Valid-Until on a mirror snapshot; services must not start.
  printf 'Acquire::Check-Valid-Until "false";\nAPT::Install-Recommends "false";\n' > "$partial/etc/apt/apt.conf.d/90bake-radiosity"
  printf '#!/bin/sh\nexit 101\n' > "$partial/usr/sbin/policy-rc.d"; chmod +x "$partial/usr/sbin/policy-rc.d"
  echo "deb $mirror $suite main" > "$partial/etc/apt/sources.list"
  ln -sfn ../proc/self/mounts "$partial/etc/mtab"  # Blender asks for the mounted file systems
  # Blender is installed by apt after the base system: debootstrap cannot resolve sid's virtual
  # packages (libopenexr-…-imath-…).
  in_chroot "$partial" "" /bin/sh -ec "apt-get update -q && apt-get install -y -q ${packages[*]} && apt-get clean" >&2
  echo "$stamp_text" > "$partial/$stamp"
  mv "$partial" "$dir"
  echo "chroot $dir made in $(( $(date +%s) - start )) s, $(du -sh --one-file-system "$dir" | cut -f1)" >&2
}

case $action in
  create) create ;;
  path) echo "$dir" ;;
  remove)
    mkdir -p "$cache"; exec 9>"$cache/chroot-$suite.lock"; flock 9
    rm -rf --one-file-system "$dir" "$partial" ;;
  run)
    [ "${1:-}" = "--" ] && shift
    [ $# -ge 1 ] || usage
    complete "$dir" || create
    [ -e "$dir/etc/mtab" ] || ln -sfn ../proc/self/mounts "$dir/etc/mtab"  # chroots made before it was added
    in_chroot "$dir" "$root_dir" /bin/sh -c 'cd "$0" && exec "$@"' "$root_dir" "$@"
    ;;
  *) usage ;;
esac
