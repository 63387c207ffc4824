"""Re-bakes of the Cornell box of blender_tests/scenes.py under 8 point lamps at a preset, one lamp moved
by 1 cm before each, to profile what a re-bake does; prints the last one's phases and its gather's.
Run inside Blender, under a profiler if wanted:

    BLENDER_USER_SCRIPTS=$(mktemp -d) BLENDER_USER_CONFIG=$(mktemp -d) perf record -g -o perf.data \\
      blender -b --factory-startup --python-exit-code 1 --python lab/rebake/rebakes.py -- \\
        --addon-zip build/bake_radiosity.zip [--count 15] [--quality MEDIUM]

(`_core` in the zip is stripped: link an unstripped copy from build/native/python's link line, whose
build id is the same, and `perf buildid-cache -a` it.)
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "blender_tests"))

import bpy  # noqa: E402

import harness  # noqa: E402
import scenes  # noqa: E402


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--addon-zip", required=True)
    parser.add_argument("--count", type=int, default=15)
    parser.add_argument("--quality", default="MEDIUM")
    args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:])
    addon = harness.install_addon(args.addon_zip)
    scenes.cornell_box_under_lamps(8)
    lamp = sorted((o for o in bpy.context.scene.objects if o.type == "LIGHT"), key=lambda o: o.name)[0]
    summary = addon.bake(bpy.context.scene, quality=args.quality)
    for _ in range(args.count):
        lamp.location = tuple(a + b for a, b in zip(lamp.location, (0.01, 0.0, 0.0)))
        summary = addon.bake(bpy.context.scene, quality=args.quality)
    print("phases", {k: round(v, 3) for k, v in summary["seconds"].items()})
    print("gather", summary["gather"])


main()
