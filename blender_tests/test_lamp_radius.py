"""A point lamp of radius 5 cm at 3, 10 and 50 cm from a wall, baked through the panel at Medium
and by this Blender's Cycles (the mean of two seeds; their difference measures Cycles' noise):
every corner within 1 m of the lamp within 2 % of Cycles. The wall is alone, so all its light is
the lamp's, and near the lamp that is the near field of the lamp's sphere or disk: 1 / r^2 from its
centre is 3 to 100 times off there (at 3 cm the lamp reaches through the wall's plane)."""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402
import numpy as np  # noqa: E402

import harness  # noqa: E402
import scenes  # noqa: E402

args = harness.arguments()
harness.install_addon(args.addon_zip)

RADIUS = 0.05
CELLS = 40  # over 2 m: a corner every 5 cm
SAMPLES_PER_SEED = 2048
MAX_ERROR = 0.02
MAX_CYCLES_NOISE = 0.005  # per corner, well below the tolerance


def wall_and_lamp(distance):
    """A grey wall 2 x 2 m in the plane x = 0 facing +x, and a 100 W point lamp of radius 5 cm
    `distance` in front of its centre. Returns the wall and the lamp's position."""
    scenes.clear_scene()
    wall = scenes.mesh_object("Wall", [scenes.grid((0, -1, 0), (0, 2, 0), (0, 0, 2), CELLS, CELLS) + (0,)],
                              [scenes.diffuse("Grey", (0.8, 0.8, 0.8))])
    lamp = bpy.data.lights.new("Bulb", "POINT")
    lamp.energy, lamp.shadow_soft_size = 100.0, RADIUS
    lamp_object = bpy.data.objects.new("Bulb", lamp)
    lamp_object.location = (distance, 0.0, 1.0)
    bpy.context.scene.collection.objects.link(lamp_object)
    return wall, np.array(lamp_object.location)


def compare(distance):
    wall, lamp = wall_and_lamp(distance)
    seeds = np.array([harness.cycles_corner_bake(wall, SAMPLES_PER_SEED, seed).mean(axis=1) for seed in (1, 2)])
    settings = bpy.context.scene.radiosity
    settings.quality = "MEDIUM"
    assert bpy.ops.radiosity.bake() == {"FINISHED"}, settings.last_report
    assert "Radius" not in settings.last_report, settings.last_report
    baked = harness.corner_colors(wall.data, "Radiosity").mean(axis=1)
    near = np.linalg.norm(harness.corner_positions(wall.data) - lamp, axis=1) <= 1.0
    cycles = seeds.mean(axis=0)[near]
    noise = np.abs(seeds[0] - seeds[1])[near] / 2 / cycles
    error = baked[near] / cycles - 1
    worst = np.argmax(np.abs(error))
    print("Blender %s, lamp of radius %g m at %g m: %d corners within 1 m, error max %.2f%% (at %.3f of Cycles' "
          "%.4g), mean %+.2f%%, RMS %.2f%%; Cycles' noise max %.2f%%, RMS %.2f%%"
          % (bpy.app.version_string, RADIUS, distance, near.sum(), 100 * np.abs(error).max(), baked[near][worst],
             cycles[worst], 100 * error.mean(), 100 * np.sqrt(np.mean(error ** 2)), 100 * noise.max(),
             100 * np.sqrt(np.mean(noise ** 2))), flush=True)
    assert noise.max() < MAX_CYCLES_NOISE, "Cycles is too noisy to judge: %.2f%%" % (100 * noise.max())
    assert np.abs(error).max() <= MAX_ERROR, "%.2f%%" % (100 * np.abs(error).max())


def test_lamp_3_cm_from_the_wall():
    compare(0.03)


def test_lamp_10_cm_from_the_wall():
    compare(0.10)


def test_lamp_50_cm_from_the_wall():
    compare(0.50)


harness.run(test_lamp_3_cm_from_the_wall, test_lamp_10_cm_from_the_wall, test_lamp_50_cm_from_the_wall)
