"""The Bake Radiosity button as an artist uses it, in a real Blender window (run under Xvfb):
the bake runs in the background while the status bar reports, Esc (a real key press, sent with
xdotool) cancels and leaves the file as it was, a finished bake writes the attribute, and one
undo removes it.

    xvfb-run -a blender --factory-startup --python interactive_bake.py -- --addon-zip <zip> --work <dir>

Windowed Blender runs this script before its event loop, so the steps run from a timer; the
process ends with exit code 0 when every step passed, 1 otherwise."""

import importlib
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402

import harness  # noqa: E402
import scenes  # noqa: E402

TIME_LIMIT = 300.0  # seconds for the whole script, so a hang fails instead of blocking CI

args = harness.arguments()


def view3d():
    window = bpy.context.window_manager.windows[0]
    area = max((a for a in window.screen.areas if a.type == "VIEW_3D"), key=lambda a: a.width * a.height)
    return window, area


def baked_state():
    """What a bake may change: the colour attributes and the collections."""
    return ({m.name: sorted(m.color_attributes.keys()) for m in bpy.data.meshes},
            sorted(c.name for c in bpy.data.collections))


def press_escape():
    window, area = view3d()
    ids = subprocess.run(["xdotool", "search", "--name", "Blender"], capture_output=True, text=True).stdout.split()
    assert ids, "no Blender window for xdotool"
    x, y = area.x + area.width // 2, window.height - (area.y + area.height // 2)
    subprocess.run(["xdotool", "windowfocus", "--sync", ids[-1]], check=True)
    subprocess.run(["xdotool", "mousemove", "--window", ids[-1], str(x), str(y)], check=True)
    subprocess.run(["xdotool", "key", "Escape"], check=True)


def invoke_bake():
    window, area = view3d()
    with bpy.context.temp_override(window=window, area=area, region=area.regions[-1]):
        return bpy.ops.radiosity.bake("INVOKE_DEFAULT")


def steps():
    """A generator of test steps; each yield waits for the next timer tick."""
    harness.install_addon(args.addon_zip)
    operators = importlib.import_module(harness.MODULE + ".operators")
    scenes.clear_scene()
    scenes.cornell_box("MESH")
    settings = bpy.context.scene.radiosity
    settings.quality = "CUSTOM"
    settings.method, settings.element_size, settings.hemicube_resolution = "PROGRESSIVE", 0.02, 64
    settings.tolerance = 1e-6
    before = baked_state()
    bpy.ops.ed.undo_push(message="scene ready")

    # Esc during the solve: nothing changes.
    assert invoke_bake() == {"RUNNING_MODAL"}
    while True:
        yield
        info = operators._running._worker.monitor.snapshot() if operators._running else None
        if info is not None and info["phase"] == "solve":
            break
    press_escape()
    start = time.monotonic()
    while operators._running is not None:
        assert time.monotonic() - start < 30, "Esc did not stop the bake"
        yield
    assert baked_state() == before, "a cancelled bake changed the file: %r" % (baked_state(),)
    print("PASS Esc cancels and changes nothing (%.1f s)" % (time.monotonic() - start), flush=True)

    # A bake left to finish writes the attribute; one undo removes it.
    settings.element_size, settings.tolerance = 0.05, 1e-4
    assert invoke_bake() == {"RUNNING_MODAL"}
    while operators._running is not None:
        yield
    box = bpy.data.objects["Cornell Box"]
    assert "Radiosity" in box.data.color_attributes, "the finished bake wrote no attribute"
    assert settings.last_report, "the finished bake reported nothing"
    print("PASS interactive bake finished: %s" % settings.last_report, flush=True)
    window, area = view3d()
    with bpy.context.temp_override(window=window, area=area):
        bpy.ops.ed.undo()
    assert baked_state() == before, "one undo did not remove the bake: %r" % (baked_state(),)
    print("PASS one undo removes the bake", flush=True)


harness.drive_steps(steps(), TIME_LIMIT)
