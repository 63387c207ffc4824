"""Wires the baked light into the materials of the baked objects, for the viewport and renders, and
takes exactly that wiring out again.

Each material gets a Color Attribute node reading the bake and an Emission shader in front of its
active Material Output. With the light-only attribute, the emission is that light times the
material's diffuse colour as Cycles' Diffuse bake has it: whatever feeds the Base Color of a
Principled BSDF or the Color of a Diffuse BSDF (a texture at full resolution included), times the
share of it the BSDF reflects diffusely (the Emission's Strength; materials.diffuse_share). With
the full radiance, the emission is the attribute itself. The nodes added carry a name prefix, and
the link they replaced is kept on the material, so unwiring restores the node tree as it was.
With light group layers (light_mix.py) on every object using the material, the emission is their
live mix, the node group "Radiosity Light Mix", instead of the attribute."""

import json

import bpy

from . import light_mix
from .materials import diffuse_share
from .writeback import light_attribute_name

NODE_PREFIX = "Radiosity Wire "
STATE_KEY = "radiosity_wiring"


def wire(scene):
    """Wires every material of the scene's baked meshes; returns (materials wired, messages)."""
    name = scene.radiosity.attribute_name
    light_name = light_attribute_name(name)
    users = {}  # material -> the baked objects using it
    for obj in scene.objects:
        if obj.type != "MESH" or obj.data.color_attributes.get(name) is None:
            continue
        for slot in obj.material_slots:
            if slot.material is not None:
                users.setdefault(slot.material, []).append(obj)
    if not users:
        return 0, ["Nothing to wire: no mesh in this scene with a material has a colour attribute '%s'" % name]
    wired, messages = 0, []
    for material, objects in users.items():
        if STATE_KEY in material:
            continue  # wired already
        mixed = all(light_mix.has_layers(scene, o.data) for o in objects)
        light_only = not mixed and all(o.data.color_attributes.get(light_name) is not None for o in objects)
        source = light_mix.mix_group(scene) if mixed else (light_name if light_only else name)
        problem = _wire_material(material, source, light_only)
        if problem:
            messages.append("Material '%s' not wired: %s" % (material.name, problem))
        else:
            wired += 1
    return wired, messages


def unwire(scene):
    """Removes the wiring from every material that has it; returns how many."""
    count = 0
    for material in bpy.data.materials:
        if STATE_KEY in material:
            _unwire_material(material)
            count += 1
    return count


def is_wired(material):
    return STATE_KEY in material


def _active_output(tree):
    outputs = [n for n in tree.nodes if n.bl_idname == "ShaderNodeOutputMaterial"]
    active = [n for n in outputs if n.is_active_output]
    return (active or outputs or [None])[0]


def _colour_socket(tree, output):
    """The input that gives the material its diffuse colour: Base Color of a Principled BSDF, Color of a
    Diffuse BSDF, on the shader that feeds the output; None for any other shader."""
    surface = output.inputs["Surface"]
    if not surface.is_linked:
        return None
    shader = surface.links[0].from_node
    for socket_name in ("Base Color", "Color"):
        if shader.bl_idname in ("ShaderNodeBsdfPrincipled", "ShaderNodeBsdfDiffuse") and socket_name in shader.inputs:
            return shader.inputs[socket_name]
    return None


def _light_node(nodes, source):
    """The node giving the light: a Color Attribute reading the attribute named `source`, or a
    group node of the node group `source` (the light group layers' mix)."""
    if isinstance(source, str):
        node = nodes.new("ShaderNodeVertexColor")
        node.layer_name = source
        return node, source
    node = nodes.new("ShaderNodeGroup")
    node.node_tree = source
    return node, source.name


def _wire_material(material, source, light_only):
    if material.node_tree is None:
        return "it has no node tree"
    tree = material.node_tree
    output = _active_output(tree)
    if output is None:
        return "it has no Material Output node"
    surface = output.inputs["Surface"]
    previous = None
    if surface.is_linked:
        link = surface.links[0]
        previous = [link.from_node.name, link.from_socket.identifier]
    colour = _colour_socket(tree, output) if light_only else None
    if light_only and colour is None:
        return "its surface is not a Principled or Diffuse BSDF, whose colour the light-only bake multiplies"

    nodes, links = tree.nodes, tree.links
    x, y = output.location
    attribute, attribute_name = _light_node(nodes, source)
    attribute.location = (x - 600, y - 300)
    emission = nodes.new("ShaderNodeEmission")
    emission.inputs["Strength"].default_value = 1.0
    emission.location = (x - 200, y - 300)
    added = [attribute, emission]
    if light_only:
        # The light times the colour: Vector Math multiplies colours alike in Blender 3.4 to 5.x.
        product = nodes.new("ShaderNodeVectorMath")
        product.operation = "MULTIPLY"
        product.location = (x - 400, y - 300)
        added.append(product)
        links.new(attribute.outputs[0], product.inputs[0])
        if colour.is_linked:
            links.new(colour.links[0].from_socket, product.inputs[1])
        else:
            product.inputs[1].default_value = tuple(colour.default_value)[:3]
        links.new(product.outputs[0], emission.inputs["Color"])
        emission.inputs["Strength"].default_value = diffuse_share(colour.node)
    else:
        links.new(attribute.outputs[0], emission.inputs["Color"])
    links.new(emission.outputs["Emission"], surface)
    for node in added:
        node.name = NODE_PREFIX + node.name
        node.label = NODE_PREFIX + "(" + attribute_name + ")"
    material[STATE_KEY] = json.dumps({"output": output.name, "previous": previous})
    return None


def _unwire_material(material):
    state = json.loads(material[STATE_KEY])
    del material[STATE_KEY]
    tree = material.node_tree
    if tree is None:
        return
    for node in [n for n in tree.nodes if n.name.startswith(NODE_PREFIX)]:
        tree.nodes.remove(node)
    output = tree.nodes.get(state["output"])
    previous = state["previous"]
    if output is None or previous is None:
        return
    source = tree.nodes.get(previous[0])
    socket = next((s for s in source.outputs if s.identifier == previous[1]), None) if source else None
    if socket is not None:
        tree.links.new(socket, output.inputs["Surface"])
