"""The cluttered room's cost and light: blender_tests/scenes.cluttered_room (a 2 m room, rho 0.7,
--cells x --cells quads a side, a 50 cm panel 1 cm under the ceiling) empty and with --blocks blocks
of 2 cm on its floor, baked at --quality with the add-on's defaults one after the other: each bake's
method, elements (and unknowns solved), CPU and wall seconds, the cost line, and the walls' mean
light (area-weighted over the Room's wall faces) cluttered over empty, against Cycles' ratio (the
means of two seeds of Cycles' Combined bake of each room, cached in --truth-folder, made when
missing).

    blender -b --factory-startup --python-exit-code 1 --python lab/cluttered_room/measure.py -- \\
        --addon-zip build/bake_radiosity.zip --truth-folder /tmp/cluttered_room \\
        [--blocks 1000] [--cells 8] [--quality MEDIUM] [--samples 1024]
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "blender_tests"))

import bpy  # noqa: E402
import numpy as np  # noqa: E402

import harness  # noqa: E402
import scenes  # noqa: E402


def measure(addon, blocks, args):
    scenes.clear_scene()
    scenes.cluttered_room(blocks, cells=args.cells)
    room = bpy.data.objects["Room"]
    truth = os.path.join(args.truth_folder, "cells%d-blocks%d-%dspp.npz" % (args.cells, blocks, args.samples))
    cycles = harness.cached_cycles_bakes(room, truth, args.samples)
    with harness.Stopwatch() as seconds:
        summary = addon.bake(bpy.context.scene, quality=args.quality)
    walls = scenes.wall_light(room.data, harness.corner_colors(room.data, "Radiosity"))
    cycles_walls = [scenes.wall_light(room.data, c) for c in cycles["colors"]]
    print("%d blocks: %s, %d elements (%d solved), %.1f s wall, %.1f s CPU; walls %.4f, Cycles %.4f (seeds %.2f%% "
          "apart, %.0f s for both)" % (
              blocks, summary["method"], summary["elements"], summary.get("solve_elements", summary["elements"]),
              seconds.wall, seconds.cpu, walls, np.mean(cycles_walls),
              100 * abs(cycles_walls[0] - cycles_walls[1]) / np.mean(cycles_walls), float(cycles["seconds"])),
          flush=True)
    print("  " + bpy.context.scene.radiosity.last_cost, flush=True)
    return seconds, walls, np.mean(cycles_walls)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--addon-zip", required=True)
    parser.add_argument("--truth-folder", required=True)
    parser.add_argument("--blocks", type=int, default=1000)
    parser.add_argument("--cells", type=int, default=8)
    parser.add_argument("--quality", default="MEDIUM")
    parser.add_argument("--samples", type=int, default=1024)
    args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:])
    os.makedirs(args.truth_folder, exist_ok=True)
    addon = harness.install_addon(args.addon_zip)
    empty_seconds, empty_walls, empty_cycles = measure(addon, 0, args)
    seconds, walls, cycles = measure(addon, args.blocks, args)
    ratio, cycles_ratio = walls / empty_walls, cycles / empty_cycles
    print("walls cluttered / empty: bake %.4f, Cycles %.4f (%+.2f%%); CPU %.1fx, wall %.1fx the empty room's" % (
        ratio, cycles_ratio, 100 * (ratio / cycles_ratio - 1), seconds.cpu / empty_seconds.cpu,
        seconds.wall / empty_seconds.wall))


if __name__ == "__main__":
    main()
