"""Small scenes tried as a new user would, through the operator, each against an exact answer or a
Cycles bake of the same scene: a closed box that emits and reflects (every preset), a white room
lit by a panel just under its ceiling, and the same room a millionth of its size."""

import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402
import numpy as np  # noqa: E402

import harness  # noqa: E402
import scenes  # noqa: E402

args = harness.arguments()
addon = harness.install_addon(args.addon_zip)

QUALITIES = ("DRAFT", "MEDIUM", "HIGH")


def bake_with_operator(quality):
    """The panel's Bake button at `quality`; the seconds it took."""
    bpy.context.scene.radiosity.quality = quality
    start = time.perf_counter()
    assert bpy.ops.radiosity.bake() == {"FINISHED"}
    return time.perf_counter() - start


def test_box_that_emits_and_reflects_counts_its_emission_once():
    # One mesh of 6 quads, normals inside, the object turned and scaled as an artist leaves it:
    # Diffuse 0.5 plus Emission 0.7 through an Add Shader. Every point sees only the box, so its
    # radiance is exactly E / (1 - rho) = 1.4.
    rho, emitted = 0.5, 0.7
    for quality in QUALITIES:
        scenes.clear_scene()
        box = scenes.furnace_box(rho, emitted, cells=1)
        box.rotation_euler = (0.3, 0.5, 0.7)
        box.scale = (2.0, 1.5, 0.8)
        seconds = bake_with_operator(quality)
        colors = harness.corner_colors(box.data, "Radiosity")
        error = np.abs(colors / (emitted / (1 - rho)) - 1)
        print("box that emits and reflects, %s: %.1f s, corners %.5f to %.5f, worst %.3f%%"
              % (quality, seconds, colors.min(), colors.max(), 100 * error.max()))
        assert error.max() < 0.005, quality


def white_room(scale=1.0):
    """A closed 2 m room of albedo 0.7 (4 x 4 quads a side) lit by a 50 cm emitting square 1 cm
    under its ceiling, facing down; every object scaled by `scale` about the origin."""
    scenes.clear_scene()
    room = scenes.mesh_object("Room", [scenes.grid(o, u, v, 4, 4) + (0,) for o, u, v in scenes.ROOM_SIDES],
                              [scenes.diffuse("Walls", (0.7, 0.7, 0.7))])
    panel = scenes.mesh_object("Panel", [scenes.grid((0.75, 0.75, 1.99), (0, 0.5, 0), (0.5, 0, 0), 1, 1) + (0,)],
                               [scenes.emission("Panel", (1.0, 1.0, 1.0), 5.0)])
    for obj in (room, panel):
        obj.scale = (scale, scale, scale)
    return room


def test_white_room_under_a_panel_matches_cycles_and_any_scale():
    # The ceiling around the panel takes its back side's light from 1 cm: light that changes on
    # the scale of that centimetre, inside elements of about 12 cm. The room's mean against
    # Cycles' (4 seeds of 1,024 samples: its own noise about 0.1%) within 1%; a millionth of the
    # size (the same light, physically) within 0.1% of the full-size bake.
    room = white_room()
    bake_with_operator("MEDIUM")
    baked = harness.corner_colors(room.data, "Radiosity").mean()
    cycles = np.mean([harness.cycles_corner_bake(room, 1024, seed).mean() for seed in range(4)])
    print("white room: baked mean %.5f, Cycles %.5f: %+.2f%%" % (baked, cycles, 100 * (baked / cycles - 1)))
    assert abs(baked / cycles - 1) < 0.01
    room = white_room(1e-6)
    bake_with_operator("MEDIUM")
    tiny = harness.corner_colors(room.data, "Radiosity").mean()
    print("white room at 1e-6 of its size: mean %.5f, %+.3f%% from full size" % (tiny, 100 * (tiny / baked - 1)))
    assert abs(tiny / baked - 1) < 0.001


harness.run(test_box_that_emits_and_reflects_counts_its_emission_once,
            test_white_room_under_a_panel_matches_cycles_and_any_scale)
