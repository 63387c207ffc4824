"""Scenes as a battery of awkward inputs makes them, in a 2 m room lit by a panel: a bake with the
viewport previewing materials, walls modelled with their normals outwards, a stray triangle far
away, objects that are not meshes, and input that cannot be baked as asked."""

import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402
import numpy as np  # noqa: E402

import harness  # noqa: E402
import scenes  # noqa: E402

args = harness.arguments()
addon = harness.install_addon(args.addon_zip)
pipeline = sys.modules[harness.MODULE + ".pipeline"]


def set_viewport_shading(shading_type):
    for screen in bpy.data.screens:
        for area in screen.areas:
            if area.type == "VIEW_3D":
                area.spaces.active.shading.type = shading_type


def test_the_real_materials_bake_whatever_the_viewport_previews():
    """A red block in the room, baked once in Solid shading, then again with the baked light
    previewed (Preview Radiosity: an emission material on every baked object) and the viewport in
    Material Preview and Rendered: the block stays red and every colour equals the Solid bake."""
    room = scenes.room_with_panel()
    block = scenes.mesh_object("Block", scenes.block((0.6, 0.6), (1.2, 1.0), 0.5, 0.25),
                               [scenes.diffuse("Red", scenes.RED)])
    settings = bpy.context.scene.radiosity
    settings.element_size, settings.hemicube_resolution = 0.25, 64
    set_viewport_shading("SOLID")
    addon.bake(bpy.context.scene)
    solid = {o.name: harness.corner_colors(o.data, "Radiosity") for o in (room, block)}
    red = solid["Block"].mean(axis=0)
    assert red[0] > 4.0 * red[1] > 0.0, red

    assert bpy.ops.radiosity.preview() == {"FINISHED"}
    for shading_type in ("MATERIAL", "RENDERED"):
        set_viewport_shading(shading_type)
        summary = addon.bake(bpy.context.scene)
        assert not any("Radiosity Preview" in w for w in summary["warnings"]), summary["warnings"]
        for obj in (room, block):
            baked = harness.corner_colors(obj.data, "Radiosity")
            np.testing.assert_allclose(baked, solid[obj.name], rtol=1e-5, atol=1e-7,
                                       err_msg="%s baked in %s" % (obj.name, shading_type))
    assert bpy.ops.radiosity.bake() == {"FINISHED"}
    np.testing.assert_allclose(harness.corner_colors(block.data, "Radiosity"), solid["Block"], rtol=1e-5)
    assert bpy.ops.radiosity.preview() == {"FINISHED"}  # off again: the artist's materials are back
    assert block.material_slots[0].material.name == "Red"


def closed_cube(name, corner, size):
    """The six faces of a cube (outward normals), its bottom face on whatever it stands on."""
    sides = [((0, 0, 0), (0, 1, 0), (1, 0, 0)), ((0, 0, 1), (1, 0, 0), (0, 1, 0)),
             ((0, 0, 0), (1, 0, 0), (0, 0, 1)), ((0, 1, 0), (0, 0, 1), (1, 0, 0)),
             ((0, 0, 0), (0, 0, 1), (0, 1, 0)), ((1, 0, 0), (0, 1, 0), (0, 0, 1))]
    corner = np.asarray(corner, dtype=np.float64)
    return scenes.mesh_object(name, [scenes.grid(corner + size * np.array(o), size * np.array(u), size * np.array(v),
                                                 1, 1) + (0,) for o, u, v in sides],
                              [scenes.diffuse(name, (0.5, 0.5, 0.5))])


def test_a_room_with_outward_normals_is_named():
    """The room modelled with its normals outwards bakes black, as Cycles' bake of it does (both
    light a face's front); the bake names the room and how many of its faces turn away from the
    light. A cube standing on the floor of a well-made room, whose bottom face is black too, is not
    named: nothing lights its back."""
    room = scenes.room_with_panel()
    room.data.flip_normals()
    summary = addon.bake(bpy.context.scene, quality="DRAFT")
    assert harness.corner_colors(room.data, "Radiosity").max() == 0.0
    named = [w for w in summary["warnings"] if "turned away" in w]
    assert len(named) == 1 and "object 'Room' (96 faces)" in named[0], summary["warnings"]
    cycles = harness.cycles_corner_bake(room, 4, 1)
    assert cycles.max() == 0.0, cycles.max()

    room.data.flip_normals()
    cube = closed_cube("Cube", (0.3, 0.3, 0.0), 0.4)
    summary = addon.bake(bpy.context.scene, quality="DRAFT")
    assert harness.corner_colors(room.data, "Radiosity").mean() > 0.05
    assert harness.corner_colors(cube.data, "Radiosity").min() == 0.0, "the cube's bottom face is lit"
    assert not any("turned away" in w for w in summary["warnings"]), summary["warnings"]


def test_a_stray_triangle_far_away_costs_nothing():
    """One triangle 1e6 m away (1 m across), or 1e30 m away (1e25 m across): the room bakes with the
    settings, colours and about the time it has alone, and the triangle is named as left out."""
    room = scenes.room_with_panel()
    start = time.perf_counter()
    alone = addon.bake(bpy.context.scene, quality="DRAFT")
    seconds_alone = time.perf_counter() - start
    lit_alone = harness.corner_colors(room.data, "Radiosity")
    for distance, size in ((1e6, 1.0), (1e30, 1e25)):
        stray = scenes.mesh_object("Stray", [(distance + size * np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]]),
                                              np.array([[0, 1, 2]]), 0)])
        start = time.perf_counter()
        summary = addon.bake(bpy.context.scene, quality="DRAFT")
        seconds = time.perf_counter() - start
        print("stray at %g m: %.1f s (room alone %.1f s), resolution %d x %d, element size %.3g m"
              % (distance, seconds, seconds_alone, summary["resolution"], summary["hemicube_rotations"],
                 summary["element_size"]))
        named = [w for w in summary["warnings"] if "left out" in w]
        assert len(named) == 1 and "object 'Stray' (1 face)" in named[0], summary["warnings"]
        assert not any("skipped" in w for w in summary["warnings"]), summary["warnings"]
        for key in ("resolution", "hemicube_rotations", "element_size", "elements"):
            assert summary[key] == alone[key], (key, summary[key], alone[key])
        assert seconds < 2.0 * seconds_alone + 2.0, (seconds, seconds_alone)
        np.testing.assert_allclose(harness.corner_colors(room.data, "Radiosity"), lit_alone, rtol=1e-6)
        bpy.data.objects.remove(stray)


def text_curve_and_metaball():
    """A 30 cm text, a bevelled curve across the room and a metaball, as an artist adds them."""
    text = bpy.data.curves.new("Text", "FONT")
    text.body, text.extrude, text.size = "Hello", 0.02, 0.3
    curve = bpy.data.curves.new("Curve", "CURVE")
    curve.dimensions, curve.bevel_depth = "3D", 0.03
    spline = curve.splines.new("BEZIER")
    spline.bezier_points.add(1)
    spline.bezier_points[0].co, spline.bezier_points[1].co = (0.3, 0.3, 0.3), (1.6, 1.6, 1.0)
    for point in spline.bezier_points:
        point.handle_left_type = point.handle_right_type = "AUTO"
    ball = bpy.data.metaballs.new("Meta")
    ball.resolution = 0.05
    ball.elements.new().radius = 0.3
    for data, location in ((text, (0.3, 1.0, 0.5)), (curve, (0.0, 0.0, 0.0)), (ball, (1.4, 0.6, 0.4))):
        obj = bpy.data.objects.new(data.name, data)
        obj.location = location
        bpy.context.scene.collection.objects.link(obj)
        obj.data.materials.append(scenes.diffuse(data.name, (0.6, 0.6, 0.6)))


def test_text_curves_and_metaballs_bake_once_and_quickly():
    """Text, a bevelled curve and a metaball each bake as the one mesh Cycles renders of them (the
    depsgraph lists that mesh as an instance besides the object itself), so the hierarchical bake
    meets no doubled, coincident surfaces; with them it ran over 5 minutes without converging.
    The truth: the same scene with the three converted to meshes."""
    scenes.room_with_panel()
    text_curve_and_metaball()
    keywords = dict(method="HIERARCHICAL", element_size=0.064, tolerance=1e-4, refine_tolerance=0.02)
    start = time.perf_counter()
    summary = addon.bake(bpy.context.scene, **keywords)
    seconds = time.perf_counter() - start
    print("text, curve and metaball: %d elements (%d faces), %.1f s, residual %.2g"
          % (summary["elements"], summary["hierarchy"]["patches"], seconds, summary["residual"]))
    assert summary["converged"] and seconds < 120.0, (summary["converged"], seconds)

    depsgraph = bpy.context.evaluated_depsgraph_get()
    for name in ("Text", "Curve", "Meta"):
        obj = bpy.data.objects[name]
        mesh = bpy.data.meshes.new_from_object(obj.evaluated_get(depsgraph))
        converted = bpy.data.objects.new(name + " mesh", mesh)
        converted.matrix_world = obj.matrix_world
        bpy.context.scene.collection.objects.link(converted)
        obj.hide_render = True
    converted = addon.bake(bpy.context.scene, **keywords)
    assert summary["hierarchy"]["patches"] == converted["hierarchy"]["patches"], \
        (summary["hierarchy"]["patches"], converted["hierarchy"]["patches"])


def test_an_array_modifier_and_a_missing_volume_file_are_named():
    """An Array modifier on target Original: the warning names the modifier and says that Subdivided
    Copies bakes the object. A Volume object whose .vdb file is missing: named with its file, with
    and without a volume material."""
    room = scenes.room_with_panel()
    shelf = scenes.mesh_object("Shelf", [scenes.grid((0.2, 0.2, 0.6), (0.3, 0, 0), (0, 0.3, 0), 1, 1) + (0,)],
                               [scenes.diffuse("Shelf", (0.5, 0.5, 0.5))])
    shelf.modifiers.new("Shelves", "ARRAY").relative_offset_displace = (0.0, 0.0, 1.0)
    summary = addon.bake(bpy.context.scene, quality="DRAFT")
    named = [w for w in summary["warnings"] if "Shelf" in w]
    assert len(named) == 1 and "Shelves" in named[0] and "Target: Subdivided Copies bakes" in named[0], \
        summary["warnings"]
    summary = addon.bake(bpy.context.scene, quality="DRAFT", target="COPIES")
    assert not any("Shelf" in w for w in summary["warnings"]), summary["warnings"]
    copies = [o for o in bpy.data.objects if o.get("radiosity_bake_copy") == "Shelf"]
    assert copies and harness.corner_colors(copies[0].data, "Radiosity").mean() > 0.0, copies
    bpy.data.objects.remove(shelf)
    assert room.name == "Room"

    missing = os.path.join(args.work, "no-such-folder", "smoke.vdb")
    for with_material in (False, True):
        volume = bpy.data.volumes.new("Smoke")
        volume.filepath = missing
        if with_material:
            volume.materials.append(scenes.fog_material())
        smoke = bpy.data.objects.new("Smoke", volume)
        smoke.location = (1.0, 1.0, 1.0)
        bpy.context.scene.collection.objects.link(smoke)
        summary = addon.bake(bpy.context.scene, quality="DRAFT")
        named = [w for w in summary["warnings"] if "'Smoke'" in w and missing in w and "not found" in w]
        assert len(named) == 1, (with_material, summary["warnings"])
        bpy.data.objects.remove(smoke)


def test_the_batch_command_reports_every_phase():
    """The batch command prints a line as each phase starts, the add-on's own (export, settings,
    write-back) and the core's (building elements, form factors, solve, final gather), in the order
    they run."""
    scenes.room_with_panel()
    source = os.path.join(args.work, "room.blend")
    bpy.ops.wm.save_as_mainfile(filepath=source, copy=True)
    run = subprocess.run(harness.batch_command(source, "--quality", "DRAFT",
                                               "--output", os.path.join(args.work, "room-baked.blend")),
                         capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr[-800:]
    lines = [line for line in run.stdout.splitlines() if line.startswith("Bake Radiosity: ")]
    print("\n".join(lines))
    phases = ["exporting", "choosing settings", "preparing", "form factors", "solving", "final gather", "writing",
              "saved"]
    first = [next((k for k, line in enumerate(lines) if line.startswith("Bake Radiosity: " + p)), None)
             for p in phases]
    assert None not in first and first == sorted(first), dict(zip(phases, first))


harness.run(test_the_real_materials_bake_whatever_the_viewport_previews,
            test_a_room_with_outward_normals_is_named,
            test_a_stray_triangle_far_away_costs_nothing,
            test_text_curves_and_metaballs_bake_once_and_quickly,
            test_an_array_modifier_and_a_missing_volume_file_are_named,
            test_the_batch_command_reports_every_phase)
