"""The light group layers mixed live: one shader node group, "Radiosity Light Mix", sums each layer's
colour attribute times its strength and tint (scene.radiosity.light_layers). Wire Baked Light puts
it in front of each material's emission, so Eevee, Cycles and the viewport show a new mix as soon
as a strength or tint changes (the panel writes them into the group's nodes, which the artist may
also edit there). Apply Light Mix writes the current mix into the usual attribute."""

import bpy
import numpy as np

from .engine.light_groups import attribute_name

GROUP_NAME = "Radiosity Light Mix"
STRENGTH_PREFIX = "Strength "
TINT_PREFIX = "Tint "


def remember_layers(scene, attribute, groups):
    """The layers of a bake into `attribute` just written (none: a bake without layers, which leaves
    an earlier bake's layers and mix as they are): each group keeps the strength and tint it had, a
    new one starts at 1 and white; the node group is made again for them."""
    if not groups:
        return
    settings = scene.radiosity
    kept = {layer.group: (layer.strength, tuple(layer.tint)) for layer in settings.light_layers}
    settings.light_layers.clear()
    settings.light_layers_attribute = attribute
    for group in groups:
        layer = settings.light_layers.add()
        layer.group, layer.attribute = group, attribute_name(attribute, group)
        layer.strength, layer.tint = kept.get(group, (1.0, (1.0, 1.0, 1.0)))
    build_group(bpy.data.node_groups.get(GROUP_NAME) or bpy.data.node_groups.new(GROUP_NAME, "ShaderNodeTree"), scene)


def has_layers(scene, mesh):
    """Whether `mesh` holds every layer of the scene's last layered bake."""
    layers = scene.radiosity.light_layers
    return len(layers) > 0 and all(mesh.color_attributes.get(layer.attribute) is not None for layer in layers)


def mix_group(scene):
    """The node group of the scene's layers (made if missing)."""
    group = bpy.data.node_groups.get(GROUP_NAME)
    if group is None:
        group = bpy.data.node_groups.new(GROUP_NAME, "ShaderNodeTree")
        build_group(group, scene)
    return group


def build_group(group, scene):
    """Fills `group` with the sum of the layers' attributes, each times a Strength value and a Tint colour."""
    group.nodes.clear()
    _set_color_output(group)
    output = group.nodes.new("NodeGroupOutput")
    output.location = (900, 0)
    total = None
    for k, layer in enumerate(scene.radiosity.light_layers):
        term = _layer_term(group, layer, y=-250 * k)
        if total is None:
            total = term
        else:
            add = group.nodes.new("ShaderNodeVectorMath")
            add.operation = "ADD"
            add.location = (700, -250 * k)
            group.links.new(total, add.inputs[0])
            group.links.new(term, add.inputs[1])
            total = add.outputs[0]
    if total is not None:
        group.links.new(total, output.inputs[0])
    update_mix(scene)


def _set_color_output(group):
    """One colour output, "Color" (Blender 4.0 moved group sockets to `interface`)."""
    if hasattr(group, "interface"):
        group.interface.clear()
        group.interface.new_socket("Color", in_out="OUTPUT", socket_type="NodeSocketColor")
    else:
        group.outputs.clear()
        group.outputs.new("NodeSocketColor", "Color")


def _layer_term(group, layer, y):
    """attribute x tint x strength for one layer: the output socket."""
    nodes, links = group.nodes, group.links
    colour = nodes.new("ShaderNodeVertexColor")
    colour.layer_name = layer.attribute
    colour.location = (0, y)
    tint = nodes.new("ShaderNodeRGB")
    tint.name = tint.label = TINT_PREFIX + layer.group
    tint.location = (0, y - 100)
    strength = nodes.new("ShaderNodeValue")
    strength.name = strength.label = STRENGTH_PREFIX + layer.group
    strength.location = (200, y - 150)
    tinted = nodes.new("ShaderNodeVectorMath")
    tinted.operation = "MULTIPLY"
    tinted.location = (250, y)
    links.new(colour.outputs["Color"], tinted.inputs[0])
    links.new(tint.outputs[0], tinted.inputs[1])
    scaled = nodes.new("ShaderNodeVectorMath")
    scaled.operation = "SCALE"
    scaled.location = (450, y)
    links.new(tinted.outputs[0], scaled.inputs[0])
    links.new(strength.outputs[0], scaled.inputs["Scale"])
    return scaled.outputs[0]


def update_mix(scene):
    """Writes the panel's strengths and tints into the node group's Strength and Tint nodes."""
    group = bpy.data.node_groups.get(GROUP_NAME)
    if group is None:
        return
    for layer in scene.radiosity.light_layers:
        strength = group.nodes.get(STRENGTH_PREFIX + layer.group)
        tint = group.nodes.get(TINT_PREFIX + layer.group)
        if strength is not None:
            strength.outputs[0].default_value = layer.strength
        if tint is not None:
            tint.outputs[0].default_value = tuple(layer.tint) + (1.0,)


def mix_weights(scene):
    """(layers, 3): each layer's strength x tint, as the node group's nodes hold them (the artist may
    have edited them there)."""
    group = bpy.data.node_groups.get(GROUP_NAME)
    weights = []
    for layer in scene.radiosity.light_layers:
        strength, tint = layer.strength, np.array(layer.tint[:3])
        if group is not None and group.nodes.get(STRENGTH_PREFIX + layer.group) is not None:
            strength = group.nodes[STRENGTH_PREFIX + layer.group].outputs[0].default_value
            tint = np.array(group.nodes[TINT_PREFIX + layer.group].outputs[0].default_value[:3])
        weights.append(strength * tint)
    return np.array(weights, dtype=np.float64).reshape(-1, 3)


def apply_mix(scene):
    """Writes the current mix into the usual attribute of the layered bake (light_layers_attribute) on
    every scene mesh holding the layers; returns how many."""
    name = scene.radiosity.light_layers_attribute
    weights = mix_weights(scene)
    meshes = {obj.data for obj in scene.objects if obj.type == "MESH" and has_layers(scene, obj.data)}
    for mesh in meshes:
        total = np.zeros((len(mesh.loops), 4), dtype=np.float64)
        rgba = np.empty(len(mesh.loops) * 4, dtype=np.float32)
        for layer, weight in zip(scene.radiosity.light_layers, weights):
            mesh.color_attributes[layer.attribute].data.foreach_get("color", rgba)
            total[:, :3] += rgba.reshape(-1, 4)[:, :3] * weight
        total[:, 3] = 1.0
        target = mesh.color_attributes.get(name) or mesh.color_attributes.new(name, "FLOAT_COLOR", "CORNER")
        target.data.foreach_set("color", total.astype(np.float32).ravel())
        mesh.update()
    return len(meshes)
