"""The Cornell box of blender_tests/scenes.py with its walls subdivided (the scene and its light
unchanged), baked at a preset: how the bake's time grows with the vertices (issue: cost that follows
the light, not the mesh). Run inside Blender:

    BLENDER_USER_SCRIPTS=$(mktemp -d) BLENDER_USER_CONFIG=$(mktemp -d) \\
      blender -b --factory-startup --python-exit-code 1 --python lab/dense_cornell/measure.py -- \\
        --addon-zip build/bake_radiosity.zip [--cells 8,16,32] [--quality MEDIUM]
"""

import argparse
import os
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "blender_tests"))

import bpy  # noqa: E402

import harness  # noqa: E402
import scenes  # noqa: E402


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--addon-zip", required=True)
    parser.add_argument("--cells", default="8,16,32", help="quads per wall edge (8: the test scene's own)")
    parser.add_argument("--quality", default="MEDIUM")
    args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:])
    addon = harness.install_addon(args.addon_zip)
    for cells in [int(c) for c in args.cells.split(",")]:
        scenes.clear_scene()
        box = scenes.cornell_box(cells=cells)
        wall, cpu = time.perf_counter(), time.process_time()
        summary = addon.bake(bpy.context.scene, quality=args.quality)
        phases = {k: round(v, 1) for k, v in summary["seconds"].items() if v >= 0.05}
        print("%d cells, %d vertices: %s, %d elements, %.1f wall s, %.1f CPU s, load %.1f; %s"
              % (cells, len(box.data.vertices), summary["method"], summary["elements"], time.perf_counter() - wall,
                 time.process_time() - cpu, os.getloadavg()[0], phases), flush=True)


main()
