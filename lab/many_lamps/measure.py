"""Many lamps against one: blender_tests/scenes.lamp_room (a 10 x 10 x 3 m grey room) lit by
--lamps point lamps of --radius, 1,000 W in all. Bakes at the add-on's defaults, times the bake
and its phases, and compares the mean of the floor, the ceiling and each wall with Cycles'
Combined bake (the mean of two seeds, cached in --truth, made when the file is missing).

    blender -b --factory-startup --python-exit-code 1 --python lab/many_lamps/measure.py -- \\
        --addon-zip build/bake_radiosity.zip --lamps 500 --truth /tmp/many_lamps/500.npz \\
        [--radius 0.05] [--samples 1024]
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
    parser.add_argument("--lamps", type=int, default=500)
    parser.add_argument("--radius", type=float, default=0.0)
    parser.add_argument("--truth", required=True)
    parser.add_argument("--samples", type=int, default=1024)
    args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:])
    addon = harness.install_addon(args.addon_zip)
    scenes.clear_scene()
    room = scenes.lamp_room(args.lamps, args.radius)
    reference = harness.cached_cycles_bakes(room, args.truth, args.samples)
    seeds = reference["colors"].mean(axis=2)  # grey per corner, per seed
    with harness.Stopwatch() as seconds:
        summary = addon.bake(bpy.context.scene)
    baked = harness.corner_colors(room.data, "Radiosity").mean(axis=1)
    print("%d lamps of radius %g m: bake %.1f s wall, %.1f s CPU; %d elements, method %s; phases %s" % (
        args.lamps, args.radius, seconds.wall, seconds.cpu, summary["elements"], summary["method"],
        {k: round(v, 2) for k, v in summary.get("seconds", {}).items()}))
    worst = 0.0
    for name, where in scenes.lamp_room_surfaces(harness.corner_positions(room.data)).items():
        cycles = seeds[:, where].mean(axis=1)
        ratio = baked[where].mean() / cycles.mean() - 1
        worst = max(worst, abs(ratio))
        print("%-10s bake %.4f, Cycles %.4f (seeds %.2f%% apart): %+.2f%%" % (
            name, baked[where].mean(), cycles.mean(), 100 * abs(cycles[0] - cycles[1]) / cycles.mean(), 100 * ratio))
    print("worst surface %.2f%%; Cycles %d samples x 2 took %.0f s" % (
        100 * worst, int(reference["samples"]), float(reference["seconds"])))


if __name__ == "__main__":
    main()
