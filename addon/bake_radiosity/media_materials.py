"""Blender volume shaders as the core's Principled Volume parameters.

Follows the material output's Volume input through Principled Volume, Volume Absorption, Volume
Scatter, Emission, Add Shader and Mix Shader. Each shader becomes one `Term`: the arguments of
the core's principled_volume() with the grids that scale its density and emission strength, so
every coefficient is computed by the core exactly as Cycles does (svm_node_principled_volume and
svm_node_closure_volume):
  Volume Scatter (color c, density d)    = Principled (color c, density d, absorption colour 1)
  Volume Absorption (color c, density d) = Principled (color 0, density d, absorption colour c^2),
                                           since Principled absorbs d (1 - color)(1 - sqrt(absorption))
  Emission (color c, strength s)         = Principled (density 0, emission strength s, colour c)
"""

from dataclasses import dataclass, field

import numpy as np

from .materials import _linked_node, _surface_output

WHITE = (1.0, 1.0, 1.0)
BLACK = (0.0, 0.0, 0.0)


@dataclass
class Term:
    color: tuple
    density: float
    absorption_color: tuple
    emission_strength: float
    emission_color: tuple
    # Grid (Volume objects) whose values multiply the density / the emission strength; None = none.
    density_grid: str = None
    emission_grid: str = None


@dataclass
class VolumeShader:
    terms: list = field(default_factory=list)
    problems: list = field(default_factory=list)


def volume_output_node(material):
    """The node feeding the active output's Volume socket, or None."""
    if material is None or not material.use_nodes or material.node_tree is None:
        return None
    output = _surface_output(material.node_tree)
    if output is None or not output.inputs["Volume"].is_linked:
        return None
    return _linked_node(output.inputs["Volume"])


def has_surface(material):
    """Whether Cycles renders a surface for `material` (a material without nodes does)."""
    if material is None or not material.use_nodes or material.node_tree is None:
        return True
    output = _surface_output(material.node_tree)
    return output is not None and output.inputs["Surface"].is_linked


def is_medium_only(obj):
    """A mesh whose materials all have a volume shader and no surface: Cycles renders no surface for it."""
    materials = [slot.material for slot in obj.material_slots]
    return bool(materials) and all(
        m is not None and volume_output_node(m) is not None and not has_surface(m)
        for m in materials)


def volume_shader(material):
    """The Terms of `material`'s volume shader (empty when it has none)."""
    node = volume_output_node(material)
    shader = VolumeShader()
    if node is not None:
        _add(node, 1.0, shader)
    return shader


def _add(node, weight, shader):
    kind = node.type if node is not None else "NONE"
    if kind == "PRINCIPLED_VOLUME":
        _principled(node, weight, shader)
    elif kind in {"VOLUME_SCATTER", "VOLUME_ABSORPTION"}:
        color = _color(node.inputs["Color"], shader)
        density, grid = _scaled_number(node.inputs["Density"], shader)
        if kind == "VOLUME_SCATTER":
            _anisotropy(node, shader)
            shader.terms.append(Term(tuple(color), weight * density, WHITE, 0.0, BLACK, density_grid=grid))
        else:
            shader.terms.append(Term(BLACK, weight * density, tuple(np.square(color)), 0.0, BLACK, density_grid=grid))
    elif kind == "EMISSION":
        color = _color(node.inputs["Color"], shader)
        strength, grid = _scaled_number(node.inputs["Strength"], shader)
        shader.terms.append(Term(BLACK, 0.0, WHITE, weight * strength, tuple(color), emission_grid=grid))
    elif kind in {"ADD_SHADER", "MIX_SHADER"}:
        if kind == "MIX_SHADER":
            fac = _plain_number(node.inputs[0], shader)
            parts = ((node.inputs[1], 1.0 - fac), (node.inputs[2], fac))
        else:
            parts = ((node.inputs[0], 1.0), (node.inputs[1], 1.0))
        for socket, share in parts:
            if socket.is_linked and share != 0.0:
                _add(_linked_node(socket), weight * share, shader)
    else:
        label = node.bl_label if node is not None else "nothing"
        shader.problems.append("volume shader '%s' is not supported; ignored" % label)


def _principled(node, weight, shader):
    _anisotropy(node, shader)
    density, grid = _scaled_number(node.inputs["Density"], shader)
    strength, emission_grid = _scaled_number(node.inputs["Emission Strength"], shader)
    # The Density Attribute names the grid Cycles multiplies the density by (default "density").
    attribute = node.inputs["Density Attribute"].default_value if "Density Attribute" in node.inputs else ""
    if grid is None and attribute:
        grid = attribute
    if _plain_number(node.inputs["Blackbody Intensity"], shader) > 0.0:
        shader.problems.append("blackbody (temperature) emission is not baked")
    shader.terms.append(Term(
        tuple(_color(node.inputs["Color"], shader)), weight * density,
        tuple(_color(node.inputs["Absorption Color"], shader)),
        weight * strength, tuple(_color(node.inputs["Emission Color"], shader)),
        density_grid=grid, emission_grid=emission_grid))


def _anisotropy(node, shader):
    socket = node.inputs.get("Anisotropy")
    if socket is not None and (socket.is_linked or socket.default_value != 0.0):
        shader.problems.append("anisotropy %.2g treated as 0 (the zonal method scatters isotropically)"
                               % socket.default_value)


def _scaled_number(socket, shader):
    """(value, grid name): an Attribute node reads a grid (as Cycles' Fac), else the socket's value."""
    if not socket.is_linked:
        return float(socket.default_value), None
    node = _linked_node(socket)
    if node is not None and node.type == "ATTRIBUTE" and node.attribute_name:
        return 1.0, node.attribute_name
    shader.problems.append("'%s' input is driven by nodes; using its value %.3g" % (socket.name, socket.default_value))
    return float(socket.default_value), None


def _plain_number(socket, shader):
    if socket.is_linked:
        shader.problems.append("'%s' input is driven by nodes; using its value %.3g"
                               % (socket.name, socket.default_value))
    return float(socket.default_value)


def _color(socket, shader):
    if socket.is_linked:
        node = _linked_node(socket)
        if node is not None and node.type == "RGB":
            return np.array(node.outputs[0].default_value[:3], dtype=np.float64)
        shader.problems.append("'%s' input is driven by nodes; using its value" % socket.name)
    return np.array(socket.default_value[:3], dtype=np.float64)
