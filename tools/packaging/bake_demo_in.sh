#!/usr/bin/env bash
# The demo, as an artist gets it from build/packages/: installs the package into fresh user
# folders with Blender's command line, bakes the bundled Cornell box with the batch command and
# renders it (Workbench under Xvfb):
#
#   tools/packaging/bake_demo_in.sh trixie|sid   the extension, in that chroot's Blender (4.3, 5.2):
#                                                `--command extension install-file`, `--command bake_radiosity`
#   tools/packaging/bake_demo_in.sh host         the legacy zip in the host's Blender 3.4: addon_install,
#                                                the `--python-expr` form
#
# Writes build/packages/demo-ENV.png and build/packages/demo-ENV/cornell_baked.blend (compare the
# bakes with tools/packaging/compare_bakes.py). Run tools/build_packages.sh first. Needs root (chroot).
# shellcheck disable=SC2016  # the script run in the environment expands its own arguments
set -euo pipefail
[ $# -eq 1 ] || { sed -n '2,13p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
env=$1
root=$(cd "$(dirname "$0")/../.." && pwd)
cd "$root"
for file in build/packages/bake_radiosity-*-linux_x64.zip; do
  case $file in *-legacy-*) legacy=$file ;; *) extension=$file ;; esac
done
if [ "$env" = host ]; then package=${legacy:-}; else package=${extension:-}; fi
if [ -z "$package" ]; then echo "no package for $env in build/packages: run tools/build_packages.sh" >&2; exit 1; fi
work=$root/build/packages/demo-$env
rm -rf "$work"; mkdir -p "$work"
homes=(BLENDER_USER_CONFIG="$work/config" BLENDER_USER_SCRIPTS="$work/scripts" BLENDER_USER_EXTENSIONS="$work/extensions")

if [ "$env" = host ]; then
  env "${homes[@]}" /bin/sh -ec '
    package=$1 work=$2
    blender -b --factory-startup --python-exit-code 1 --python-expr \
      "import bpy; bpy.ops.preferences.addon_install(filepath=\"$package\")" >/dev/null
    blender -b --factory-startup --python tools/make_demo_scene.py -- "$work/cornell.blend" >/dev/null
    blender -b --factory-startup "$work/cornell.blend" --python-exit-code 1 \
      --python-expr "import bake_radiosity.cli as c; c.main()" -- \
      --output "$work/cornell_baked.blend" --target COPIES --element-size 0.04 --resolution 256
  ' sh "$root/$package" "$work"
else
  tools/blender_chroot.sh "$env" run -- env "${homes[@]}" /bin/sh -ec '
    package=$1 work=$2
    blender --command extension install-file -r user_default -e "$package"
    blender -b --python tools/make_demo_scene.py -- "$work/cornell.blend" >/dev/null
    blender -b "$work/cornell.blend" --command bake_radiosity \
      --output "$work/cornell_baked.blend" --target COPIES --element-size 0.04 --resolution 256
  ' sh "$root/$package" "$work"
fi

render=(xvfb-run -a -s "-screen 0 1280x1024x24" blender -b "$work/cornell_baked.blend" --python tools/render_demo.py --
        "$work.png" baked)
if [ "$env" = host ]; then "${render[@]}" >/dev/null; else tools/blender_chroot.sh "$env" run -- "${render[@]}" >/dev/null; fi
echo "Baked in the $env Blender: build/packages/demo-$env.png"
