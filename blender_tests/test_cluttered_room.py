"""The cluttered room's light against Cycles', both in this test: scenes.cluttered_room (a 2 m room of
8 x 8 quads a side, rho 0.7, a 50 cm panel 1 cm under the ceiling) empty and with 1,000 blocks of
2 cm scattered on its floor, baked at Medium with the add-on's defaults and by Cycles (two seeds of
1,024 samples). The blocks take light from the walls (about 3% here); the bake must find the walls'
light cluttered over empty within 1% of Cycles' ratio. (Its time against the empty room's:
lab/cluttered_room/measure.py, docs/benchmarks.md.)"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402
import numpy as np  # noqa: E402

import harness  # noqa: E402
import scenes  # noqa: E402

args = harness.arguments()
addon = harness.install_addon(args.addon_zip)

SAMPLES, SEEDS = 1024, (1, 2)


def room_walls(blocks):
    """The walls' light of the room with `blocks` blocks: the bake's summary and light, and each
    Cycles seed's light."""
    scenes.clear_scene()
    scenes.cluttered_room(blocks, cells=8)
    room = bpy.data.objects["Room"]
    cycles = [scenes.wall_light(room.data, harness.cycles_corner_bake(room, SAMPLES, seed)) for seed in SEEDS]
    with harness.Stopwatch() as seconds:
        summary = addon.bake(bpy.context.scene, quality="MEDIUM")
    baked = scenes.wall_light(room.data, harness.corner_colors(room.data, "Radiosity"))
    print("%d blocks: %s, %d elements (%d solved), %.1f s CPU; walls %.4f, Cycles %.4f and %.4f" % (
        blocks, summary["method"], summary["elements"], summary.get("solve_elements", summary["elements"]),
        seconds.cpu, baked, cycles[0], cycles[1]), flush=True)
    return summary, baked, np.array(cycles)


def test_the_walls_lose_to_the_blocks_what_cycles_finds():
    empty, empty_walls, empty_cycles = room_walls(0)
    cluttered, walls, cycles = room_walls(1000)
    ratio, cycles_ratio = walls / empty_walls, cycles.mean() / empty_cycles.mean()
    # The ratio's own noise from the seeds' spread: each mean's half difference, relative, combined.
    noise = np.hypot(*[abs(c[0] - c[1]) / 2 / c.mean() for c in (cycles, empty_cycles)])
    print("walls cluttered / empty: bake %.4f, Cycles %.4f (its noise %.2f%%): %+.2f%%" % (
        ratio, cycles_ratio, 100 * noise, 100 * (ratio / cycles_ratio - 1)))
    assert noise < 0.003, noise
    assert cycles_ratio < 0.99, cycles_ratio  # the blocks do darken the walls
    assert abs(ratio / cycles_ratio - 1.0) < 0.01, (ratio, cycles_ratio)
    assert cluttered["converged"] and empty["converged"]


harness.run(test_the_walls_lose_to_the_blocks_what_cycles_finds)
