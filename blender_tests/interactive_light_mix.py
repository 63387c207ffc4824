"""Apply Light Mix as an artist uses it, in a real Blender window (run under Xvfb): after a bake with
light group layers, a mix with the Key lamp's layer at strength 3 is written into the baked
attribute, and one undo takes it out again.

    xvfb-run -a blender --factory-startup --python interactive_light_mix.py -- --addon-zip <zip> --work <dir>

Windowed Blender runs this script before its event loop, so the steps run from a timer; the
process ends with exit code 0 when every step passed, 1 otherwise."""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402
import numpy as np  # noqa: E402

import harness  # noqa: E402
import scenes  # noqa: E402

TIME_LIMIT = 300.0  # seconds for the whole script, so a hang fails instead of blocking CI

args = harness.arguments()


def lit_floor():
    """A floor with a block, lit by a lamp in the light group 'Key' and one in 'Fill'."""
    scenes.clear_scene()
    grey = scenes.diffuse("Grey", (0.7, 0.7, 0.7))
    scenes.mesh_object("Floor", [scenes.grid((-1, -1, 0), (2, 0, 0), (0, 2, 0), 4, 4) + (0,)]
                       + scenes.block((-0.3, -0.3), (0.3, 0.3), 0.5, 0.3), [grey])
    for group, location in (("Key", (0.8, -0.6, 1.2)), ("Fill", (-0.9, 0.7, 0.9))):
        bpy.context.view_layer.lightgroups.add(name=group)
        light = bpy.data.lights.new(group, "POINT")
        light.energy = 100.0
        lamp = bpy.data.objects.new(group, light)
        lamp.location, lamp.lightgroup = location, group
        bpy.context.scene.collection.objects.link(lamp)


def steps():
    """A generator of test steps; each yield waits for the next timer tick."""
    harness.install_addon(args.addon_zip)
    lit_floor()
    settings = bpy.context.scene.radiosity
    settings.quality, settings.light_group_layers = "DRAFT", True
    yield
    assert bpy.ops.radiosity.bake() == {"FINISHED"}
    mesh = bpy.data.objects["Floor"].data
    baked = harness.corner_colors(mesh, "Radiosity")
    key, fill = harness.corner_colors(mesh, "Radiosity Key"), harness.corner_colors(mesh, "Radiosity Fill")
    bpy.ops.ed.undo_push(message="baked")
    yield
    next(layer for layer in settings.light_layers if layer.group == "Key").strength = 3.0
    window = bpy.context.window_manager.windows[0]
    with bpy.context.temp_override(window=window):  # undo=True: pushes its undo step as the panel's button does
        assert bpy.ops.radiosity.apply_light_mix("EXEC_DEFAULT", True) == {"FINISHED"}
    mixed = harness.corner_colors(mesh, "Radiosity")
    assert np.abs(mixed - (3.0 * key + fill)).max() <= 1e-6 * np.abs(mixed).max(), "the mix written is not 3 Key + Fill"
    print("PASS Apply Light Mix writes 3 x Key + Fill", flush=True)
    yield
    with bpy.context.temp_override(window=window):
        bpy.ops.ed.undo()
    mesh = bpy.data.objects["Floor"].data
    assert np.array_equal(harness.corner_colors(mesh, "Radiosity"), baked), "one undo did not take the mix out"
    assert np.array_equal(harness.corner_colors(mesh, "Radiosity Key"), key)
    print("PASS one undo takes the mix out", flush=True)


harness.drive_steps(steps(), TIME_LIMIT)
