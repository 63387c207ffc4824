"""How long the Bake Radiosity operator's modal timer ticks take while a bake runs, and how late
Blender's event loop runs a 20 ms timer meanwhile: the Cornell box of blender_tests/scenes.py by
progressive refinement at 1 cm elements (about 60,000; its preview overlay redrawn as the solve
brightens), in a
real window. The bake is cancelled (Esc's path) after SECONDS, if it has not finished by then.

    xvfb-run -a -s "-screen 0 1280x800x24" blender --factory-startup \\
        --python lab/responsive_panel/measure_ticks.py -- --addon-zip build/bake_radiosity.zip --work /tmp/ticks

Prints the ticks' count, median, 90th percentile and maximum (ms of the operator's modal() on a
TIMER event), and the same of the 20 ms timer's lateness, over the bake."""

import importlib
import os
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "blender_tests"))

import bpy  # noqa: E402
import numpy as np  # noqa: E402

import harness  # noqa: E402
import scenes  # noqa: E402

args = harness.arguments()
ELEMENT_SIZE, SECONDS = 0.01, 60.0
ticks, lateness = [], []


def view3d():
    window = bpy.context.window_manager.windows[0]
    area = max((a for a in window.screen.areas if a.type == "VIEW_3D"), key=lambda a: a.width * a.height)
    return window, area


def timed_modal(modal):
    def wrapper(self, context, event):
        start = time.perf_counter()
        try:
            return modal(self, context, event)
        finally:
            if event.type == "TIMER":
                ticks.append(time.perf_counter() - start)
    return wrapper


def probe(last=[None]):
    now = time.perf_counter()
    if last[0] is not None:
        lateness.append(max(0.0, now - last[0] - 0.02))
    last[0] = now
    return 0.02


def line(name, values):
    ms = 1000 * np.array(values)
    return "%s: %d, median %.2f ms, 90%% %.2f ms, max %.2f ms" % (
        name, len(ms), np.median(ms), np.percentile(ms, 90), ms.max())


def steps():
    harness.install_addon(args.addon_zip)
    operators = importlib.import_module(harness.MODULE + ".operators")
    operators.RADIOSITY_OT_bake.modal = timed_modal(operators.RADIOSITY_OT_bake.modal)
    scenes.clear_scene()
    scenes.cornell_box("MESH")
    settings = bpy.context.scene.radiosity
    settings.quality = "CUSTOM"
    settings.method, settings.element_size, settings.hemicube_resolution = "PROGRESSIVE", ELEMENT_SIZE, 64
    settings.tolerance = 1e-4
    window, area = view3d()
    with bpy.context.temp_override(window=window, area=area, region=area.regions[-1]):
        assert bpy.ops.radiosity.bake("INVOKE_DEFAULT") == {"RUNNING_MODAL"}
    bpy.app.timers.register(probe)
    start = time.monotonic()
    while operators._running is not None:
        if time.monotonic() - start > SECONDS:
            operators._running._worker.cancel()
        yield
    bpy.app.timers.unregister(probe)
    print("bake: %s" % settings.last_report)
    print(line("operator ticks", ticks))
    print(line("20 ms timer lateness", lateness), flush=True)


harness.drive_steps(steps())
