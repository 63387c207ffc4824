"""Screenshots of the add-on in a real Blender window (run under Xvfb, not with -b):

    xvfb-run -a -s "-screen 0 1600x1000x24" blender --factory-startup scene.blend \\
        --python tools/screenshot_ui.py -- <out-folder>

Writes baking.png (an interactive progressive
bake under way: status bar and the brightening viewport), baked.png (the finished bake in
the preview shading), panel.png (Properties > Render maximized, the Radiosity panel with the
bake's summary; run with a tall screen, e.g. 1000x1800, to see all of it), then quits. Needs the
add-on enabled in the profile it runs with."""

import os
import sys

import bpy

out = os.path.abspath(sys.argv[sys.argv.index("--") + 1])
os.makedirs(out, exist_ok=True)
steps = []


def window_and_area(kind):
    window = bpy.context.window_manager.windows[0]
    area = max((a for a in window.screen.areas if a.type == kind), key=lambda a: a.width * a.height)
    return window, area


def shoot(name, kind=None):
    window = bpy.context.window_manager.windows[0]
    if kind is None:
        with bpy.context.temp_override(window=window):
            bpy.ops.screen.screenshot(filepath=os.path.join(out, name))
    else:
        window, area = window_and_area(kind)
        with bpy.context.temp_override(window=window, area=area):
            bpy.ops.screen.screenshot_area(filepath=os.path.join(out, name))
    print("wrote", name, flush=True)


def set_up_views():
    window, view = window_and_area("VIEW_3D")
    view.spaces.active.region_3d.view_perspective = "CAMERA"
    view.spaces.active.show_region_ui = True
    properties = next(a for a in window.screen.areas if a.type == "PROPERTIES")
    properties.spaces.active.context = "RENDER"
    bpy.context.scene.render.engine = "BLENDER_WORKBENCH"
    settings = bpy.context.scene.radiosity
    settings.method, settings.element_size, settings.hemicube_resolution = "PROGRESSIVE", 0.04, 128


def start_bake():
    window, area = window_and_area("VIEW_3D")
    area.spaces.active.shading.type = "SOLID"
    with bpy.context.temp_override(window=window, area=area, region=area.regions[-1]):
        bpy.ops.radiosity.bake("INVOKE_DEFAULT")


def preview():
    window, area = window_and_area("VIEW_3D")
    with bpy.context.temp_override(window=window, area=area):
        bpy.ops.radiosity.preview()


script = [
    (1.0, set_up_views),
    (0.5, start_bake), (2.5, lambda: shoot("baking.png")),
]


def maximize_properties():
    window = bpy.context.window_manager.windows[0]
    properties = next(a for a in window.screen.areas if a.type == "PROPERTIES")
    with bpy.context.temp_override(window=window, area=properties):
        bpy.ops.screen.screen_full_area()


def finish():
    shoot("baked.png")
    maximize_properties()
    bpy.app.timers.register(lambda: (shoot("panel.png"), bpy.ops.wm.quit_blender())[0], first_interval=1.0)


def run_script():
    if script:
        delay, step = script.pop(0)
        step()
        return delay if script else 0.5
    if bpy.context.scene.radiosity.last_report:
        preview()
        bpy.app.timers.register(finish, first_interval=1.0)
        return None
    return 0.5


bpy.app.timers.register(run_script, first_interval=2.0)
