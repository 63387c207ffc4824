"""Soft shadows as Cycles casts them: a 40 cm block on a 3 x 3 m floor under a sun of angle 20
degrees and under a point lamp of radius 20 cm, baked at Medium and by this Blender's Cycles (the
mean of two seeds). The floor's corners that get any direct light, the penumbrae among them:
RMS within 2 % of Cycles (its noise taken out), mean within 1 %."""

import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402
import numpy as np  # noqa: E402

import harness  # noqa: E402
import scenes  # noqa: E402

args = harness.arguments()
harness.install_addon(args.addon_zip)

SIZE, CELLS = 3.0, 60  # a corner every 5 cm
SAMPLES_PER_SEED = 1024
MAX_RMS, MAX_MEAN = 0.02, 0.01


def floor_and_block():
    scenes.clear_scene()
    grey = scenes.diffuse("Grey", (0.5, 0.5, 0.5))
    floor = scenes.mesh_object("Floor", [scenes.grid((0, 0, 0), (SIZE, 0, 0), (0, SIZE, 0), CELLS, CELLS) + (0,)],
                               [grey])
    scenes.mesh_object("Block", scenes.block((1.3, 1.3), (1.7, 1.7), 0.4, 0.1), [grey])
    return floor


def add_lamp(kind):
    lamp = bpy.data.lights.new(kind.title(), kind)
    obj = bpy.data.objects.new(lamp.name, lamp)
    if kind == "SUN":
        lamp.energy, lamp.angle = 3.0, math.radians(20.0)
        obj.rotation_euler = (math.radians(45.0), 0.0, math.radians(30.0))
    else:
        lamp.energy, lamp.shadow_soft_size = 300.0, 0.2
        obj.location = (1.2, 1.1, 1.0)
    bpy.context.scene.collection.objects.link(obj)


def compare(kind):
    floor = floor_and_block()
    add_lamp(kind)
    seeds = np.array([harness.cycles_corner_bake(floor, SAMPLES_PER_SEED, seed).mean(axis=1) for seed in (1, 2)])
    settings = bpy.context.scene.radiosity
    settings.quality = "MEDIUM"
    assert bpy.ops.radiosity.bake() == {"FINISHED"}, settings.last_report
    baked = harness.corner_colors(floor.data, "Radiosity").mean(axis=1)
    cycles = seeds.mean(axis=0)
    lit = cycles > 0.05 * cycles.max()
    relative = (baked - cycles)[lit] / cycles[lit]
    noise = np.sqrt(np.mean(((seeds[0] - seeds[1])[lit] / 2 / cycles[lit]) ** 2))
    rms = math.sqrt(max(np.mean(relative ** 2) - noise ** 2, 0.0))
    mean = baked[lit].mean() / cycles[lit].mean() - 1
    print("Blender %s, %s: %d lit corners, RMS %.2f%% (Cycles' noise %.2f%% taken out), max %.1f%%, mean %+.2f%%"
          % (bpy.app.version_string, kind.lower(), lit.sum(), 100 * rms, 100 * noise, 100 * np.abs(relative).max(),
             100 * mean), flush=True)
    assert rms <= MAX_RMS and abs(mean) <= MAX_MEAN, (rms, mean)


def test_sun_with_an_angle():
    compare("SUN")


def test_point_lamp_with_a_radius():
    compare("POINT")


harness.run(test_sun_with_an_angle, test_point_lamp_with_a_radius)
