#!/usr/bin/env bash
# The demo, as an artist with a newer Blender gets it: in the chroot of SUITE (tools/blender_chroot.sh),
# installs the extension package from build/packages/ with Blender's command line into fresh user
# folders, bakes the bundled Cornell box with the batch command and renders it:
#
#   tools/packaging/bake_demo_in.sh trixie|sid        -> build/packages/demo-SUITE.png
#
# Run tools/build_packages.sh first. Needs root (chroot).
# shellcheck disable=SC2016  # the script inside the chroot expands its own variables
set -euo pipefail
[ $# -eq 1 ] || { sed -n '2,8p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
suite=$1
root=$(cd "$(dirname "$0")/../.." && pwd)
cd "$root"
for file in build/packages/bake_radiosity-*-linux_x64.zip; do
  case $file in *-legacy-*) ;; *) package=$file ;; esac
done
[ -n "${package:-}" ] || { echo "no extension package in build/packages: run tools/build_packages.sh" >&2; exit 1; }
work=$root/build/packages/demo-$suite
rm -rf "$work"; mkdir -p "$work"
"$root/tools/blender_chroot.sh" "$suite" run -- env BLENDER_USER_CONFIG="$work/config" \
  BLENDER_USER_SCRIPTS="$work/scripts" BLENDER_USER_EXTENSIONS="$work/extensions" /bin/sh -exc '
  package=$1 work=$2
  blender --command extension install-file -r user_default -e "$package"
  blender -b --python tools/make_demo_scene.py -- "$work/cornell.blend" >/dev/null
  blender -b "$work/cornell.blend" --command bake_radiosity --output "$work/cornell_baked.blend" \
    --target COPIES --element-size 0.04 --resolution 256
  xvfb-run -a -s "-screen 0 1280x1024x24" blender -b "$work/cornell_baked.blend" --python tools/render_demo.py -- \
    "$work/../demo-'"$suite"'.png" baked >/dev/null
' sh "$package" "$work"
echo "Baked with the extension in the $suite chroot's Blender: build/packages/demo-$suite.png"
