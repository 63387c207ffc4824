"""A re-bake after a lighting or material edit, through the panel's operator: the Cornell box lit by
its ceiling opening and a soft point lamp, baked at Medium.

- the first bake in the session bakes the geometry afresh and keeps it (the summary says so);
- after moving the lamp, changing its power, its colour or its size, the opening's emission
  strength or a wall's colour, the operator's bake reuses it (the summary says so) and its colours
  are, to the bit, those of a bake from scratch (bake(reuse=False));
- after moving one of the box's vertices, or with a modifier that changes the mesh, it bakes the
  geometry afresh and says why;
- with the box's walls cut into small faces, which the bake solves together and no larger than half
  their distance from a lamp, the lamp brought down to the floor: the re-bake merges them again and
  computes their form factors anew (the summary says so), and its colours are a bake from scratch's;
- the batch command given two scenes that show the same box, one without the lamp, bakes the
  second over the first one's geometry."""

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

REUSED = "Reused the geometry of the previous bake ("
MERGED_AGAIN = ("Reused the geometry of the previous bake, its form factors computed again (the faces beside the moved "
                "lamps merge otherwise) (")
CHANGED = "Baked the geometry afresh (the geometry, or a setting that chooses the elements, changed)"


def make_scene(cells=6):
    scenes.clear_scene()
    scenes.cornell_box(light="MESH", cells=cells)
    light = bpy.data.lights.new("Lamp", "POINT")
    light.energy, light.shadow_soft_size = 20.0, 0.05
    lamp = bpy.data.objects.new("Lamp", light)
    lamp.location = (0.3, 0.3, 0.6)
    bpy.context.scene.collection.objects.link(lamp)
    bpy.context.scene.radiosity.quality = "MEDIUM"


def operator_bake(attribute):
    """The panel's Bake into `attribute`; its colours and the cost line."""
    bpy.context.scene.radiosity.attribute_name = attribute
    assert bpy.ops.radiosity.bake() == {"FINISHED"}
    cost = bpy.context.scene.radiosity.last_cost
    print(cost)
    return harness.corner_colors(bpy.data.objects["Cornell Box"].data, attribute), cost


def fresh_bake(attribute):
    """A bake from scratch (the session's cache let go) into `attribute`; its colours."""
    bpy.context.scene.radiosity.attribute_name = attribute
    summary = addon.bake(bpy.context.scene, reuse=False)
    assert summary["cache"] is None, summary["cache"]
    return harness.corner_colors(bpy.data.objects["Cornell Box"].data, attribute)


def edits():
    lamp, emission = bpy.data.objects["Lamp"], bpy.data.materials["Light"]
    strength = next(n for n in emission.node_tree.nodes if n.type == "EMISSION").inputs["Strength"]
    red = next(n for n in bpy.data.materials["Red"].node_tree.nodes if n.type == "BSDF_DIFFUSE").inputs["Color"]
    return [
        ("the lamp moved", lambda: setattr(lamp, "location", (0.7, 0.4, 0.7))),
        ("the lamp's power", lambda: setattr(lamp.data, "energy", 35.0)),
        ("the lamp's colour", lambda: setattr(lamp.data, "color", (1.0, 0.6, 0.3))),
        ("the lamp's size", lambda: setattr(lamp.data, "shadow_soft_size", 0.15)),
        ("the opening's strength", lambda: setattr(strength, "default_value", strength.default_value * 0.5)),
        ("the red wall's colour", lambda: setattr(red, "default_value", (0.1, 0.2, 0.6, 1.0))),
    ]


def test_a_rebake_after_a_lighting_edit_reuses_the_geometry_and_equals_a_bake_from_scratch():
    make_scene()
    _, cost = operator_bake("First")
    assert "Baked the geometry afresh (no earlier bake was kept) and kept it for the next bake (" in cost, cost
    for name, edit in edits():
        edit()
        colours, cost = operator_bake("Rebake")
        assert REUSED in cost, (name, cost)
        fresh = fresh_bake("Fresh")
        worst = float(np.abs(colours - fresh).max())
        print("%s: re-bake against a bake from scratch, largest difference %.3g" % (name, worst))
        assert np.array_equal(colours, fresh), (name, worst)
        operator_bake("Rebake")  # the cache again, for the next edit (the fresh bake let it go)


def test_a_lamp_brought_beside_merged_faces_merges_them_again():
    make_scene(cells=48)  # faces of 2.1 cm, under half Medium's elements of 5.7 cm: pairs merge
    operator_bake("First")
    bpy.data.objects["Lamp"].location = (0.3, 0.3, 0.05)
    colours, cost = operator_bake("Rebake")
    assert MERGED_AGAIN in cost, cost
    fresh = fresh_bake("Fresh")
    worst = float(np.abs(colours - fresh).max())
    print("the lamp brought to the floor: re-bake against a bake from scratch, largest difference %.3g" % worst)
    assert np.array_equal(colours, fresh), worst


def test_a_change_of_geometry_bakes_afresh():
    make_scene()
    operator_bake("First")
    mesh = bpy.data.objects["Cornell Box"].data
    mesh.vertices[0].co.z -= 0.01
    mesh.update()
    _, cost = operator_bake("Moved")
    assert CHANGED in cost, cost
    _, cost = operator_bake("Again")
    assert REUSED in cost, cost
    bpy.data.objects["Cornell Box"].modifiers.new("Displace", "DISPLACE").strength = 0.01  # 5 mm along the normals
    _, cost = operator_bake("Displaced")
    assert CHANGED in cost, cost


def test_the_batch_command_bakes_lighting_variants_over_one_geometry():
    make_scene()
    first = bpy.context.scene
    first.radiosity.attribute_name = "Lamp and opening"
    bpy.ops.scene.new(type="LINK_COPY")
    variant = bpy.context.scene
    variant.name, variant.radiosity.attribute_name = "Opening only", "Opening only"
    variant.collection.objects.unlink(bpy.data.objects["Lamp"])
    source = os.path.join(args.work, "variants.blend")
    bpy.ops.wm.save_as_mainfile(filepath=source, copy=True)
    run = subprocess.run(harness.batch_command(source, "--scene", first.name, "--scene", variant.name,
                                               "--output", os.path.join(args.work, "variants-baked.blend")),
                         capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr[-800:]
    costs = [line for line in run.stdout.splitlines() if line.startswith("Bake Radiosity: Cost: ")]
    print("\n".join(costs))
    assert len(costs) == 2, run.stdout[-2000:]
    assert "Baked the geometry afresh (no earlier bake was kept)" in costs[0], costs[0]
    assert REUSED in costs[1], costs[1]


harness.run(test_a_rebake_after_a_lighting_edit_reuses_the_geometry_and_equals_a_bake_from_scratch,
            test_a_lamp_brought_beside_merged_faces_merges_them_again,
            test_a_change_of_geometry_bakes_afresh,
            test_the_batch_command_bakes_lighting_variants_over_one_geometry)
