"""Bakes that cannot run, or meet bad input: one report that names the problem (never a Python
traceback), through the operator, bake() and the batch command, and the file as it was."""

import math
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402

import harness  # noqa: E402
import scenes  # noqa: E402

args = harness.arguments()
addon = harness.install_addon(args.addon_zip)
pipeline = sys.modules[harness.MODULE + ".pipeline"]


def room_that_absorbs_nothing():
    """scenes.room_with_panel's room with albedo 1 everywhere, lit by its ceiling, which also reflects
    all light."""
    scenes.clear_scene()
    walls = scenes.diffuse("Walls", (1.0, 1.0, 1.0))
    ceiling = scenes.furnace_material(1.0, 1.0)
    sides = enumerate(scenes.ROOM_SIDES)
    scenes.mesh_object("Room", [scenes.grid(o, u, v, 4, 4) + (int(i == 1),) for i, (o, u, v) in sides],
                       [walls, ceiling])


def test_a_diverging_solve_is_a_report_and_changes_nothing():
    """Albedo 1 everywhere: nothing absorbs, the over-relaxed solve diverges. The core's message
    is the report, from the operator and from bake(); the batch command exits 1 with it."""
    room_that_absorbs_nothing()
    before = harness.file_state()
    message = harness.operator_error()
    assert message is not None, "a bake of a room that absorbs nothing finished"
    assert "Bake Radiosity failed" in message and "diverged" in message, message
    assert "Traceback" not in message, message
    assert harness.file_state() == before
    try:
        addon.bake(bpy.context.scene)
    except pipeline.BakeError as error:
        assert "diverged" in str(error), error
    else:
        raise AssertionError("bake() of a diverging solve returned")
    assert harness.file_state() == before

    source = os.path.join(args.work, "diverging.blend")
    bpy.ops.wm.save_as_mainfile(filepath=source, copy=True)
    run = subprocess.run(harness.batch_command(source, "--output", os.path.join(args.work, "diverging-baked.blend")),
                         capture_output=True, text=True, timeout=600)
    print(run.stderr[-800:])
    assert run.returncode == 1, run.returncode
    assert "Bake Radiosity failed: Gauss-Seidel diverged" in run.stderr and "Traceback" not in run.stderr


def test_an_unwritable_media_folder_fails_before_the_solve():
    """Fog whose grids would go into a folder that cannot be made (its parent is a file): the bake
    says so before any form factor is computed, and the file is as it was."""
    scenes.room_with_panel(0.5)
    fog = scenes.fog_material()
    scenes.mesh_object("Fog", [scenes.grid(o, u, v, 1, 1) + (0,) for o, u, v in
                               [((0.5 + 0.5 * o[0], 0.5 + 0.5 * o[1], 0.5 + 0.5 * o[2]),
                                 tuple(0.5 * c for c in u), tuple(0.5 * c for c in v))
                                for o, u, v in scenes.ROOM_SIDES]], [fog])
    blocker = os.path.join(args.work, "a-file")
    with open(blocker, "w") as handle:
        handle.write("not a folder")
    bpy.context.scene.radiosity.media_folder = os.path.join(blocker, "media")
    before = harness.file_state()
    solved = []
    original_solve = pipeline.BakeJob.solve
    pipeline.BakeJob.solve = lambda job, progress=None: solved.append(job) or original_solve(job, progress)
    try:
        message = harness.operator_error()
    finally:
        pipeline.BakeJob.solve = original_solve
    assert message is not None, "a bake into an unwritable media folder finished"
    assert "Media Folder" in message and "a-file" in message and "Traceback" not in message, message
    assert not solved, "the bake solved before finding that its files cannot be written"
    assert harness.file_state() == before


def test_a_non_finite_vertex_at_the_default_settings_is_skipped_and_named():
    """A NaN vertex must not decide the automatic element size: its faces are skipped with a
    warning naming the object, at the default quality as with an explicit element size."""
    scenes.room_with_panel(0.5)
    broken = scenes.mesh_object("Broken", [scenes.grid((0.5, 0.5, 0.5), (0.3, 0, 0), (0, 0.3, 0), 1, 1) + (0,)])
    broken.data.vertices[0].co = (math.nan, 0.5, 0.5)
    start = time.perf_counter()
    summary = addon.bake(bpy.context.scene)
    print("baked in %.1f s" % (time.perf_counter() - start))
    named = [w for w in summary["warnings"] if "Broken face 0" in w]
    assert named, summary["warnings"]
    room = harness.corner_colors(bpy.data.objects["Room"].data, "Radiosity")
    assert (room > 0.0).all() and (room < 100.0).all(), (room.min(), room.max())


harness.run(test_a_diverging_solve_is_a_report_and_changes_nothing,
            test_an_unwritable_media_folder_fails_before_the_solve,
            test_a_non_finite_vertex_at_the_default_settings_is_skipped_and_named)
