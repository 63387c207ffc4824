"""Each lamp type (point, spot, sun, area) lighting a Diffuse BSDF and Principled BSDFs of
roughness 0, 0.25, 0.5, 0.75 and 1, baked through the panel at Medium and by this Blender's own Cycles, compared
corner by corner per material.

The scene: a 2 x 2 m floor in strips of one base colour (Diffuse, then the Principled BSDFs) and
nothing else, so all its light is direct and the radiosity error (the final
gather's) is well below the tolerance (a grey wall behind it was 1.5% dark beside Cycles, from the
interreflection at their seam). Cycles' Diffuse bake (direct, indirect and colour) is the
reference: the light each surface reflects diffusely, without the Principled's view-dependent
highlights, which a diffuse bake does not hold. Cycles bakes in two halves with different seeds;
their difference measures its noise, which is taken out of the difference in quadrature."""

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

ROOM, CELLS = 2.0, 18
BASE = (0.6, 0.6, 0.6)
SAMPLES_PER_HALF = 1024
MAX_CYCLES_NOISE = 0.01
MAX_RELATIVE_RMS = 0.02
ROUGHNESS = (0.0, 0.25, 0.5, 0.75, 1.0)
# The floor's strips, in material slots 0, 1, ...
STRIPS = ("Diffuse",) + tuple("Principled roughness %g" % r for r in ROUGHNESS)


def principled(name, roughness):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    bsdf = material.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*BASE, 1.0)
    bsdf.inputs["Roughness"].default_value = roughness
    return material


def floor():
    scenes.clear_scene()
    strip = ROOM / len(STRIPS)
    columns = CELLS // len(STRIPS)
    pieces = [scenes.grid((i * strip, 0, 0), (strip, 0, 0), (0, ROOM, 0), columns, CELLS) + (i,)
              for i in range(len(STRIPS))]
    materials = [scenes.diffuse(STRIPS[0], BASE)]
    materials += [principled(name, roughness) for name, roughness in zip(STRIPS[1:], ROUGHNESS)]
    return scenes.mesh_object("Floor", pieces, materials)


def add_lamp(kind):
    """The lamp of type `kind`, its light reaching the floor from above and at an angle."""
    lamp = bpy.data.lights.new(kind.title(), kind)
    if kind == "POINT":
        lamp.energy, location, rotation = 150.0, (0.9, 0.8, 1.0), (0.0, 0.0, 0.0)
    elif kind == "SPOT":
        lamp.energy, location, rotation = 300.0, (1.0, 0.4, 1.2), (math.radians(30.0), 0.0, 0.0)
        lamp.spot_size, lamp.spot_blend = math.radians(100.0), 0.3
    elif kind == "SUN":
        lamp.energy, location, rotation = 3.0, (1.0, 1.0, 3.0), (math.radians(40.0), 0.0, math.radians(25.0))
        lamp.angle = 0.0
    else:
        lamp.energy, location, rotation = 100.0, (1.0, 0.9, 1.2), (math.radians(-15.0), 0.0, 0.0)
        lamp.shape, lamp.size = "SQUARE", 0.5
    if kind in {"POINT", "SPOT"}:
        lamp.shadow_soft_size = 0.0
    obj = bpy.data.objects.new(lamp.name, lamp)
    obj.location, obj.rotation_euler = location, rotation
    bpy.context.scene.collection.objects.link(obj)


def corner_materials(mesh):
    index = np.empty(len(mesh.polygons), dtype=np.int64)
    mesh.polygons.foreach_get("material_index", index)
    total = np.empty(len(mesh.polygons), dtype=np.int64)
    mesh.polygons.foreach_get("loop_total", total)
    return np.repeat(index, total)


def compare(kind):
    """{material: relative RMS beyond Cycles' noise} of the panel's Medium bake against Cycles."""
    obj = floor()
    add_lamp(kind)
    halves = [harness.cycles_corner_bake(obj, SAMPLES_PER_HALF, seed, diffuse_only=True) for seed in (1, 2)]
    settings = bpy.context.scene.radiosity
    settings.quality = "MEDIUM"
    assert bpy.ops.radiosity.bake() == {"FINISHED"}, settings.last_report
    baked = harness.corner_colors(obj.data, "Radiosity")
    material = corner_materials(obj.data)
    errors = {}
    for index, name in enumerate(STRIPS):
        where = material == index
        reference = 0.5 * (halves[0][where] + halves[1][where])
        scale = np.sqrt(np.mean(reference ** 2))
        noise = np.sqrt(np.mean((halves[0][where] - halves[1][where]) ** 2)) / 2 / scale
        measured = np.sqrt(np.mean((baked[where] - reference) ** 2)) / scale
        error = float(np.sqrt(max(measured ** 2 - noise ** 2, 0.0)))
        mean = baked[where].mean() / reference.mean() - 1
        print("Blender %s, %s lamp, %s: relative RMS %.2f%% (Cycles' noise %.2f%% taken out), mean %+.2f%%"
              % (bpy.app.version_string, kind.lower(), name, 100 * error, 100 * noise, 100 * mean), flush=True)
        assert noise < MAX_CYCLES_NOISE, "Cycles is too noisy to judge: %.2f%%" % (100 * noise)
        errors[name] = error
    return errors


def check(kind):
    errors = compare(kind)
    assert max(errors.values()) <= MAX_RELATIVE_RMS, errors


def test_point_lamp():
    check("POINT")


def test_spot_lamp():
    check("SPOT")


def test_sun_lamp():
    check("SUN")


def test_area_lamp():
    check("AREA")


harness.run(test_point_lamp, test_spot_lamp, test_sun_lamp, test_area_lamp)
