"""500 point lamps in a 10 x 10 x 3 m grey room (scenes.lamp_room), baked at the defaults and by
this Blender's Cycles (the mean of two seeds; their difference measures Cycles' noise): the mean of
the floor, the ceiling and each wall within 1 % of Cycles'. The time against the one-lamp room is
measured by lab/many_lamps/measure.py (docs/benchmarks.md), not here."""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402
import numpy as np  # noqa: E402

import harness  # noqa: E402
import scenes  # noqa: E402

args = harness.arguments()
addon = harness.install_addon(args.addon_zip)

LAMPS = 500
SAMPLES_PER_SEED = 1024
MAX_ERROR = 0.01
MAX_CYCLES_NOISE = 0.004  # the seeds' means half as far apart


def test_500_lamps_light_each_surface_as_cycles():
    scenes.clear_scene()
    room = scenes.lamp_room(LAMPS, 0.0)
    seeds = np.array([harness.cycles_corner_bake(room, SAMPLES_PER_SEED, seed).mean(axis=1) for seed in (1, 2)])
    summary = addon.bake(bpy.context.scene)
    baked = harness.corner_colors(room.data, "Radiosity").mean(axis=1)
    failures = []
    for name, where in scenes.lamp_room_surfaces(harness.corner_positions(room.data)).items():
        cycles = seeds[:, where].mean(axis=1)
        error = baked[where].mean() / cycles.mean() - 1
        noise = abs(cycles[0] - cycles[1]) / 2 / cycles.mean()
        print("Blender %s, %d lamps, %s: bake %+.2f%% from Cycles (its noise %.2f%%), method %s"
              % (bpy.app.version_string, LAMPS, name, 100 * error, 100 * noise, summary["method"]), flush=True)
        assert noise < MAX_CYCLES_NOISE, "Cycles is too noisy to judge %s: %.2f%%" % (name, 100 * noise)
        if abs(error) > MAX_ERROR:
            failures.append("%s %+.2f%%" % (name, 100 * error))
    assert not failures, failures


harness.run(test_500_lamps_light_each_surface_as_cycles)
