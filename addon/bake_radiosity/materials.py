"""Blender materials as the core sees them: a diffuse reflectance and an emitted radiance.

Follows the material output's Surface input through Principled BSDF, Diffuse BSDF, Emission,
Add Shader, Mix Shader, reroutes and node groups (into a group to its output, and from its
inputs back out to the group node). Anything else becomes a grey diffuse stand-in with a
one-line warning naming the material, so a bake never fails on an unusual node tree.

An Image Texture on a colour input counts as its mean colour here; the surface also says which
texture varies its reflectance and its emission about that mean (TextureUse, one of each).
"""

from dataclasses import dataclass, field
from typing import Optional

import bpy
import numpy as np

from . import textures

# Cycles renders a surface without a material as this grey diffuse.
DEFAULT_REFLECTANCE = (0.8, 0.8, 0.8)
# The core needs reflectance strictly below 1 for its iterations to converge.
MAX_REFLECTANCE = 0.999
# From Blender 4.0 on, Cycles' Principled BSDF lays its dielectric specular layer over the diffuse
# one and takes the layer's albedo off the diffuse weight (svm_node_closure_bsdf,
# closure_layering_weight), for a bake at normal incidence. That albedo is F0 times a factor of the
# roughness from Cycles' tables; the factor at roughness 0, 0.5, 1, measured from Cycles 5.2's
# Diffuse bake at IOR 1.5 (blender_test_lamps: Principled 4.16%, 3.88%, 1.40% above Lambert).
SPECULAR_ALBEDO_OVER_F0 = ((0.0, 0.5, 1.0), (1.0, 0.934, 0.345))


@dataclass
class TextureUse:
    """An Image Texture that varies a colour: colour = mean colour + scale x (texel - image mean)."""
    image: textures.Image
    node: object
    uv_map: str
    uv_transform: np.ndarray  # (2, 3): the texture reads uv_transform @ (u, v, 1) (Mapping nodes)
    scale: np.ndarray

    def reads_uvs_of(self, other):
        return self.uv_map == other.uv_map and np.array_equal(self.uv_transform, other.uv_transform)

    def scaled(self, factor):
        # A negative factor (a Metallic above 1) takes nothing away: the colour is clamped at 0 anyway.
        return TextureUse(self.image, self.node, self.uv_map, self.uv_transform, np.maximum(self.scale * factor, 0.0))


@dataclass
class Surface:
    reflectance: np.ndarray
    emission: np.ndarray
    problems: list = field(default_factory=list)
    reflectance_texture: Optional[TextureUse] = None
    emission_texture: Optional[TextureUse] = None


def surface_of(material, images=None):
    """Diffuse reflectance and emitted radiance of `material` (None = no material). `images`
    (textures.Images) loads each image once across materials."""
    images = images if images is not None else textures.Images()
    if material is None:
        return Surface(np.array(DEFAULT_REFLECTANCE), np.zeros(3))
    if not material.use_nodes or material.node_tree is None:
        return Surface(np.array(material.diffuse_color[:3]), np.zeros(3))
    output = _surface_output(material.node_tree)
    if output is None or not output.inputs["Surface"].is_linked:
        # Cycles renders an unconnected output black; a black surface only absorbs.
        return Surface(np.zeros(3), np.zeros(3), ["no surface shader connected"])
    surface = _shader_at(output.inputs["Surface"], (), 1.0, images)
    if (surface.reflectance > 1.0).any() or (surface.reflectance < 0.0).any():
        # Above 1 a surface would give out more light than it receives (and the solve diverge).
        surface.problems.append("diffuse colour (%.3g, %.3g, %.3g) is outside 0-1; clamped"
                                % tuple(surface.reflectance))
    if (surface.emission < 0.0).any():
        surface.problems.append("negative emission (%.3g, %.3g, %.3g) is taken as 0" % tuple(surface.emission))
    surface.reflectance = np.clip(surface.reflectance, 0.0, MAX_REFLECTANCE)
    surface.emission = np.maximum(surface.emission, 0.0)
    return surface


def warning_for(material_name, surface):
    if not surface.problems:
        return None
    return "Material '%s': %s" % (material_name, "; ".join(surface.problems))


def _surface_output(tree):
    outputs = [n for n in tree.nodes if n.type == "OUTPUT_MATERIAL" and n.target in {"ALL", "CYCLES"}]
    active = [n for n in outputs if n.is_active_output]
    return (active or outputs or [None])[0]


def _linked_node(socket):
    node = socket.links[0].from_node
    while node.type == "REROUTE":
        if not node.inputs[0].is_linked:
            return None
        node = node.inputs[0].links[0].from_node
    return node


def _source(socket, groups):
    """What feeds the input `socket` inside the nest of group nodes `groups`: (an output socket of
    a node that is neither a reroute nor a group, its groups), or (an input socket left unlinked,
    whose default_value is the value, its groups). A group's output leads to what feeds that
    output inside the group; a Group Input node leads back out to the group node's input."""
    while socket.is_linked:
        link = socket.links[0]
        node, output = link.from_node, link.from_socket
        if node.type == "REROUTE":
            socket = node.inputs[0]
        elif node.type == "GROUP" and node.node_tree is not None and _group_output(node.node_tree) is not None:
            socket = _group_output(node.node_tree).inputs[list(node.outputs).index(output)]
            groups = groups + (node,)
        elif node.type == "GROUP_INPUT" and groups:
            socket = groups[-1].inputs[list(node.outputs).index(output)]
            groups = groups[:-1]
        else:
            return output, groups
    return socket, groups


def _group_output(tree):
    outputs = [n for n in tree.nodes if n.type == "GROUP_OUTPUT"]
    active = [n for n in outputs if n.is_active_output]
    return (active or outputs or [None])[0]


def _shader_at(socket, groups, weight, images):
    """Weighted reflectance and emission of the shader network feeding the input `socket`."""
    source, groups = _source(socket, groups)
    if not source.is_output:  # nothing connected inside a group: Cycles renders no closure, black
        return Surface(np.zeros(3), np.zeros(3))
    return _shader(source.node, groups, weight, images)


def _shader(node, groups, weight, images):
    """Weighted reflectance and emission of the shader network that ends in `node`."""
    kind = node.type
    if kind == "BSDF_PRINCIPLED":
        return _principled(node, groups, weight, images)
    if kind == "BSDF_DIFFUSE":
        color, problems, texture = _color(node.inputs["Color"], groups, images)
        return Surface(weight * color, np.zeros(3), problems, reflectance_texture=_scaled(texture, weight))
    if kind == "EMISSION":
        color, problems, texture = _color(node.inputs["Color"], groups, images)
        strength, more = _number(node.inputs["Strength"], groups)
        return Surface(np.zeros(3), weight * color * strength, problems + more,
                       emission_texture=_scaled(texture, weight * strength))
    if kind in {"ADD_SHADER", "MIX_SHADER"}:
        return _combination(node, groups, weight, images)
    return Surface(weight * np.array(DEFAULT_REFLECTANCE), np.zeros(3),
                   ["'%s' is not diffuse; using grey diffuse %.1f" % (node.bl_label, DEFAULT_REFLECTANCE[0])])


def _scaled(texture, factor):
    return texture.scaled(factor) if texture is not None else None


def _principled(node, groups, weight, images):
    base, problems, base_texture = _color(node.inputs["Base Color"], groups, images)
    diffuse, more = _diffuse_share(node, groups, images)
    problems += more
    transmission = node.inputs.get("Transmission") or node.inputs.get("Transmission Weight")
    if transmission is not None and (transmission.is_linked or transmission.default_value > 0.0):
        problems.append("transmission is ignored (treated as opaque)")
    # Blender 3.x calls the emission colour "Emission"; 4.x calls it "Emission Color".
    emission_socket = node.inputs.get("Emission Color") or node.inputs.get("Emission")
    emission, more, emission_texture = _color(emission_socket, groups, images)
    problems += more
    strength, more = _number(node.inputs["Emission Strength"], groups)
    problems += more
    return Surface(weight * base * diffuse, weight * emission * strength, problems,
                   reflectance_texture=_scaled(base_texture, weight * diffuse),
                   emission_texture=_scaled(emission_texture, weight * strength))


def diffuse_share(shader):
    """The share of the colour input of `shader`, a Principled BSDF's Base Color or a Diffuse BSDF's
    Color, that Cycles reflects diffusely, as the bake takes it (1 for a Diffuse BSDF)."""
    if shader.type != "BSDF_PRINCIPLED":
        return 1.0
    return _diffuse_share(shader, (), textures.Images())[0]


def _diffuse_share(node, groups, images):
    """The share of a Principled BSDF's Base Color that reflects diffusely, and problems: metals
    have no diffuse lobe, and from Blender 4.0 on the specular layer takes its albedo off the rest."""
    metallic, problems = _number(node.inputs["Metallic"], groups)
    share = 1.0 - metallic
    if bpy.app.version >= (4, 0, 0):
        layer, more = _under_specular_layer(node, groups, images)
        share, problems = share * layer, problems + more
    return share, problems


def _under_specular_layer(node, groups, images):
    """The share of a 4.x Principled BSDF's diffuse weight its specular layer leaves (see
    SPECULAR_ALBEDO_OVER_F0), and problems. A texture on the tint counts as its mean colour."""
    ior, problems = _number(node.inputs["IOR"], groups)
    level, more = _number(node.inputs["Specular IOR Level"], groups)
    roughness, more2 = _number(node.inputs["Roughness"], groups)
    tint, more3, _ = _color(node.inputs["Specular Tint"], groups, images)
    f0 = ((ior - 1.0) / (ior + 1.0)) ** 2 * 2.0 * level * max(float(np.max(tint)), 0.0)
    albedo = f0 * np.interp(min(max(roughness, 0.0), 1.0), *SPECULAR_ALBEDO_OVER_F0)
    return 1.0 - min(albedo, 1.0), problems + more + more2 + more3


def _combination(node, groups, weight, images):
    if node.type == "MIX_SHADER":
        fac, problems = _number(node.inputs[0], groups)
        parts = ((node.inputs[1], 1.0 - fac), (node.inputs[2], fac))
    else:
        problems = []
        parts = ((node.inputs[0], 1.0), (node.inputs[1], 1.0))
    total = Surface(np.zeros(3), np.zeros(3), problems)
    for socket, share in parts:
        if not socket.is_linked or share == 0.0:
            continue
        part = _shader_at(socket, groups, weight * share, images)
        total.reflectance = total.reflectance + part.reflectance
        total.emission = total.emission + part.emission
        total.problems += part.problems
        for role in ("reflectance_texture", "emission_texture"):
            mine, theirs = getattr(total, role), getattr(part, role)
            if theirs is not None and mine is None:
                setattr(total, role, theirs)
            elif theirs is not None:
                total.problems.append("only one image texture varies its %s across the surface; image '%s' counts as "
                                      "its mean colour" % (role.split("_")[0], theirs.image.name))
    return total


def _color(socket, groups, images):
    """RGB of a colour input (its value, an RGB node, or an image texture's mean colour), the
    problems met, and the TextureUse of an image texture that varies it (None: it is uniform)."""
    source, inner_groups = _source(socket, groups)
    if not source.is_output:
        value = np.atleast_1d(np.array(source.default_value, dtype=np.float64))
        if len(value) < 3:  # a group input of another type: Blender would convert it
            problem = ("'%s' input fed by a '%s' group input is not supported; using grey %.1f"
                       % (socket.name, source.type, DEFAULT_REFLECTANCE[0]))
            return np.array(DEFAULT_REFLECTANCE), [problem], None
        return value[:3], [], None
    node = source.node
    if node.type == "RGB":
        return np.array(node.outputs[0].default_value[:3], dtype=np.float64), [], None
    if node.type == "TEX_IMAGE" and source.name == "Color":
        return _image_color(socket, node, inner_groups, images)
    return (np.array(DEFAULT_REFLECTANCE),
            ["'%s' input driven by '%s' is not supported; using grey %.1f"
             % (socket.name, node.bl_label, DEFAULT_REFLECTANCE[0])], None)


def _image_color(socket, node, groups, images):
    """An Image Texture on a colour input: its image's mean and the texture's use, or, for an
    image that cannot be read, the input's own value (Cycles renders a missing image magenta; a
    bake would spread that colour as light)."""
    fallback = np.array(socket.default_value[:3], dtype=np.float64)
    if node.image is None:
        return fallback, ["'%s' has no image; using the '%s' value (%.3g, %.3g, %.3g)"
                          % (node.name, socket.name, *fallback)], None
    image = images.load(node.image)
    if isinstance(image, str):
        return fallback, ["%s; using the '%s' value (%.3g, %.3g, %.3g)" % (image, socket.name, *fallback)], None
    uv_map, uv_transform, why_not = textures.uv_map_of(node, groups, _source)
    if uv_map is None:
        return image.mean, ["image '%s' counts as its mean colour: %s" % (image.name, why_not)], None
    return image.mean, [], TextureUse(image, node, uv_map, uv_transform, np.ones(3))


def _number(socket, groups):
    source, _ = _source(socket, groups)
    if not source.is_output and np.ndim(source.default_value) == 0:
        return float(source.default_value), []
    return float(socket.default_value), ["'%s' input is driven by nodes; using its value %.3g"
                                         % (socket.name, socket.default_value)]
