"""What renders is what bakes: objects and lamps that Cycles leaves out of a render (disabled in
renders, in a collection disabled in renders or excluded from the view layer, in an instanced
collection's disabled part) add nothing to the bake, objects only hidden in the viewport bake as
they render, and a lamp's node tree scales it as Cycles does. Bad lamps are named; warnings that
repeat per lamp are said once."""

import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402
import numpy as np  # noqa: E402

import harness  # noqa: E402
import scenes  # noqa: E402

args = harness.arguments()
addon = harness.install_addon(args.addon_zip)
pipeline = sys.modules[harness.MODULE + ".pipeline"]
export = sys.modules[harness.MODULE + ".export"]

# A 1 m room of 4 x 4 faces a side, one element a face: a bake takes a fraction of a second.
# A fixed method and tolerance, so that two bakes of the same light sum the same way.
QUICK = dict(method="GAUSS_SEIDEL", element_size=0.0, hemicube_resolution=32, tolerance=1e-6)
KEY_WATTS = 10.0


def room():
    """A closed 1 m cube seen from inside (normals inward), grey 0.5, lit by a 10 W point lamp 'Key'."""
    scenes.clear_scene()
    sides = [((0, 0, 0), (1, 0, 0), (0, 1, 0)), ((0, 0, 1), (0, 1, 0), (1, 0, 0)),
             ((0, 0, 0), (0, 0, 1), (1, 0, 0)), ((0, 1, 0), (1, 0, 0), (0, 0, 1)),
             ((0, 0, 0), (0, 1, 0), (0, 0, 1)), ((1, 0, 0), (0, 0, 1), (0, 1, 0))]
    scenes.mesh_object("Room", [scenes.grid(o, u, v, 4, 4) + (0,) for o, u, v in sides],
                       [scenes.diffuse("Grey", (0.5, 0.5, 0.5))])
    settings = bpy.context.scene.radiosity
    for name, value in QUICK.items():
        setattr(settings, name, value)
    point_lamp("Key", KEY_WATTS, (0.5, 0.5, 0.7))


def point_lamp(name, watts, location, collection=None, kind="POINT"):
    data = bpy.data.lights.new(name, kind)
    data.energy = watts
    if kind == "POINT":
        data.shadow_soft_size = 0.0
    else:
        data.size = 0.2
    obj = bpy.data.objects.new(name, data)
    obj.location = location
    (collection or bpy.context.scene.collection).objects.link(obj)
    return obj


def baked():
    """The room's baked corner colours and the bake's summary, through the artists' Python call."""
    summary = addon.bake(bpy.context.scene)
    return harness.corner_colors(bpy.data.objects["Room"].data, "Radiosity"), summary


def assert_same(colors, reference, what):
    error = np.abs(colors - reference).max() / reference.max()
    print("%s: largest difference %.2e of the brightest corner" % (what, error))
    assert error <= 1e-6, "%s: differs by %.3g of the brightest corner" % (what, error)


def move_to(obj, collection):
    for holder in list(obj.users_collection):
        holder.objects.unlink(obj)
    collection.objects.link(obj)


def test_lamp_disabled_in_renders_adds_no_light():
    room()
    reference, _ = baked()
    extra = point_lamp("Disabled Lamp", 1000.0, (0.3, 0.3, 0.3))
    lit, _ = baked()
    assert lit.mean() > 10 * reference.mean(), "the 1000 W lamp should light the room when it renders"

    extra.hide_render = True
    assert_same(baked()[0], reference, "lamp disabled in renders")

    # In a collection inside a collection disabled in renders.
    extra.hide_render = False
    outer = bpy.data.collections.new("Outer")
    inner = bpy.data.collections.new("Inner")
    bpy.context.scene.collection.children.link(outer)
    outer.children.link(inner)
    move_to(extra, inner)
    outer.hide_render = True
    assert_same(baked()[0], reference, "lamp in a collection disabled in renders")

    # In a collection excluded from the view layer.
    outer.hide_render = False
    bpy.context.view_layer.layer_collection.children["Outer"].exclude = True
    assert_same(baked()[0], reference, "lamp in a collection excluded from the view layer")

    # Through the operator as well.
    assert bpy.ops.radiosity.bake() == {"FINISHED"}
    assert_same(harness.corner_colors(bpy.data.objects["Room"].data, "Radiosity"), reference, "operator")


def test_mesh_disabled_in_renders_casts_no_shadow():
    room()
    reference, _ = baked()
    # A plate between the lamp and the floor.
    blocker = scenes.mesh_object("Blocker", [scenes.grid((0.25, 0.25, 0.4), (0.5, 0, 0), (0, 0.5, 0), 1, 1) + (0,)],
                                 [scenes.diffuse("Black", (0.0, 0.0, 0.0))])
    shadowed, _ = baked()
    assert np.abs(shadowed - reference).max() > 0.1 * reference.max(), "the plate should shadow the floor"

    blocker.hide_render = True
    assert_same(baked()[0], reference, "mesh disabled in renders")

    # Hidden in the viewport only (eye icon): Cycles renders it, so it shadows the bake too.
    blocker.hide_render = False
    blocker.hide_set(True)
    assert_same(baked()[0], shadowed, "mesh hidden in the viewport")


def test_instanced_collection_follows_render_visibility():
    room()
    reference, _ = baked()
    # A collection outside the scene, shown by an instancing empty; its lamp sits in a child
    # collection disabled in renders.
    source = bpy.data.collections.new("Lamp Set")
    child = bpy.data.collections.new("Lamp Set Off")
    source.children.link(child)
    point_lamp("Instanced Lamp", 1000.0, (0.0, 0.0, 0.0), child)
    child.hide_render = True
    empty = bpy.data.objects.new("Lamp Set Instancer", None)
    empty.instance_type = "COLLECTION"
    empty.instance_collection = source
    empty.location = (0.3, 0.3, 0.3)
    bpy.context.scene.collection.objects.link(empty)
    assert_same(baked()[0], reference, "instanced lamp in a collection disabled in renders")

    child.hide_render = False
    lit, _ = baked()
    assert lit.mean() > 10 * reference.mean(), "the instanced lamp should light the room"

    empty.hide_render = True
    assert_same(baked()[0], reference, "lamp instanced by an empty disabled in renders")


def test_viewport_hidden_lamps_bake_as_they_render():
    room()
    reference, _ = baked()
    # The eye icon hides the key lamp in the viewport only: F12 still renders its light.
    bpy.data.objects["Key"].hide_set(True)
    colors, summary = baked()
    assert_same(colors, reference, "lamp hidden in the viewport")

    # Disabled in viewports (monitor icon) but not in renders: Blender does not evaluate it for the
    # viewport, so the bake cannot follow it; it must say so, naming it.
    extra = point_lamp("Viewport Disabled Lamp", 1000.0, (0.3, 0.3, 0.3))
    extra.hide_viewport = True
    colors, summary = baked()
    named = [w for w in summary["warnings"] if "'Viewport Disabled Lamp'" in w]
    assert len(named) == 1, summary["warnings"]
    print(named[0])


def instancing_plane(name, location):
    """A plane whose geometry nodes put a cube on each of its corners and keep the plane too."""
    plane = scenes.mesh_object(name, [scenes.grid(location, (0.2, 0, 0), (0, 0.2, 0), 1, 1) + (0,)])
    tree = bpy.data.node_groups.new(name, "GeometryNodeTree")
    if bpy.app.version >= (4, 0, 0):  # 4.0 moved a group's sockets into its interface
        tree.interface.new_socket("Geometry", in_out="INPUT", socket_type="NodeSocketGeometry")
        tree.interface.new_socket("Geometry", in_out="OUTPUT", socket_type="NodeSocketGeometry")
    else:
        tree.inputs.new("NodeSocketGeometry", "Geometry")
        tree.outputs.new("NodeSocketGeometry", "Geometry")
    nodes, links = tree.nodes, tree.links
    group_in, group_out = nodes.new("NodeGroupInput"), nodes.new("NodeGroupOutput")
    on_points, cube, join = (nodes.new("GeometryNodeInstanceOnPoints"), nodes.new("GeometryNodeMeshCube"),
                             nodes.new("GeometryNodeJoinGeometry"))
    cube.inputs["Size"].default_value = (0.05, 0.05, 0.05)
    links.new(group_in.outputs[0], on_points.inputs["Points"])
    links.new(cube.outputs[0], on_points.inputs["Instance"])
    links.new(on_points.outputs[0], join.inputs[0])
    links.new(group_in.outputs[0], join.inputs[0])
    links.new(join.outputs[0], group_out.inputs[0])
    plane.modifiers.new("Cubes", "NODES").node_group = tree
    return plane


def test_instancers_show_themselves_as_in_renders():
    room()
    shown = instancing_plane("Shown", (0.2, 0.2, 0.3))
    hidden = instancing_plane("Hidden", (0.6, 0.6, 0.3))
    # Show Instancer: the viewport and renders may differ; the bake follows renders.
    shown.show_instancer_for_viewport = False
    hidden.show_instancer_for_render = False
    # An instancer of the older kind (instancing on vertices) with its viewport flag off.
    verts = scenes.mesh_object("Verts", [scenes.grid((0.4, 0.2, 0.6), (0.2, 0, 0), (0, 0.2, 0), 1, 1) + (0,)])
    verts.instance_type = "VERTS"
    verts.show_instancer_for_viewport = False
    bpy.data.objects["Key"].parent = verts
    view_layer, depsgraph = pipeline.view_layer_and_depsgraph(bpy.context.scene)
    exported = export.export_scene(depsgraph, view_layer)
    parts = sorted((p.object_name, p.is_instance) for p in exported.parts)
    print(parts, exported.warnings)
    assert parts == sorted([("Room", False), ("Shown", False), ("Verts", False)] + [("Shown", True)] * 4
                           + [("Hidden", True)] * 4), parts
    # The key lamp on each of the four vertices (offset by its own location).
    on_vertices = [light for light in exported.lights if light["position"][2] > 1.2]
    assert len(on_vertices) == 4, exported.lights
    assert not exported.warnings, exported.warnings


def emission_node(light):
    light.use_nodes = True
    return next(n for n in light.node_tree.nodes if n.type == "EMISSION")


def without_node_effect(light, emission):
    """The lamp as if it had no node tree: before 5.0 by turning its nodes off; from 5.0, where a
    lamp always uses its node tree (use_nodes is deprecated), by the tree's neutral Emission."""
    if bpy.app.version >= (5, 0, 0):
        emission.inputs["Strength"].default_value = 1.0
        emission.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    else:
        light.use_nodes = False


def test_lamp_node_tree_scales_the_lamp():
    room()
    reference, _ = baked()
    lamp = point_lamp("Noded Lamp", 100.0, (0.3, 0.3, 0.3))
    plain, _ = baked()
    emission = emission_node(lamp.data)
    # Blender's default lamp node tree (Emission strength 1, white) changes nothing.
    assert_same(baked()[0], plain, "default lamp node tree")

    emission.inputs["Strength"].default_value = 0.0
    assert_same(baked()[0], reference, "lamp node tree with strength 0")

    emission.inputs["Strength"].default_value = 2.0
    doubled, _ = baked()
    assert_same(doubled - reference, 2.0 * (plain - reference), "lamp node tree with strength 2, its contribution")
    without_node_effect(lamp.data, emission)
    lamp.data.energy = 200.0
    assert_same(doubled, baked()[0], "strength 2 against 200 W")

    lamp.data.energy = 100.0
    lamp.data.use_nodes = True
    emission.inputs["Strength"].default_value = 1.0
    emission.inputs["Color"].default_value = (1.0, 0.5, 0.25, 1.0)
    tinted, _ = baked()
    without_node_effect(lamp.data, emission)
    lamp.data.color = (1.0, 0.5, 0.25)
    assert_same(tinted, baked()[0], "node colour against lamp colour")

    # An area lamp whose node tree emits nothing adds nothing (nor does it block light).
    bpy.data.objects.remove(lamp)
    area = point_lamp("Noded Area", 100.0, (0.5, 0.5, 0.3), kind="AREA")
    emission_node(area.data).inputs["Strength"].default_value = 0.0
    assert_same(baked()[0], reference, "area lamp node tree with strength 0")


def test_lamp_node_tree_that_varies_is_named():
    room()
    lamp = point_lamp("Textured Lamp", 100.0, (0.3, 0.3, 0.3))
    plain, _ = baked()
    tree_emission = emission_node(lamp.data)
    noise = lamp.data.node_tree.nodes.new("ShaderNodeTexNoise")
    lamp.data.node_tree.links.new(noise.outputs["Fac"], tree_emission.inputs["Strength"])
    colors, summary = baked()
    named = [w for w in summary["warnings"] if "'Textured Lamp'" in w]
    assert len(named) == 1, summary["warnings"]
    print(named[0])
    # The lamp is kept as it is without its node tree.
    assert_same(colors, plain, "lamp with a texture-driven strength")

    ies = lamp.data.node_tree.nodes.new("ShaderNodeTexIES")
    lamp.data.node_tree.links.new(ies.outputs["Fac"], tree_emission.inputs["Strength"])
    colors, summary = baked()
    named = [w for w in summary["warnings"] if "'Textured Lamp'" in w]
    assert len(named) == 1 and "IES" in named[0], summary["warnings"]
    assert_same(colors, plain, "lamp with an IES profile")


def test_negative_lamp_is_named():
    room()
    point_lamp("Negative Lamp", -1000.0, (0.3, 0.3, 0.3))
    before = harness.file_state()
    try:
        addon.bake(bpy.context.scene)
    except pipeline.BakeError as error:
        message = str(error)
    else:
        raise AssertionError("a negative lamp was baked")
    print(message)
    assert "'Negative Lamp'" in message, message
    assert harness.file_state() == before

    # The operator reports it (an operator's error reaches Python as a RuntimeError).
    try:
        bpy.ops.radiosity.bake()
    except RuntimeError as error:
        message = str(error)
    else:
        raise AssertionError("the operator baked a negative lamp")
    assert "'Negative Lamp'" in message, message
    assert harness.file_state() == before


def test_repeated_lamp_warnings_said_once():
    room()
    for i in range(30):
        lamp = point_lamp("Panel %02d" % i, 1.0, (0.2 + 0.02 * i, 0.5, 0.5), kind="AREA")
        lamp.data.spread = math.radians(90.0)
    _, summary = baked()
    about_spread = [w for w in summary["warnings"] if "spread" in w.lower()]
    print(about_spread)
    assert len(about_spread) == 1, summary["warnings"]
    assert "30" in about_spread[0] and "'Panel 00'" in about_spread[0], about_spread
    assert len(about_spread[0]) < 200, about_spread


harness.run(test_lamp_disabled_in_renders_adds_no_light, test_mesh_disabled_in_renders_casts_no_shadow,
            test_instanced_collection_follows_render_visibility, test_instancers_show_themselves_as_in_renders,
            test_viewport_hidden_lamps_bake_as_they_render,
            test_lamp_node_tree_scales_the_lamp, test_lamp_node_tree_that_varies_is_named,
            test_negative_lamp_is_named, test_repeated_lamp_warnings_said_once)
