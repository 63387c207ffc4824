"""Blender materials as the core sees them: a diffuse reflectance and an emitted radiance.

Follows the material output's Surface input through Principled BSDF, Diffuse BSDF, Emission,
Add Shader and Mix Shader. Anything else becomes a grey diffuse stand-in with a one-line
warning naming the material, so a bake never fails on an unusual node tree.
"""

from dataclasses import dataclass, field

import numpy as np

# Cycles renders a surface without a material as this grey diffuse.
DEFAULT_REFLECTANCE = (0.8, 0.8, 0.8)
# The core needs reflectance strictly below 1 for its iterations to converge.
MAX_REFLECTANCE = 0.999


@dataclass
class Surface:
    reflectance: np.ndarray
    emission: np.ndarray
    problems: list = field(default_factory=list)


def surface_of(material):
    """Diffuse reflectance and emitted radiance of `material` (None = no material)."""
    if material is None:
        return Surface(np.array(DEFAULT_REFLECTANCE), np.zeros(3))
    if not material.use_nodes or material.node_tree is None:
        return Surface(np.array(material.diffuse_color[:3]), np.zeros(3))
    output = _surface_output(material.node_tree)
    if output is None or not output.inputs["Surface"].is_linked:
        # Cycles renders an unconnected output black; a black surface only absorbs.
        return Surface(np.zeros(3), np.zeros(3), ["no surface shader connected"])
    surface = _shader(_linked_node(output.inputs["Surface"]), 1.0)
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


def _shader(node, weight):
    """Weighted reflectance and emission of the shader network that ends in `node`."""
    kind = node.type if node is not None else "NONE"
    if kind == "BSDF_PRINCIPLED":
        return _principled(node, weight)
    if kind == "BSDF_DIFFUSE":
        color, problems = _color(node.inputs["Color"])
        return Surface(weight * color, np.zeros(3), problems)
    if kind == "EMISSION":
        color, problems = _color(node.inputs["Color"])
        strength, more = _number(node.inputs["Strength"])
        return Surface(np.zeros(3), weight * color * strength, problems + more)
    if kind in {"ADD_SHADER", "MIX_SHADER"}:
        return _combination(node, weight)
    label = node.bl_label if node is not None else "nothing"
    return Surface(weight * np.array(DEFAULT_REFLECTANCE), np.zeros(3),
                   ["'%s' is not diffuse; using grey diffuse %.1f" % (label, DEFAULT_REFLECTANCE[0])])


def _principled(node, weight):
    base, problems = _color(node.inputs["Base Color"])
    metallic, more = _number(node.inputs["Metallic"])
    problems += more
    transmission = node.inputs.get("Transmission") or node.inputs.get("Transmission Weight")
    if transmission is not None and (transmission.is_linked or transmission.default_value > 0.0):
        problems.append("transmission is ignored (treated as opaque)")
    # Blender 3.x calls the emission colour "Emission"; 4.x calls it "Emission Color".
    emission_socket = node.inputs.get("Emission Color") or node.inputs.get("Emission")
    emission, more = _color(emission_socket)
    problems += more
    strength, more = _number(node.inputs["Emission Strength"])
    problems += more
    # Metals have no diffuse lobe: only the dielectric part reflects diffusely.
    return Surface(weight * base * (1.0 - metallic), weight * emission * strength, problems)


def _combination(node, weight):
    if node.type == "MIX_SHADER":
        fac, problems = _number(node.inputs[0])
        parts = ((node.inputs[1], 1.0 - fac), (node.inputs[2], fac))
    else:
        problems = []
        parts = ((node.inputs[0], 1.0), (node.inputs[1], 1.0))
    total = Surface(np.zeros(3), np.zeros(3), problems)
    for socket, share in parts:
        if not socket.is_linked or share == 0.0:
            continue
        part = _shader(_linked_node(socket), weight * share)
        total.reflectance = total.reflectance + part.reflectance
        total.emission = total.emission + part.emission
        total.problems += part.problems
    return total


def _color(socket):
    """RGB of a colour input: its value, an RGB node, or the mean of an image texture."""
    if not socket.is_linked:
        return np.array(socket.default_value[:3], dtype=np.float64), []
    node = _linked_node(socket)
    if node is not None and node.type == "RGB":
        return np.array(node.outputs[0].default_value[:3], dtype=np.float64), []
    if node is not None and node.type == "TEX_IMAGE" and node.image is not None:
        mean = image_mean_color(node.image)
        if mean is not None:
            return mean, []
        return np.array(socket.default_value[:3]), ["image '%s' has no pixels" % node.image.name]
    label = node.bl_label if node is not None else "nothing"
    return (np.array(DEFAULT_REFLECTANCE),
            ["'%s' input driven by '%s' is not supported; using grey %.1f" % (socket.name, label, DEFAULT_REFLECTANCE[0])])


def _number(socket):
    if not socket.is_linked:
        return float(socket.default_value), []
    return float(socket.default_value), ["'%s' input is driven by nodes; using its value %.3g" % (socket.name, socket.default_value)]


def image_mean_color(image):
    """Mean linear RGB of an image, or None if it has no pixels."""
    width, height = image.size
    channels = image.channels
    if width * height == 0 or channels < 3:
        return None
    pixels = np.empty(width * height * channels, dtype=np.float32)
    image.pixels.foreach_get(pixels)
    rgb = pixels.reshape(-1, channels)[:, :3].astype(np.float64)
    # Byte images hold display-encoded values; float images are already linear.
    if image.colorspace_settings.name == "sRGB" and not image.is_float:
        rgb = srgb_to_linear(rgb)
    return rgb.mean(axis=0)


def srgb_to_linear(values):
    return np.where(values <= 0.04045, values / 12.92, ((values + 0.055) / 1.055) ** 2.4)
