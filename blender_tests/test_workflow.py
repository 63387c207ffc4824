"""What an artist relies on around the bake: cancel changes nothing, re-baking replaces only
the bake's own output, one undo removes a bake, the add-on enables and disables cleanly, the
preview restores exactly, and the command line bakes and saves (or fails loudly)."""

import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import addon_utils  # noqa: E402
import bpy  # noqa: E402
import numpy as np  # noqa: E402

import harness  # noqa: E402
import scenes  # noqa: E402

args = harness.arguments()
addon = harness.install_addon(args.addon_zip)
pipeline = sys.modules[harness.MODULE + ".pipeline"]
operators = sys.modules[harness.MODULE + ".operators"]
native = sys.modules[harness.MODULE + ".engine.native"]

QUICK = dict(element_size=0.125, hemicube_resolution=64)  # 4 x 4 walls: 2 x 2 elements a face


def quick_box():
    scenes.clear_scene()
    box = scenes.cornell_box("MESH", cells=4)
    settings = bpy.context.scene.radiosity
    settings.element_size, settings.hemicube_resolution = QUICK["element_size"], QUICK["hemicube_resolution"]
    return box


def test_cancel_changes_nothing():
    quick_box()
    # Small elements: the form factors take long enough to be cancelled half-way.
    bpy.context.scene.radiosity.element_size = 0.04
    before = harness.file_state()
    view_layer, depsgraph = pipeline.view_layer_and_depsgraph(bpy.context.scene)
    job = pipeline.BakeJob(bpy.context.scene, depsgraph, view_layer)

    # The worker the interactive operator runs, cancelled through its monitor as Esc does, once
    # the core has reported some form factors.
    worker = operators._Worker(job, want_layout=False)
    worker.thread.start()
    deadline = time.perf_counter() + 60
    while worker.monitor.snapshot() is None and time.perf_counter() < deadline:
        time.sleep(0.001)
    reported = worker.monitor.snapshot()
    worker.cancel()
    worker.thread.join(timeout=600)
    assert reported is not None and reported["phase"] == "form_factors", reported
    assert reported["done"] < reported["total"], reported
    assert worker.done and worker.cancelled and worker.error is None, (worker.done, worker.cancelled, worker.error)
    assert harness.file_state() == before

    # The synchronous path raises the core's Cancelled and has written nothing either.
    try:
        job.solve(progress=lambda info: False)
    except native.core().Cancelled:
        pass
    else:
        raise AssertionError("returning False from progress did not cancel")
    assert harness.file_state() == before


def test_rebake_is_idempotent():
    box = quick_box()
    addon.bake(bpy.context.scene)
    first = harness.file_state()
    addon.bake(bpy.context.scene)
    assert harness.file_state()["meshes"] == first["meshes"], "re-bake changed the ORIGINAL output"
    assert list(box.data.color_attributes.keys()) == ["Radiosity"]

    addon.bake(bpy.context.scene, target="COPIES")
    copies = harness.file_state()
    addon.bake(bpy.context.scene, target="COPIES")
    again = harness.file_state()
    assert again["objects"] == copies["objects"] and again["meshes"] == copies["meshes"], "re-bake changed COPIES"
    made = [o for o in bpy.data.collections["Radiosity Bake"].objects]
    assert [o.name for o in made] == ["Cornell Box Radiosity"], [o.name for o in made]
    # The copy keeps the elements: more faces than the original, same total area.
    assert len(made[0].data.polygons) > len(box.data.polygons)
    areas = [np.sum([p.area for p in m.polygons]) for m in (made[0].data, box.data)]
    assert abs(areas[0] - areas[1]) < 1e-4 * areas[1], areas


def test_undo_restores():
    mesh_name = quick_box().data.name  # undo replaces every Python reference to data
    bpy.ops.ed.undo_push(message="before bake")
    before = harness.file_state()
    # As a click does: scripts only push an undo step when asked (the second argument).
    assert bpy.ops.radiosity.bake("EXEC_DEFAULT", True) == {"FINISHED"}
    assert bpy.data.meshes[mesh_name].color_attributes.get("Radiosity") is not None
    bpy.ops.ed.undo()
    assert harness.file_state() == before, "one undo did not remove the bake"
    bpy.ops.ed.redo()
    assert bpy.data.meshes[mesh_name].color_attributes.get("Radiosity") is not None, "redo lost the bake"


def test_preview_restores():
    quick_box()
    addon.bake(bpy.context.scene)
    shadings = [a.spaces.active.shading for s in bpy.data.screens for a in s.areas if a.type == "VIEW_3D"]
    assert shadings, "no 3D view in the factory startup file"
    before = harness.file_state()
    before_shading = [(s.type, s.color_type, s.light) for s in shadings]
    assert bpy.ops.radiosity.preview() == {"FINISHED"}
    assert all((s.type, s.color_type, s.light) == ("SOLID", "VERTEX", "FLAT") for s in shadings)
    box = bpy.data.objects["Cornell Box"]
    assert all(slot.material.name == "Radiosity Preview" for slot in box.material_slots)
    assert bpy.ops.radiosity.preview() == {"FINISHED"}
    assert [(s.type, s.color_type, s.light) for s in shadings] == before_shading
    assert harness.file_state() == before


def test_enable_disable_twice():
    for _ in range(2):
        addon_utils.disable(harness.MODULE, default_set=True)
        assert not hasattr(bpy.types.Scene, "radiosity")
        leftovers = [name for name in dir(bpy.types) if name.startswith("RADIOSITY_")]
        assert not leftovers, leftovers
        addon_utils.enable(harness.MODULE, default_set=True)
        assert hasattr(bpy.types.Scene, "radiosity") and hasattr(bpy.types, "RADIOSITY_OT_bake")


def test_command_line():
    quick_box()
    source = os.path.join(args.work, "scene.blend")
    baked = os.path.join(args.work, "baked.blend")
    if os.path.exists(baked):
        os.remove(baked)
    bpy.ops.wm.save_as_mainfile(filepath=source, copy=True)
    command = harness.batch_command(source, "--output", baked, "--resolution", "64", "--element-size", "0.25")
    run = subprocess.run(command, capture_output=True, text=True, timeout=600)
    print(run.stdout[-1500:], run.stderr[-1500:])
    assert run.returncode == 0, run.returncode
    with bpy.data.libraries.load(baked) as (source_data, loaded):
        loaded.meshes = ["Cornell Box"]
    mesh = loaded.meshes[0]
    assert mesh.color_attributes.get("Radiosity") is not None, "the saved file has no baked attribute"
    assert harness.corner_colors(mesh, "Radiosity").max() > 0.0

    # The script form, on a file with nothing to bake: a clear message and a non-zero exit.
    empty = os.path.join(args.work, "empty.blend")
    scenes.clear_scene()
    bpy.ops.wm.save_as_mainfile(filepath=empty, copy=True)
    cli_path = os.path.join(os.path.dirname(addon.__file__), "cli.py")
    run = subprocess.run([bpy.app.binary_path, "-b", empty, "--python", cli_path, "--", "--output", baked],
                         capture_output=True, text=True, timeout=600)
    print(run.stderr[-800:])
    assert run.returncode != 0
    assert "Bake Radiosity failed: Nothing to bake" in run.stderr


harness.run(test_cancel_changes_nothing, test_rebake_is_idempotent, test_undo_restores, test_preview_restores,
            test_enable_disable_twice, test_command_line)
