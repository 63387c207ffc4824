"""The World's light against Cycles on a 2 m room lit through a window by an Environment Texture
(an equirectangular OpenEXR made here: a sky, a ground, and a sun disc 8 degrees across shining
through the window onto the floor), baked by bake() at the default preset; and, for the accuracy
the preset reaches on this room lit by a lamp, the same room lit by a sun lamp of the sun disc's
irradiance through the same window with a black World (world_scenes.py). And a lone floor under
Blender's physical Sky Texture, with and without its sun disc (0.545 degrees across, the map's
pixels are 0.7 degrees): the whole light of the sky and of the sun, as Cycles bakes it."""

import math

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402
import numpy as np  # noqa: E402

import harness  # noqa: E402
import scenes  # noqa: E402
import world_scenes  # noqa: E402

args = harness.arguments()
addon = harness.install_addon(args.addon_zip)

# The World's own sampling adds to the lamp's error (test_world.py); the HDRI's sun disc, 8 degrees
# across, also softens its shadow's edge where the sun lamp's is sharp, and its sky and ground add
# light the sun lamp does not give. Measured: 0.43% RMS, mean +0.10%, against the sun lamp's 0.23%,
# +0.18% (rays spread evenly over each corner's sky give 0.56%, which this allowance refuses).
WORLD_SAMPLING_RMS = 0.003
MAX_MEAN_ERROR = 0.003


def test_hdri_world_through_a_window_by_bake():
    scenes.clear_scene()
    obj = world_scenes.room()
    lamp = world_scenes.sun_lamp()
    reference, noise = world_scenes.cycles_reference(obj)
    addon.bake(bpy.context.scene)
    lamp_rms, lamp_mean = world_scenes.errors("sun lamp through the window", obj, reference, noise)

    bpy.data.objects.remove(lamp)
    world_scenes.hdri_world(args.work)
    scenes_before = sorted(bpy.data.scenes.keys())
    reference, noise = world_scenes.cycles_reference(obj)
    summary = addon.bake(bpy.context.scene)
    assert summary["world"]["rendered"], summary["world"]
    assert summary["lit_by"] == "the World only", summary["lit_by"]
    assert sorted(bpy.data.scenes.keys()) == scenes_before
    print("seconds: %s" % {k: round(v, 2) for k, v in summary["seconds"].items()})
    rms, mean_error = world_scenes.errors("Environment Texture through the window", obj, reference, noise)
    assert rms <= lamp_rms + WORLD_SAMPLING_RMS, "RMS %.2f%%, the lamp's %.2f%%" % (100 * rms, 100 * lamp_rms)
    assert abs(mean_error) <= abs(lamp_mean) + MAX_MEAN_ERROR, "mean %+.2f%%" % (100 * mean_error)


def physical_sky():
    """A Sky Texture of Blender's physical model (Nishita; its successors in Blender 5) into the Background."""
    world, background = world_scenes.world_nodes()
    sky = world.node_tree.nodes.new("ShaderNodeTexSky")
    types = sky.bl_rna.properties["sky_type"].enum_items.keys()
    sky.sky_type = next(t for t in ("NISHITA", "MULTIPLE_SCATTERING", "SINGLE_SCATTERING") if t in types)
    sky.sun_size = math.radians(0.545)
    sky.sun_elevation = math.radians(30.0)
    world.node_tree.links.new(sky.outputs["Color"], background.inputs["Color"])
    return sky


def test_sky_texture_sun_disc_over_a_floor():
    scenes.clear_scene()
    vertices, quads = scenes.grid((-1, -1, 0), (2, 0, 0), (0, 2, 0), 2, 2)
    floor = scenes.mesh_object("Floor", [(vertices, quads, 0)], [scenes.diffuse("Grey", world_scenes.ALBEDO)])
    sky = physical_sky()
    # Measured: +0.11% with the sun (+2.9% before its pixels are rendered again), +0.01% without.
    for sun_disc, tolerance in ((True, 0.01), (False, 0.002)):
        sky.sun_disc = sun_disc
        reference, noise = world_scenes.cycles_reference(floor)
        summary = addon.bake(bpy.context.scene)
        baked = harness.corner_colors(floor.data, "Radiosity")
        ratio = baked.mean(axis=0) / reference.mean(axis=0)
        print("Sky Texture, sun disc %s: radiosity %s, Cycles %s (noise %.3f%%), map %.1f s" % (
            sun_disc, baked.mean(axis=0).round(4), reference.mean(axis=0).round(4), 100 * noise,
            summary["seconds"]["world_map"]), flush=True)
        assert np.all(np.abs(ratio - 1) < tolerance), ratio


harness.run(test_sky_texture_sun_disc_over_a_floor, test_hdri_world_through_a_window_by_bake)
