#!/usr/bin/env bash
# A Debian chroot with Python and numpy and nothing of what the native core needs (no TBB, OpenVDB,
# Embree, Boost, Imath, blosc, ...), to show that a wheel's bundled libraries are enough:
#
#   tools/packaging/minimal_chroot.sh SUITE run -- CMD...   run CMD inside, this worktree mounted
#
# Made once (debootstrap minbase + python3-numpy from the host's mirror) and cached in
# ${BAKE_RADIOSITY_CHROOTS:-/var/cache/bake-radiosity}/minimal-SUITE; built in a .partial folder and
# renamed when complete. Needs root.
set -euo pipefail
if [ $# -lt 3 ] || [ "$2" != run ] || [ "$3" != -- ]; then sed -n '2,9p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; fi
suite=$1; shift 3
root_dir=$(cd "$(dirname "$0")/../.." && pwd)
cache=${BAKE_RADIOSITY_CHROOTS:-/var/cache/bake-radiosity}
dir=$cache/minimal-$suite
mirror=${DEBIAN_MIRROR:-$(grep -hsE '^(URIs:|deb )' /etc/apt/sources.list /etc/apt/sources.list.d/* \
  | grep -oE 'https?://[^ ]+/debian/?( |$)' | grep -v security | head -n1 | tr -d ' ' || true)}

mkdir -p "$cache"
exec 9>"$dir.lock"
flock 9
if [ ! -d "$dir" ]; then
  rm -rf --one-file-system "$dir.partial"
  debootstrap --variant=minbase --include=python3,python3-numpy "$suite" "$dir.partial" "${mirror:-http://deb.debian.org/debian}" >&2
  rm -rf "$dir.partial/var/cache/apt/archives/"*.deb
  mv "$dir.partial" "$dir"
fi
flock -u 9

# shellcheck disable=SC2016  # the script inside expands its own arguments
unshare --mount --propagation private -- /bin/bash -euo pipefail -c '
  dir=$1 bind=$2; shift 2
  mount -t proc proc "$dir/proc"
  mount --rbind /dev "$dir/dev"
  mkdir -p "$dir$bind"; mount --bind "$bind" "$dir$bind"
  exec chroot "$dir" /usr/bin/env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root LANG=C.UTF-8 \
    /bin/sh -c "cd \"\$0\" && exec \"\$@\"" "$bind" "$@"
' minimal "$dir" "$root_dir" "$@"
