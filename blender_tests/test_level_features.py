"""What makes OpenArena's converted levels hard (lab/levels/README.md), each in a small scene of
its own, baked through the panel at Medium and by this Blender's Cycles in the same test."""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402
import numpy as np  # noqa: E402

import harness  # noqa: E402
import level_scenes as level  # noqa: E402
import scenes  # noqa: E402

args = harness.arguments()
harness.install_addon(args.addon_zip)

SAMPLES = 1024
LAMPS_LET_LIGHT_PASS = 8  # Cycles' transparent bounces (Blender's default): rays pass the lamps' disks
MEAN_TOLERANCE = 0.02  # Medium on a game-level-like interior: 1.67% per vertex (docs/accuracy.md), target 2%
CORNER_TOLERANCE = 0.02


def fixture_scene():
    """A 4 x 4 x 3 m room lit by a lamp inside an open shade."""
    scenes.clear_scene()
    pieces = level.box((0, 0, 0), (4, 4, 3), 0.25, inward=True)
    pieces += level.shade((2, 2, 2.6), 0.08, 0.02, 0.08, 0.10, 0.02)
    obj = level.level_object(pieces)
    level.point_lamp("Bulb", (2, 2, 2.6), 300.0)
    return obj


def thin_brush_scene():
    """Two rooms split by a 2 cm wall with a doorway, a 2 cm ledge in the lit one."""
    scenes.clear_scene()
    cell = 0.25
    pieces = level.box((0, 0, 0), (2.99, 4, 3), cell, inward=True, skip=("+x", "-y"))
    pieces += level.box((3.01, 0, 0), (6, 4, 3), cell, inward=True, skip=("-x",))
    pieces += level.wall_with_door(2.99, (0, 4), 3, (3.0, 3.8, 2.2), 0.02, cell)
    up = (0, 1, 0)
    pieces += [level.rect((0, 0, 0), (2.99, 0, 0), (0, 0, 1.49), up, cell),
               level.rect((0, 0, 1.51), (2.99, 0, 0), (0, 0, 1.49), up, cell),
               level.rect((0, 0, 1.49), (0.5, 0, 0), (0, 0, 0.02), up, cell),
               level.rect((2.5, 0, 1.49), (0.49, 0, 0), (0, 0, 0.02), up, cell)]
    pieces += level.box((0.5, 0, 1.49), (2.5, 0.3, 1.51), 0.05, skip=("-y",))
    obj = level.level_object(pieces)
    level.point_lamp("Bulb", (1.5, 2.0, 2.2), 200.0)
    return obj


def junction_scene():
    """A room whose floor is three unwelded pieces (a T-junction at every vertex of one side's edge)
    lit by a lamp over the junction, and a 20 cm wall brush that stops a crack of round-off width
    (10 um) over the floor, with the room's other half lit only through a doorway."""
    scenes.clear_scene()
    cell = 0.25
    pieces = [level.rect((0, 0, 0), (3, 0, 0), (0, 2, 0), (0, 0, 1), cell),
              level.rect((0, 2, 0), (1.5, 0, 0), (0, 2, 0), (0, 0, 1), 0.3),
              level.rect((1.5, 2, 0), (1.5, 0, 0), (0, 2, 0), (0, 0, 1), 0.3)]
    pieces += level.box((0, 0, 0), (3, 4, 3), cell, inward=True, skip=("+x", "-z"))
    pieces += level.box((3.2, 0, 0), (6, 4, 3), cell, inward=True, skip=("-x",))
    crack = 1e-5
    door = level.wall_with_door(3.0, (0, 4), 3, (3.0, 3.8, 2.2), 0.2, cell)
    pieces += [(v + np.where(v[:, 2:3] < crack, crack, 0) * (0, 0, 1), q, m) for v, q, m in door[:-1]]
    pieces.append(door[-1])
    pieces += [level.rect((3.0, 0, 0), (0.2, 0, 0), (0, 3.0, 0), (0, 0, 1), cell),  # under the crack
               level.rect((3.0, 3.8, 0), (0.2, 0, 0), (0, 0.2, 0), (0, 0, 1), cell)]
    obj = level.level_object(pieces)
    level.point_lamp("Bulb", (1.5, 2.0, 1.0), 100.0)
    return obj


def three_rooms_scene():
    """Three 4 x 4 x 3 m rooms in a row, joined by doorways at opposite ends of 20 cm walls; a lamp
    in the first room lights a corner of the second through the first doorway, and the third only
    after two bounces or more. In the second room a 10 cm ledge stands out of the
    side wall at 1.5 m under a 10 cm overhang at 1.9 m, a block closing the slot between them: at
    the slot's end the ledge's top, the wall, the block's side and the overhang meet."""
    scenes.clear_scene()
    cell = 0.25
    pieces = level.box((0, 0, 0), (4, 4, 3), cell, inward=True, skip=("+x",))
    pieces += level.wall_with_door(4.0, (0, 4), 3, (0.3, 1.3, 2.2), 0.2, cell)
    pieces += level.box((4.2, 0, 0), (8.2, 4, 3), cell, inward=True, skip=("-x", "+x", "-y"))
    pieces += level.wall_with_door(8.2, (0, 4), 3, (2.7, 3.7, 2.2), 0.2, cell)
    pieces += level.box((8.4, 0, 0), (12.4, 4, 3), cell, inward=True, skip=("-x",))
    fine, up = 0.05, (0, 1, 0)
    pieces += [level.rect((4.2, 0, 0), (1.0, 0, 0), (0, 0, 3), up, cell),
               level.rect((7.5, 0, 0), (0.7, 0, 0), (0, 0, 3), up, cell),
               level.rect((5.2, 0, 0), (2.3, 0, 0), (0, 0, 1.5), up, cell),
               level.rect((5.2, 0, 2.0), (2.3, 0, 0), (0, 0, 1.0), up, cell),
               level.rect((5.2, 0, 1.6), (2.0, 0, 0), (0, 0, 0.3), up, fine)]
    pieces += level.box((5.2, 0, 1.5), (7.2, 0.4, 1.6), fine, skip=("-y", "+x"))  # the ledge
    pieces += level.box((5.2, 0, 1.9), (7.2, 0.2, 2.0), fine, skip=("-y", "+x"))  # the overhang
    pieces += level.box((7.2, 0, 1.5), (7.5, 0.4, 2.0), fine, skip=("-y", "-x"))  # the block
    pieces += [level.rect((7.2, 0, 1.6), (0, 0.4, 0), (0, 0, 0.3), (-1, 0, 0), fine),
               level.rect((7.2, 0.2, 1.9), (0, 0.2, 0), (0, 0, 0.1), (-1, 0, 0), fine)]
    obj = level.level_object(pieces)
    level.point_lamp("Bulb", (1.0, 3.0, 2.0), 500.0)
    return obj


def region_numbers(baked, seeds, mask):
    """The region's mean against Cycles' and the noise of Cycles' mean there (two seeds: half their
    difference), and per corner (corners Cycles leaves black, such as a room's corner point,
    apart): the RMS error, Cycles' own RMS noise, and that error with the noise taken out."""
    cycles, noise = seeds.mean(axis=0)[mask], np.abs(seeds[0] - seeds[1])[mask] / 2
    lit = cycles > 0
    error = baked[mask][lit] / cycles[lit] - 1
    rms, rms_noise = np.sqrt(np.mean(error ** 2)), np.sqrt(np.mean((noise[lit] / cycles[lit]) ** 2))
    return {"corners": int(mask.sum()), "mean": baked[mask].sum() / cycles.sum() - 1,
            "mean_noise": np.sqrt(np.sum(noise ** 2)) / cycles.sum(), "rms": rms, "rms_noise": rms_noise,
            "rms_out": np.sqrt(max(0.0, rms ** 2 - rms_noise ** 2))}


def compare(name, obj, regions):
    """Bakes `obj`'s scene at Medium and by Cycles (two seeds), and checks each of `regions`
    {name: (corner mask, per_corner)}: its mean within MEAN_TOLERANCE plus three times the noise of
    Cycles' mean, and where `per_corner`, the RMS per corner with Cycles' noise out within
    CORNER_TOLERANCE."""
    settings = bpy.context.scene.radiosity
    settings.quality = "MEDIUM"
    assert bpy.ops.radiosity.bake() == {"FINISHED"}, settings.last_report
    print("%s: %s" % (name, settings.last_report), flush=True)
    baked = harness.corner_colors(obj.data, "Radiosity").mean(axis=1)
    seeds = np.array([harness.cycles_corner_bake(obj, SAMPLES, seed, transparent_bounces=LAMPS_LET_LIGHT_PASS)
                      .mean(axis=1) for seed in (1, 2)])
    failures = []
    masks = regions(harness.corner_positions(obj.data), harness.corner_normals(obj.data))
    for region, (mask, per_corner) in masks.items():
        r = region_numbers(baked, seeds, mask)
        print("%s, %s: %d corners, mean %+.2f%% of Cycles' (its noise %.2f%%); per corner RMS %.2f%% (Cycles' "
              "noise %.2f%%), %.2f%% with the noise out"
              % (name, region, r["corners"], 100 * r["mean"], 100 * r["mean_noise"], 100 * r["rms"],
                 100 * r["rms_noise"], 100 * r["rms_out"]), flush=True)
        if abs(r["mean"]) > MEAN_TOLERANCE + 3 * r["mean_noise"]:
            failures.append("%s: mean %+.2f%%" % (region, 100 * r["mean"]))
        if per_corner and r["rms_out"] > CORNER_TOLERANCE:
            failures.append("%s: %.2f%% per corner" % (region, 100 * r["rms_out"]))
    assert not failures, "; ".join(failures)


def test_fixture_around_a_lamp():
    # Cycles finds the shade's inside, 2,000 times brighter than the room, only by chance from the
    # room (per corner its noise is 30%): the room is judged by its surfaces' means.
    obj = fixture_scene()

    def regions(p, n):
        shade = (np.abs(p[:, 0] - 2) < 0.2) & (np.abs(p[:, 1] - 2) < 0.2) & (p[:, 2] > 2.4) & (p[:, 2] < 2.8)
        inside = shade & (np.einsum("ij,ij->i", n, (2, 2, 2.6) - p) > 0) & (p[:, 2] > 2.49)
        return {"shade's inside": (inside, True), "shade's outside": (shade & ~inside, False),
                "floor": (~shade & (n[:, 2] > 0.5), False), "ceiling": (~shade & (n[:, 2] < -0.5), False),
                "walls": (~shade & (np.abs(n[:, 2]) < 0.5), False)}
    compare("fixture", obj, regions)


def test_thin_brush():
    obj = thin_brush_scene()

    def regions(p, n):
        dark = p[:, 0] > 3.005
        ledge = (p[:, 0] >= 0.5) & (p[:, 0] <= 2.5) & (p[:, 1] <= 0.3) & (np.abs(p[:, 2] - 1.5) < 0.011)
        under = (p[:, 0] >= 0.5) & (p[:, 0] <= 2.5) & (p[:, 1] < 0.001) & (p[:, 2] < 1.49) & (p[:, 2] > 1.0)
        return {"dark room": (dark, False), "thin wall's dark side": (dark & (p[:, 0] < 3.02) & (n[:, 0] > 0.5), False),
                "thin wall's lit side": ((p[:, 0] > 2.98) & (p[:, 0] < 2.995) & (n[:, 0] < -0.5), True),
                "ledge's top": (ledge & (n[:, 2] > 0.5), True), "ledge's underside": (ledge & (n[:, 2] < -0.5), True),
                "wall under the ledge": (under, True), "lit room": ((p[:, 0] < 2.99) & ~ledge & ~under, True)}
    compare("thin brush", obj, regions)


def test_t_junction_and_crack():
    obj = junction_scene()

    def regions(p, n):
        floor = (n[:, 2] > 0.5) & (p[:, 0] < 3.0)
        junction = floor & (np.abs(p[:, 1] - 2) < 0.01)
        return {"floor's T-junction": (junction, True), "lit floor": (floor & ~junction, True),
                "dark floor at the crack": ((p[:, 0] > 3.2) & (p[:, 0] < 3.3) & (n[:, 2] > 0.5), False),
                "dark wall over the crack": ((np.abs(p[:, 0] - 3.2) < 1e-4) & (n[:, 0] > 0.5) & (p[:, 2] < 0.3),
                                             False),
                "dark room": (p[:, 0] > 3.2, False), "lit room": (p[:, 0] < 3.0, True)}
    compare("T-junction", obj, regions)


def test_ledge_corner_and_rooms_lit_by_bounces():
    # Not a lamp in a shade here: light that reaches the far rooms from a shade's inside Cycles finds
    # only by chance (two seeds of 512 samples put the third room at 0.38 of what two of 4,096 give).
    obj = three_rooms_scene()

    def regions(p, n):
        slot = (p[:, 0] > 5.19) & (p[:, 0] < 7.51) & (p[:, 1] < 0.41) & (p[:, 2] > 1.49) & (p[:, 2] < 2.01)
        end = slot & (p[:, 0] > 6.99) & (p[:, 1] < 0.21) & (p[:, 2] > 1.59) & (p[:, 2] < 1.81)
        third = p[:, 0] > 8.4
        return {"first room": (p[:, 0] < 4, False), "second room": ((p[:, 0] > 4.2) & (p[:, 0] < 8.2) & ~slot, False),
                "ledge and its slot": (slot, False), "slot's end": (end, False), "third room": (third, False),
                "third room's floor": (third & (n[:, 2] > 0.5), False),
                "third room's ceiling": (third & (n[:, 2] < -0.5), False)}
    compare("three rooms", obj, regions)


harness.run(test_fixture_around_a_lamp, test_thin_brush, test_t_junction_and_crack,
            test_ledge_corner_and_rooms_lit_by_bounces)
