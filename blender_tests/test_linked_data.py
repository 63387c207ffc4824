"""Meshes linked from another .blend file, whose light would not be saved with the file that links
them: refused before any work and named, or (Make Linked Meshes Local) baked into local meshes whose
light survives saving and reopening. And a scene lit only by an emitter among black surfaces: every
number the summary, its report lines and bake()'s dictionary hold is finite or said in words."""

import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402
import numpy as np  # noqa: E402

import harness  # noqa: E402
import scenes  # noqa: E402

args = harness.arguments()
addon = harness.install_addon(args.addon_zip)
pipeline = sys.modules[harness.MODULE + ".pipeline"]
LIBRARY = os.path.join(args.work, "room-library.blend")


def write_library():
    """A .blend holding the room of scenes.room_with_panel (without its panel) in a collection 'Set'."""
    scenes.clear_scene()
    walls = scenes.diffuse("Walls", (0.5, 0.5, 0.5))
    room = scenes.mesh_object("Room", [scenes.grid(o, u, v, 4, 4) + (0,) for o, u, v in scenes.ROOM_SIDES], [walls])
    bpy.context.scene.collection.objects.unlink(room)
    collection = bpy.data.collections.new("Set")
    collection.objects.link(room)
    bpy.context.scene.collection.children.link(collection)
    bpy.ops.wm.save_as_mainfile(filepath=LIBRARY, copy=True)


def fresh_scene():
    """An empty scene with no library linked, the option off."""
    scenes.clear_scene()
    for library in list(bpy.data.libraries):
        bpy.data.libraries.remove(library)
    bpy.context.scene.radiosity.make_linked_local = False


def local_panel():
    scenes.mesh_object("Panel", [scenes.grid((0.75, 0.75, 1.9), (0, 0.5, 0), (0.5, 0, 0), 1, 1) + (0,)],
                       [scenes.emission("Panel", (1.0, 1.0, 1.0), 5.0)])


def linked_room():
    """A new scene: the library's room linked in (File > Link of the object), lit by a local panel."""
    fresh_scene()
    with bpy.data.libraries.load(LIBRARY, link=True) as (_, into):
        into.objects = ["Room"]
    room = into.objects[0]
    bpy.context.scene.collection.objects.link(room)
    local_panel()
    assert room.library is not None and room.data.library is not None
    return room


def overridden_room():
    """A new scene: the library's collection linked and made a library override (Object > Library
    Override > Make): the object is an override, its mesh still linked."""
    fresh_scene()
    with bpy.data.libraries.load(LIBRARY, link=True) as (_, into):
        into.collections = ["Set"]
    linked = into.collections[0]
    bpy.context.scene.collection.children.link(linked)
    linked.override_hierarchy_create(bpy.context.scene, bpy.context.view_layer)
    bpy.context.scene.collection.children.unlink(linked)  # the override takes its place, as Make does
    local_panel()
    room = next(o for o in bpy.context.scene.objects if o.name == "Room")
    assert room.override_library is not None and room.library is None and room.data.library is not None
    return room


def overridden_mesh_room():
    """overridden_room with its mesh overridden too: a library override's geometry is not saved either."""
    room = overridden_room()
    room.data.override_create(remap_local_usages=True)
    assert room.data.library is None and room.data.override_library is not None
    return room


class NoWork:
    """Fails the test if the bake chooses its settings (the first step of any work after reading
    the scene), and counts whether it was asked to."""

    def __init__(self):
        self.calls = 0

    def __call__(self, *arguments, **keywords):
        self.calls += 1
        raise AssertionError("the bake started working on a scene it must refuse")


def assert_refused_before_any_work(bake):
    before = harness.file_state()
    no_work = NoWork()
    with harness.patched_setting("choose", no_work):
        message = bake()
    assert no_work.calls == 0, message
    assert message is not None, "a bake onto a linked mesh finished"
    assert "'Room'" in message and "Make Linked Meshes Local" in message and "Make Local" in message, message
    assert "linked" in message and "Traceback" not in message, message
    assert harness.file_state() == before
    return message


def bake_error(**overrides):
    try:
        addon.bake(bpy.context.scene, **overrides)
    except pipeline.BakeError as error:
        return str(error)
    return None


def reopened_light(path):
    bpy.ops.wm.open_mainfile(filepath=path)
    room = bpy.data.objects[("Room", None)]
    assert room.data.library is None and room.data.override_library is None, room.data
    return harness.corner_colors(room.data, "Radiosity")


def test_a_linked_room_is_refused_before_any_work_and_named():
    for make in (linked_room, overridden_room, overridden_mesh_room):
        make()
        message = assert_refused_before_any_work(harness.operator_error)
        assert "room-library.blend" in message, message
        assert_refused_before_any_work(bake_error)
        print(make.__name__, message)

    # The batch command: exit code 1, the same words, nothing saved.
    linked_room()
    source, output = os.path.join(args.work, "linking.blend"), os.path.join(args.work, "linking-baked.blend")
    bpy.ops.wm.save_as_mainfile(filepath=source, copy=True)
    run = subprocess.run(harness.batch_command(source, "--output", output), capture_output=True, text=True,
                         timeout=600)
    assert run.returncode == 1, (run.returncode, run.stderr[-800:])
    assert "Bake Radiosity failed: The light would be lost" in run.stderr and "'Room'" in run.stderr, run.stderr
    assert not os.path.exists(output)


def test_a_linked_room_baked_into_a_local_mesh_keeps_its_light_after_reopening():
    for make, how in ((linked_room, "operator"), (overridden_room, "bake()"), (overridden_mesh_room, "bake()")):
        make()
        if how == "operator":
            bpy.context.scene.radiosity.make_linked_local = True
            assert harness.operator_error() is None
            warnings = []
        else:
            warnings = addon.bake(bpy.context.scene, make_linked_local=True)["warnings"]
            assert any("meshes of" in w and "local to hold" in w and "'Room'" in w for w in warnings), warnings
        room = bpy.data.objects[("Room", None)]
        assert room.data.library is None and room.data.override_library is None
        baked = harness.corner_colors(room.data, "Radiosity")
        # A 2 m room of albedo 0.5 under a 5 W/(m^2 sr) panel of 0.25 m^2: lit, nowhere black.
        assert baked.min() > 0.01 and 0.05 < baked.mean() < 2.0, (baked.min(), baked.mean())
        path = os.path.join(args.work, "baked-%s.blend" % make.__name__)
        bpy.ops.wm.save_as_mainfile(filepath=path)
        reopened = reopened_light(path)
        np.testing.assert_array_equal(reopened, baked)
        print("%s (%s): light after reopening, mean %.4f, min %.4f" % (make.__name__, how, reopened.mean(),
                                                                       reopened.min()))


def test_one_undo_takes_back_the_bake_and_the_local_mesh():
    linked_room()
    bpy.context.scene.radiosity.make_linked_local = True
    bpy.ops.ed.undo_push(message="before bake")
    before = harness.file_state()
    # As a click does: scripts only push an undo step when asked (the second argument).
    assert bpy.ops.radiosity.bake("EXEC_DEFAULT", True) == {"FINISHED"}
    room = bpy.data.objects[("Room", None)]
    assert room.data.color_attributes.get("Radiosity") is not None
    bpy.ops.ed.undo()
    assert harness.file_state() == before, "one undo did not remove the bake"
    room = bpy.data.objects["Room"]  # undo replaces every Python reference to data
    assert room.library is not None and room.data.library is not None, "undo left the room local"
    bpy.ops.ed.redo()
    room = bpy.data.objects[("Room", None)]
    assert room.data.library is None and room.data.color_attributes.get("Radiosity") is not None, "redo lost the bake"


def test_an_object_only_a_linked_collection_holds_is_refused_even_with_the_option():
    """File > Link of a collection, linked into the scene as it is: its objects cannot be made local
    alone (the collection holds them), so the bake says what to do instead."""
    fresh_scene()
    with bpy.data.libraries.load(LIBRARY, link=True) as (_, into):
        into.collections = ["Set"]
    bpy.context.scene.collection.children.link(into.collections[0])
    local_panel()
    bpy.context.scene.radiosity.make_linked_local = True
    message = assert_refused_before_any_work(harness.operator_error)
    assert "collection 'Set'" in message and "Library Override > Make" in message, message


def non_finite(value, path="summary"):
    """The paths of every float in `value` (dicts and lists within) that is NaN or infinite."""
    if isinstance(value, dict):
        return [p for key, item in value.items() for p in non_finite(item, "%s[%r]" % (path, key))]
    if isinstance(value, (list, tuple)):
        return [p for index, item in enumerate(value) for p in non_finite(item, "%s[%d]" % (path, index))]
    if isinstance(value, (float, np.floating)) and not math.isfinite(value):
        return [path]
    return []


def test_an_emitter_among_black_surfaces_has_no_nan_in_its_summary():
    """The room excluded from the view layer leaves only the panel; or the room black. Nothing
    reflects light, so the error estimate says so in words."""
    for case in ("room excluded", "black room"):
        scenes.room_with_panel(albedo=0.0 if case == "black room" else 0.5)
        if case == "room excluded":
            room = bpy.data.objects["Room"]
            bpy.context.scene.collection.objects.unlink(room)
            hidden = bpy.data.collections.new("Hidden")
            hidden.objects.link(room)
            bpy.context.scene.collection.children.link(hidden)
            bpy.context.view_layer.layer_collection.children["Hidden"].exclude = True
        for overrides in ({}, {"final_gather": False, "quality": "DRAFT"}):
            summary = addon.bake(bpy.context.scene, **overrides)
            assert non_finite(summary) == [], non_finite(summary)
            lines = bpy.context.scene.radiosity.last_report + " " + bpy.context.scene.radiosity.last_accuracy
            print(case, overrides, lines)
            assert "nan" not in lines.lower() and "inf" not in lines.lower(), lines
            assert "no reflected light to estimate from" in lines, lines
            assert summary["error_estimate"]["undefined"] == "no reflected light to estimate from", summary
        assert harness.operator_error() is None
        assert "no reflected light" in bpy.context.scene.radiosity.last_accuracy


write_library()
harness.run(test_a_linked_room_is_refused_before_any_work_and_named,
            test_a_linked_room_baked_into_a_local_mesh_keeps_its_light_after_reopening,
            test_one_undo_takes_back_the_bake_and_the_local_mesh,
            test_an_object_only_a_linked_collection_holds_is_refused_even_with_the_option,
            test_an_emitter_among_black_surfaces_has_no_nan_in_its_summary)
