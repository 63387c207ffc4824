"""Light groups as baked layers, through the panel's operators: a floor, a wall and a block lit by two
point lamps in the light groups 'Key' and 'Fill' and by a uniform World in 'Sky', baked at the
default preset with Light Group Layers on.

- the three layers sum to the usual attribute (1e-5 of each corner);
- each layer is the bake of its group's sources alone, the others' power (or the World's strength)
  at 0 (1e-4);
- Wire Baked Light's mix with strengths (2, 0.5, 1), as Cycles renders the wired material (a Cycles
  Emit bake of it into a colour attribute), is the layers' sum so weighted (1e-5) and matches a bake
  with the Key lamp's power doubled and the Fill lamp's halved, rendered the same way (0.5% of each
  corner): Cycles takes a corner's colour a little inside its faces, so both sides go through it;
- Apply Light Mix writes that mix into the usual attribute;
- with a memory budget that holds the form factors but not the layers too, the bake says so and
  bakes without them;
- the hierarchical method bakes the layers over one refinement: they sum to its attribute."""

import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402
import numpy as np  # noqa: E402

import harness  # noqa: E402
import scenes  # noqa: E402
import world_scenes  # noqa: E402

args = harness.arguments()
addon = harness.install_addon(args.addon_zip)

GROUPS = ("Key", "Fill", "Sky")
STRENGTHS = {"Key": 2.0, "Fill": 0.5, "Sky": 1.0}
LAMPS = {"Key": ((1.2, -1.0, 1.8), 300.0), "Fill": ((-1.5, 1.2, 1.2), 150.0)}
SUM_TOLERANCE = 1e-5
ALONE_TOLERANCE = 1e-4
MIX_TOLERANCE = 0.005


def make_scene():
    scenes.clear_scene()
    grey, red = scenes.diffuse("Grey", (0.7, 0.7, 0.7)), scenes.diffuse("Red", (0.7, 0.2, 0.1))
    scenes.mesh_object("Floor", [scenes.grid((-2, -2, 0), (4, 0, 0), (0, 4, 0), 8, 8) + (0,)], [grey])
    scenes.mesh_object("Wall", [scenes.grid((-2, 2, 0), (4, 0, 0), (0, 0, 2), 8, 4) + (0,)], [red])
    scenes.mesh_object("Block", scenes.block((-0.4, -0.4), (0.4, 0.4), 0.8, 0.2), [grey])
    view_layer = bpy.context.view_layer
    for group in GROUPS:
        view_layer.lightgroups.add(name=group)
    for group, (location, watts) in LAMPS.items():
        light = bpy.data.lights.new(group, "POINT")
        light.energy, light.shadow_soft_size = watts, 0.0
        lamp = bpy.data.objects.new(group, light)
        lamp.location = location
        lamp.lightgroup = group
        bpy.context.scene.collection.objects.link(lamp)
    world = world_scenes.uniform_world((0.05, 0.07, 0.1))
    world.lightgroup = "Sky"
    settings = bpy.context.scene.radiosity
    settings.quality = "MEDIUM"
    settings.light_group_layers = True


def bake(attribute, layers):
    settings = bpy.context.scene.radiosity
    settings.attribute_name, settings.light_group_layers = attribute, layers
    assert bpy.ops.radiosity.bake() == {"FINISHED"}


def colours(name):
    """Every baked mesh's corner colours of attribute `name`, in one array."""
    return np.concatenate([harness.corner_colors(bpy.data.objects[o].data, name) for o in ("Floor", "Wall", "Block")])


def worst_relative(values, truth):
    """The worst |values - truth| over the truth at each corner (corners of at least 1e-3 of the brightest)."""
    scale = np.maximum(np.abs(truth), 1e-3 * np.abs(truth).max())
    return float((np.abs(values - truth) / scale).max())


def set_sources(strengths):
    """Each lamp's power and the World's strength times `strengths[group]`."""
    for group, (_, watts) in LAMPS.items():
        bpy.data.lights[group].energy = watts * strengths[group]
    background = next(n for n in bpy.context.scene.world.node_tree.nodes if n.type == "BACKGROUND")
    background.inputs["Strength"].default_value = strengths["Sky"]


def test_layers_sum_and_each_is_its_group_alone():
    make_scene()
    bake("Radiosity", layers=True)
    settings = bpy.context.scene.radiosity
    groups = [layer.group for layer in settings.light_layers]
    assert groups == list(GROUPS), groups
    assert "3 light group layers (Key, Fill, Sky;" in settings.last_report, settings.last_report
    total = colours("Radiosity")
    layers = {group: colours("Radiosity " + group) for group in GROUPS}
    error = worst_relative(sum(layers.values()), total)
    print("layers' sum against the usual attribute: worst corner %.2g" % error)
    assert error < SUM_TOLERANCE, error
    for group in GROUPS:
        set_sources({g: 1.0 if g == group else 0.0 for g in GROUPS})
        bake("Alone " + group, layers=False)
        error = worst_relative(layers[group], colours("Alone " + group))
        print("layer %s against the bake of its sources alone: worst corner %.2g" % (group, error))
        assert error < ALONE_TOLERANCE, (group, error)
    set_sources({g: 1.0 for g in GROUPS})


def emit_bake(obj, name):
    """Cycles' Emit bake of `obj`'s material into the colour attribute `name`: what the wired shader renders."""
    harness.use_unbiased_cycles(samples=1, seed=1)
    bpy.context.scene.render.bake.target = "VERTEX_COLORS"
    attributes = obj.data.color_attributes
    attributes.active_color = attributes.new(name, "FLOAT_COLOR", "CORNER")
    for other in bpy.context.view_layer.objects:
        other.select_set(False)
    obj.select_set(True)
    bpy.context.view_layer.objects.active = obj
    assert bpy.ops.object.bake(type="EMIT", target="VERTEX_COLORS") == {"FINISHED"}
    return harness.corner_colors(obj.data, name)


def render(name):
    """Every baked mesh's wired material rendered by Cycles (emit_bake) into attribute `name`."""
    return np.concatenate([emit_bake(bpy.data.objects[o], name) for o in ("Floor", "Wall", "Block")])


def emission_colour_sockets():
    """The Color input of the Emission shader Wire Baked Light put in each wired material."""
    sockets = []
    for material in bpy.data.materials:
        for node in material.node_tree.nodes if material.node_tree else ():
            if node.name.startswith("Radiosity Wire ") and node.bl_idname == "ShaderNodeEmission":
                sockets.append((material.node_tree, node.inputs["Color"]))
    return sockets


def render_attribute(attribute, name):
    """render(name) with each wired Emission reading `attribute` instead of the mix, which then comes back: Cycles
    samples the corners as it samples the mix's."""
    kept = []
    for tree, socket in emission_colour_sockets():
        kept.append((tree, socket, socket.links[0].from_socket))
        reader = tree.nodes.new("ShaderNodeVertexColor")
        reader.layer_name = attribute
        tree.links.new(reader.outputs["Color"], socket)
    try:
        return render(name)
    finally:
        for tree, socket, source in kept:
            reader = socket.links[0].from_node
            tree.links.new(source, socket)
            tree.nodes.remove(reader)


def write_attribute(name, rgb):
    """(corners, 3) colours over Floor, Wall and Block into their colour attribute `name`."""
    start = 0
    for o in ("Floor", "Wall", "Block"):
        mesh = bpy.data.objects[o].data
        rgba = np.ones((len(mesh.loops), 4), dtype=np.float32)
        rgba[:, :3] = rgb[start:start + len(mesh.loops)]
        start += len(mesh.loops)
        mesh.color_attributes.new(name, "FLOAT_COLOR", "CORNER").data.foreach_set("color", rgba.ravel())


def test_wired_mix_renders_as_the_bake_with_the_lamps_changed():
    set_sources(STRENGTHS)
    bake("Reference", layers=False)  # before wiring: the wired materials emit
    set_sources({g: 1.0 for g in GROUPS})
    settings = bpy.context.scene.radiosity
    settings.attribute_name = "Radiosity"
    assert bpy.ops.radiosity.wire() == {"FINISHED"}
    for layer in settings.light_layers:
        layer.strength = STRENGTHS[layer.group]
    rendered = render("Rendered mix")
    # Cycles takes each corner's colour a little inside its faces, so the mix is compared with renders of
    # attributes through the same shader: the mix computed here (the node group's sums), and the reference bake.
    expected = sum(STRENGTHS[g] * colours("Radiosity " + g) for g in GROUPS)
    write_attribute("Expected mix", expected)
    error = worst_relative(rendered, render_attribute("Expected mix", "Rendered expected mix"))
    print("wired mix (2, 0.5, 1) rendered by Cycles against the sum of the layers so weighted: worst corner %.2g"
          % error)
    assert error < 1e-5, error
    error = worst_relative(rendered, render_attribute("Reference", "Rendered reference"))
    print("wired mix (2, 0.5, 1) rendered by Cycles against the bake with the lamps changed: worst corner %.2g"
          % error)
    assert error < MIX_TOLERANCE, error

    assert bpy.ops.radiosity.apply_light_mix() == {"FINISHED"}
    applied = colours("Radiosity")
    assert worst_relative(applied, expected) < 1e-6
    error = worst_relative(applied, colours("Reference"))
    print("applied mix against the bake with the lamps changed: worst corner %.2g" % error)
    assert error < MIX_TOLERANCE, error
    assert bpy.ops.radiosity.unwire() == {"FINISHED"}  # the wired materials would emit in the next bake


def test_over_the_budget_bakes_without_layers():
    scene = bpy.context.scene
    summary = addon.bake(scene, attribute_name="Measured", light_group_layers=True)
    bound, layer_bytes = summary["matrix_bytes_bound"], summary["light_layers"]["bytes"]
    budget = math.ceil(bound / 2 ** 20)  # megabytes: holds the form factors, not the layers too
    assert budget * 2 ** 20 < bound + layer_bytes, (bound, layer_bytes)
    summary = addon.bake(scene, attribute_name="Budget", light_group_layers=True, memory_budget=budget)
    assert summary["light_layers"] is None and summary["matrix_stored"], summary
    said = [w for w in summary["warnings"] if "Light group layers need" in w]
    assert said and "baked without them" in said[0], summary["warnings"]
    print(said[0])
    mesh = bpy.data.objects["Floor"].data
    assert mesh.color_attributes.get("Budget") is not None
    assert not [a.name for a in mesh.color_attributes if a.name.startswith("Budget ")]


def test_hierarchical_layers_sum_to_its_bake():
    summary = addon.bake(bpy.context.scene, attribute_name="Tree", light_group_layers=True, method="HIERARCHICAL",
                         element_size=0.1)
    assert summary["method"] == "hierarchical" and summary["light_layers"]["groups"] == list(GROUPS), summary
    error = worst_relative(sum(colours("Tree " + g) for g in GROUPS), colours("Tree"))
    print("hierarchical: layers' sum against its attribute: worst corner %.2g" % error)
    assert error < SUM_TOLERANCE, error


harness.run(test_layers_sum_and_each_is_its_group_alone, test_wired_mix_renders_as_the_bake_with_the_lamps_changed,
            test_over_the_budget_bakes_without_layers, test_hierarchical_layers_sum_to_its_bake)
