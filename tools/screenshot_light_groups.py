"""Screenshots of the light-group workflow in a real Blender window (run under Xvfb, not with -b):

    BLENDER_USER_CONFIG=/tmp/shot/config BLENDER_USER_SCRIPTS=/tmp/shot/scripts \\
    xvfb-run -a -s "-screen 0 1600x1000x24" blender --factory-startup \\
        --python tools/screenshot_light_groups.py -- <out-folder> build/bake_radiosity.zip

Builds a 2 m room with a window (blender_tests/world_scenes.py): the World's sky and a sun through
the window in the light group "Day", a warm lamp under the ceiling in "Night". Bakes it once with
Light Group Layers through the Radiosity panel's operator, wires the baked light, and shoots the
window twice with the panel's Light Mix set for day (Day 1, Night 0) and for night (Day 0.03,
Night 1), side by side in light-groups-day-night.png (no bake runs between the two), then the
panel with the night mix: light-groups-panel.png. The add-on is installed from the zip into the
user folders the environment names (keep them apart from your own profile)."""

import math
import os
import sys

import bpy
import numpy as np
from mathutils import Vector

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "blender_tests"))

import harness  # noqa: E402
import scenes  # noqa: E402
import world_scenes  # noqa: E402

out, addon_zip = (os.path.abspath(a) for a in sys.argv[sys.argv.index("--") + 1:][:2])
os.makedirs(out, exist_ok=True)
MIXES = (("light-groups-day.png", {"Day": 1.0, "Night": 0.0}),
         ("light-groups-night.png", {"Day": 0.03, "Night": 1.0}))


def window_and_area(kind):
    window = bpy.context.window_manager.windows[0]
    area = max((a for a in window.screen.areas if a.type == kind), key=lambda a: a.width * a.height)
    return window, area


def room_in_two_groups():
    """The window room; Day: the World's sky and a sun, Night: a warm lamp of radius 10 cm."""
    scenes.clear_scene()
    world_scenes.room()
    view_layer = bpy.context.view_layer
    for group in ("Day", "Night"):
        view_layer.lightgroups.add(name=group)
    world_scenes.uniform_world(world_scenes.SKY_RADIANCE, strength=3.0)
    bpy.context.scene.world.lightgroup = "Day"
    sun = world_scenes.sun_lamp()
    sun.data.energy, sun.data.angle, sun.lightgroup = 10.0, math.radians(2.0), "Day"
    lamp = bpy.data.lights.new("Ceiling Lamp", "POINT")
    lamp.energy, lamp.color, lamp.shadow_soft_size = 40.0, (1.0, 0.6, 0.3), 0.1
    ceiling = world_scenes.add_lamp("Ceiling Lamp", lamp, (0.8, 1.2, 1.7), (0.0, 0.0, 1.0))
    ceiling.lightgroup = "Night"
    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    camera.location = (0.15, 0.2, 1.0)
    camera.rotation_euler = (Vector((2.0, 1.2, 0.75)) - camera.location).to_track_quat("-Z", "Y").to_euler()
    camera.data.lens = 18.0
    bpy.context.scene.collection.objects.link(camera)
    bpy.context.scene.camera = camera


def close_splash():
    """Opens the scene from a file, which takes the first-run splash away."""
    path = os.path.join(out, "light-groups.blend")
    bpy.ops.wm.save_as_mainfile(filepath=path)
    bpy.ops.wm.open_mainfile(filepath=path)


def set_up_views():
    window, view = window_and_area("VIEW_3D")
    space = view.spaces.active
    space.region_3d.view_perspective = "CAMERA"
    space.show_region_ui = space.show_region_toolbar = space.show_region_header = False
    space.shading.type = "MATERIAL"
    space.overlay.show_overlays = space.show_gizmo = False
    region = next(r for r in view.regions if r.type == "WINDOW")
    with bpy.context.temp_override(window=window, area=view, region=region):
        bpy.ops.view3d.view_center_camera()
    properties = next(a for a in window.screen.areas if a.type == "PROPERTIES")
    properties.spaces.active.context = "RENDER"
    settings = bpy.context.scene.radiosity
    settings.quality, settings.light_group_layers = "MEDIUM", True


def bake_and_wire():
    assert bpy.ops.radiosity.bake() == {"FINISHED"}, "the bake failed: %s" % bpy.context.scene.radiosity.last_report
    assert bpy.ops.radiosity.wire() == {"FINISHED"}


def show_light_mix():
    """Properties > Render maximized and scrolled down to the Light Mix, the pointer out of the way."""
    window = bpy.context.window_manager.windows[0]
    window.cursor_warp(0, 0)
    bpy.context.scene.render.engine = "BLENDER_WORKBENCH"  # its few render panels leave the Radiosity panel in view
    properties = next(a for a in window.screen.areas if a.type == "PROPERTIES")
    with bpy.context.temp_override(window=window, area=properties):
        bpy.ops.screen.screen_full_area()
    _, properties = window_and_area("PROPERTIES")
    region = next(r for r in properties.regions if r.type == "WINDOW")
    with bpy.context.temp_override(window=window, area=properties, region=region):
        for _ in range(20):
            bpy.ops.view2d.scroll_down(page=True)


def mix(strengths):
    for layer in bpy.context.scene.radiosity.light_layers:
        layer.strength = strengths.get(layer.group, 0.0)


def shoot(name, kind):
    window, area = window_and_area(kind)
    with bpy.context.temp_override(window=window, area=area):
        bpy.ops.screen.screenshot_area(filepath=os.path.join(out, name))
    print("wrote", name, flush=True)


script = [(1.0, lambda: harness.install_addon(addon_zip)), (1.0, room_in_two_groups), (2.0, close_splash),
          (1.0, set_up_views), (1.0, bake_and_wire)]
for picture, strengths in MIXES:
    script += [(3.0, lambda strengths=strengths: mix(strengths)),
               (1.0, lambda picture=picture: shoot(picture, "VIEW_3D"))]
script += [(0.5, lambda: side_by_side(MIXES[0][0], MIXES[1][0], "light-groups-day-night.png")),
           (2.0, show_light_mix), (1.0, lambda: shoot("light-groups-panel.png", "PROPERTIES")),
           (0.0, lambda: bpy.ops.wm.quit_blender())]


def side_by_side(left, right, name, width=1400):
    """`left` and `right` (files in `out`, of one size) next to each other, `width` pixels wide, as `name`;
    the two files are removed."""
    images = [bpy.data.images.load(os.path.join(out, f)) for f in (left, right)]
    w, h = images[0].size
    pixels = []
    for image in images:
        rgba = np.empty(w * h * 4, dtype=np.float32)
        image.pixels.foreach_get(rgba)
        pixels.append(rgba.reshape(h, w, 4))
        bpy.data.images.remove(image)
    gap = np.ones((h, 8, 4), dtype=np.float32)
    both = np.concatenate([pixels[0], gap, pixels[1]], axis=1)
    pair = bpy.data.images.new(name, both.shape[1], h)
    pair.pixels.foreach_set(both.ravel())
    pair.scale(width, round(h * width / both.shape[1]))
    pair.filepath_raw, pair.file_format = os.path.join(out, name), "PNG"
    pair.save()
    for f in (left, right):
        os.remove(os.path.join(out, f))
    print("wrote", name, flush=True)


def run_script():
    delay, step = script.pop(0)
    step()
    return delay if script else None


bpy.app.timers.register(run_script, first_interval=2.0, persistent=True)
