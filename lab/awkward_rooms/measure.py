"""Awkward rooms against Cycles: the 2 m room of blender_tests/scenes.cluttered_room (rho 0.7, a
50 cm emitting panel 1 cm under the ceiling) with its panel shrunk to a small emitter of the same
power, with an L-shaped rug on its floor, or with many 2 cm blocks on its floor. The room has 8 x 8
quads a side, so that its corners sample the light. Bakes with the add-on's defaults (or a preset)
and compares the room's corners with Cycles' Combined bake of the room, the mean of two seeds
(unbiased light paths); the truth is cached in --truth and made when the file is missing.

    blender -b --factory-startup --python-exit-code 1 --python lab/awkward_rooms/measure.py -- \\
        --addon-zip build/bake_radiosity.zip --scene small-emitter --truth /tmp/awkward/small.npz \\
        [--samples 16384] [--quality MEDIUM] [--no-final-gather]
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "blender_tests"))

import bpy  # noqa: E402
import numpy as np  # noqa: E402

import harness  # noqa: E402
import scenes  # noqa: E402

PANEL_WATTS_RADIANCE = 10.0 * 0.25  # the panel's radiance x its area


def build(scene, emitter_side, blocks):
    scenes.clear_scene()
    scenes.cluttered_room(blocks, cells=8)
    panel = bpy.data.objects["Panel"]
    if scene == "small-emitter":  # the panel shrunk about its centre, its radiance raised to keep its power
        panel.data.transform(_scale_about((1.0, 1.0, 1.99), emitter_side / 0.5))
        strength = panel.active_material.node_tree.nodes["Emission"].inputs["Strength"]
        strength.default_value = PANEL_WATTS_RADIANCE / emitter_side ** 2
    if scene == "rug":
        z = 0.005
        outline = np.array([(0.4, 0.4, z), (1.6, 0.4, z), (1.6, 0.8, z), (0.8, 0.8, z), (0.8, 1.6, z), (0.4, 1.6, z)])
        scenes.mesh_object("Rug", [(outline, np.arange(6)[None, :], 0)], [scenes.diffuse("Red", (0.6, 0.1, 0.1))])
    return bpy.data.objects["Room"]


def _scale_about(centre, factor):
    from mathutils import Matrix
    return Matrix.Translation(centre) @ Matrix.Scale(factor, 4) @ Matrix.Translation([-c for c in centre])


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--addon-zip", required=True)
    parser.add_argument("--scene", choices=["small-emitter", "rug", "cluttered"], required=True)
    parser.add_argument("--emitter-side", type=float, default=0.01)
    parser.add_argument("--blocks", type=int, default=1000)
    parser.add_argument("--truth", required=True)
    parser.add_argument("--samples", type=int, default=4096)
    parser.add_argument("--quality", default="MEDIUM")
    parser.add_argument("--no-final-gather", dest="final_gather", action="store_false")
    args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:])
    addon = harness.install_addon(args.addon_zip)
    room = build(args.scene, args.emitter_side, args.blocks if args.scene == "cluttered" else 0)
    reference = harness.cached_cycles_bakes(room, args.truth, args.samples)
    halves = reference["colors"].mean(axis=2)  # grey per corner, per seed
    cycles = halves.mean(axis=0)

    with harness.Stopwatch() as seconds:
        summary = addon.bake(bpy.context.scene, quality=args.quality, final_gather=args.final_gather)
    wall, cpu = seconds.wall, seconds.cpu
    baked = harness.corner_colors(room.data, "Radiosity").mean(axis=1)

    positions = harness.corner_positions(room.data)
    hot = cycles > 20 * np.median(cycles)  # the spot over a small emitter: judged on its own below
    judged = ~hot & (cycles > 0.01 * cycles.mean())
    c = cycles[judged]
    noise = np.sqrt(np.mean(((halves[0] - halves[1])[judged] / 2 / c) ** 2))
    rms = np.sqrt(np.mean(((baked[judged] - c) / c) ** 2))
    print("scene %s, %s, gather %s: %d elements, method %s, resolution %d; bake %.1f s wall, %.1f s CPU "
          "(this process); Cycles %d samples x 2 took %.0f s" % (
              args.scene, args.quality, args.final_gather, summary["elements"], summary["method"],
              summary["resolution"], wall, cpu, int(reference["samples"]), float(reference["seconds"])))
    print("per corner: RMS %.2f%% against Cycles, whose own noise is %.2f%% (%.2f%% with it taken out)" % (
        100 * rms, 100 * noise, 100 * np.sqrt(max(rms ** 2 - noise ** 2, 0.0))))
    surfaces = {"floor": positions[:, 2] < 1e-6, "ceiling": positions[:, 2] > 2 - 1e-6}
    surfaces["walls"] = ~surfaces["floor"] & ~surfaces["ceiling"]
    for name, where in surfaces.items():
        where = where & ~hot
        seeds = halves[:, where].mean(axis=1)
        print("%-8s mean: bake %.4f, Cycles %.4f (seeds %.2f%% apart), ratio %.4f" % (
            name, baked[where].mean(), seeds.mean(), 100 * abs(seeds[0] - seeds[1]) / seeds.mean(),
            baked[where].mean() / seeds.mean()))
    if hot.any():
        print("hot spot (%d corners): bake %.4g, Cycles %.4g" % (hot.sum(), baked[hot].mean(), cycles[hot].mean()))
    print("energy:", summary["energy"])


if __name__ == "__main__":
    main()
