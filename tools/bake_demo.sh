#!/usr/bin/env bash
# The main job, end to end: build, generate the bundled Cornell box, bake it headless with the
# add-on installed from the zip, and render the baked result to build/demo.png.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD_DIR:-$root/build}
"$root/tools/build.sh"

work=$build/demo
mkdir -p "$work"
# A private Blender profile, so the demo neither needs nor changes the user's own.
export BLENDER_USER_SCRIPTS=$work/scripts BLENDER_USER_CONFIG=$work/config
blender=(blender -b --factory-startup --python-exit-code 1)

"${blender[@]}" --python-expr "import bpy
bpy.ops.preferences.addon_install(filepath='$build/bake_radiosity.zip', overwrite=True)
bpy.ops.preferences.addon_enable(module='bake_radiosity')" >/dev/null
"${blender[@]}" --python "$root/tools/make_demo_scene.py" -- "$work/cornell.blend" >/dev/null
"${blender[@]}" "$work/cornell.blend" --python-expr "import bake_radiosity.cli as c; c.main()" -- \
  --output "$work/cornell_baked.blend" --target COPIES --element-size 0.04 --resolution 256

# Workbench draws with OpenGL: give it a virtual display when there is none.
gl=()
[ -n "${DISPLAY:-}" ] || gl=(xvfb-run -a -s "-screen 0 1280x1024x24")
"${gl[@]}" "${blender[@]}" "$work/cornell_baked.blend" --python "$root/tools/render_demo.py" -- "$build/demo.png" baked >/dev/null
echo "Baked Cornell box rendered to $build/demo.png"
