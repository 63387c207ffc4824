"""Blender lamps in the core's units, converted exactly as Cycles converts them.

Cycles (intern/cycles/blender/light.cpp, scene/light.cpp, kernel/light/*) sets a lamp's
strength to colour x power and then:
- point and spot: a sphere of radius r with radiance strength / (4 pi * pi r^2), so a point's
  radiant intensity is strength / (4 pi) W/sr. A spot uses the same intensity inside its cone
  (its cone does not concentrate the power), with Cycles' smoothstep blend at the rim; Cycles 3.x
  also multiplies it by the cosine of the angle off the spot's axis (kernel/light/light.h,
  spot_light_attenuation), 4.0 and later do not (kernel/light/spot.h). Measured against Cycles
  3.4 and 5.2 (blender_test_lamps): 16% apart over a 100 degree spot's floor.
- point and spot with a radius: to Cycles 3.x, and to 4.0 and later while the lamp's Soft Falloff
  is on (Blender's default), a disk of that radius facing the shading point; to 4.0 and later with
  Soft Falloff off a sphere (kernel/light/point.h). The core takes the shape ("DISK", "SPHERE").
  Measured in Blender 3.4 (blender_test_lamp_radius): Cycles gives the disk's irradiance exactly,
  I / (d^2 + r^2) at the foot of a lamp d from a wall.
- sun: irradiance strength W/m^2 on a surface facing it, from a cone of half its angle: to Cycles
  3.x directions uniform over a disk of radius tan(angle / 2) one unit out (distant_light_sample),
  to 4.0 and later uniform over the cone.
- area: one-sided radiance strength / (4 A) from the lamp's -Z side, A = size_x * size_y
  (times the object's scale, times pi/4 for disk and ellipse). From Blender 4.0 on, Cycles
  converts a lamp's radiant flux to radiance by pi (scene/light.cpp: eval_fac = invarea / pi):
  strength / (pi A), and strength / pi where the lamp's Normalize is off (invarea = 1).
  Measured against Cycles 4.3 and 5.2: 4 / pi brighter than 3.4's, as this says.
- Blender 4.x adds Exposure (strength x 2^exposure) and a Temperature colour (where the lamp
  uses it, colour x temperature_color); older Blenders have neither.

A lamp's node tree is its shader, and the shader's emission multiplies that strength
(lamp_strength below). Lamps whose strength is 0 add nothing and are left out, as Cycles leaves
them out (Light::has_contribution in scene/light.cpp: strength 0, or a shader without emission).

Problems are returned as (problem, item) pairs, not sentences, so that export.py can say each
problem once for all the lamps that have it (visibility.listing).
"""

import math

import bpy
import numpy as np

from . import materials
from .engine.errors import BakeError

# Disk and ellipse lamps become ELLIPSE_GRID x ELLIPSE_GRID quads: a square grid mapped onto the
# disk (the elliptical grid mapping, x sqrt(1 - y^2 / 2), y sqrt(1 - x^2 / 2)), whose rim is a
# 16-gon with 2.6% less area than the ellipse. Cycles' radiance is power / (4 x the ellipse's
# area); the grid's is raised by that share, so the lamp emits its whole power. One many-sided
# polygon would be cut into hundreds of slivers by the element builder, and the smallest of them
# would set the hemi-cube resolution of the whole bake.
ELLIPSE_GRID = 4

SPREAD = "Spread ignored, the lamp emits over the full hemisphere"
NODES_VARY = ("Lamp node tree not followed (nodes drive its Emission, which the bake cannot average); "
              "baked as the lamp without its node tree")
NODES_EMIT_NOTHING = "Lamp node tree has no shader at its Light Output: the lamp emits nothing, as in Cycles"


def lamp_strength(light_object):
    """Cycles' strength of a lamp (3,): colour x power (W; sun: W/m^2) x its node tree's constant
    emission, and a list of (problem, item) pairs. Raises BakeError, naming the lamp, if the
    strength is negative or not a number: the bake only adds light.

    Cycles (intern/cycles/blender/shader.cpp, BlenderSync::sync_lights) uses the lamp's node tree
    as its shader when use_nodes is on, otherwise an Emission of colour 1 and strength 1; the
    kernel (kernel/light/sample.h, light_sample_shader_eval) multiplies the shader's emission by
    the lamp's strength (klight->strength = colour x power); and the Emission node's closure
    weight is Color x Strength (scene/shader_nodes.cpp, EmissionNode::compile). Blender's
    Emission node defaults to Strength 1 and white, so the default lamp node tree changes nothing.
    """
    light = light_object.data
    factor, problems = node_tree_factor(light_object)
    color = np.array(light.color[:3], dtype=np.float64)
    if getattr(light, "use_temperature", False):
        color = color * np.array(light.temperature_color[:3], dtype=np.float64)
    power = float(light.energy) * 2.0 ** float(getattr(light, "exposure", 0.0))
    strength = color * power * factor
    if not np.isfinite(strength).all() or (strength < 0.0).any():
        name, unit = ("Strength", "W/m²") if light.type == "SUN" else ("Power", "W")
        if light.energy < 0.0:
            cause = "its %s %g %s is negative" % (name, light.energy, unit)
        elif (factor < 0.0).any():
            cause = "its node tree's Emission is negative"
        else:
            cause = "its %s is not a number" % name
        raise BakeError("Light '%s': %s. The bake only adds light: set it to 0 or more" % (light_object.name, cause))
    return strength, problems


def node_tree_factor(light_object):
    """What the lamp's node tree multiplies its colour x power by (3,), and (problem, item) pairs.

    The Light Output's Surface followed to an Emission node whose Color and Strength are
    constants: Color x Strength. Nothing at the output: 0 (Cycles renders no light). Anything
    that varies over the lamp or its directions (a texture, an IES profile, Light Falloff, math
    nodes, any shader but Emission): 1, with a problem naming the lamp, since the bake cannot
    evaluate it."""
    light = light_object.data
    if not light.use_nodes or light.node_tree is None:
        return np.ones(3), []
    output = _light_output(light.node_tree)
    if output is None or not output.inputs["Surface"].is_linked:
        return np.zeros(3), [(NODES_EMIT_NOTHING, light_object.name)]
    node = materials._linked_node(output.inputs["Surface"])
    if node is None:
        return np.zeros(3), [(NODES_EMIT_NOTHING, light_object.name)]
    if node.type != "EMISSION":
        return np.ones(3), [(NODES_VARY, (light_object.name, "Light Output fed by '%s'" % node.bl_label))]
    color, strength = node.inputs["Color"], node.inputs["Strength"]
    for socket in (strength, color):
        if socket.is_linked:
            source = materials._linked_node(socket)
            label = source.bl_label if source is not None else "nothing"
            return np.ones(3), [(NODES_VARY, (light_object.name, "%s from '%s'" % (socket.name, label)))]
    return np.array(color.default_value[:3], dtype=np.float64) * float(strength.default_value), []


def _light_output(tree):
    """The Light Output Cycles uses: the active one of those for All or Cycles (as
    materials._surface_output picks a material's)."""
    outputs = [n for n in tree.nodes if n.type == "OUTPUT_LIGHT" and n.target in {"ALL", "CYCLES"}]
    active = [n for n in outputs if n.is_active_output]
    return (active or outputs or [None])[0]


def point_like(light_object, matrix, strength):
    """A core light dict for a point, spot or sun lamp of `strength` (lamp_strength), and a list
    of (problem, item) pairs."""
    light = light_object.data
    problems = []
    legacy = bpy.app.version < (4, 0, 0)
    if light.type in {"POINT", "SPOT"}:
        entry = {"type": light.type, "position": tuple(matrix.translation),
                 "intensity": tuple(strength / (4.0 * math.pi)), "radius": max(0.0, float(light.shadow_soft_size)),
                 "shape": lamp_shape(light)}
        if light.type == "SPOT":
            entry.update(direction=_emitting_axis(light_object, matrix), half_angle=0.5 * light.spot_size,
                         blend=light.spot_blend, cosine_profile=legacy)
        return entry, problems
    return {"type": "SUN", "direction": _emitting_axis(light_object, matrix), "irradiance": tuple(strength),
            "half_angle": min(0.5 * float(light.angle), 0.5 * math.pi - 1e-6), "disk_directions": legacy}, problems


def lamp_shape(light):
    """What a point or spot lamp's radius makes it to this Blender's Cycles (see the top)."""
    return "DISK" if getattr(light, "use_soft_falloff", True) else "SPHERE"


def area_quads(light_object, matrix, strength):
    """An area lamp of `strength` (lamp_strength) as world-space vertices (V,3) and quads (Q,4) of
    vertex indices, each ordered so it faces the lamp's -Z; its emitted radiance (3,), and a list
    of (problem, item) pairs. A rectangle is one quad, a disk or ellipse a grid of them."""
    light = light_object.data
    size_x = light.size
    size_y = light.size_y if light.shape in {"RECTANGLE", "ELLIPSE"} else light.size
    round_shape = light.shape in {"DISK", "ELLIPSE"}
    cells = ELLIPSE_GRID if round_shape else 1
    s, t = np.meshgrid(np.linspace(-1.0, 1.0, cells + 1), np.linspace(-1.0, 1.0, cells + 1), indexing="ij")
    s, t = s.ravel(), t.ravel()
    if round_shape:
        s, t = s * np.sqrt(1.0 - 0.5 * t * t), t * np.sqrt(1.0 - 0.5 * s * s)
    local = np.column_stack([0.5 * size_x * s, 0.5 * size_y * t])
    i, j = np.meshgrid(np.arange(cells), np.arange(cells), indexing="ij")
    first = (i * (cells + 1) + j).ravel()
    # (i, j) -> (i, j + 1) -> (i + 1, j + 1) -> (i + 1, j): clockwise seen from +Z, facing -Z.
    quads = np.stack([first, first + 1, first + cells + 2, first + cells + 1], axis=1)
    m = np.array(matrix)
    vertices = local @ m[:3, :2].T + m[:3, 3]
    scale_x = np.linalg.norm(m[:3, 0])
    scale_y = np.linalg.norm(m[:3, 1])
    # The quads' own area (shoelace), so that they emit the lamp's whole power.
    x, y = local[quads, 0], local[quads, 1]
    area = 0.5 * abs(float((x * np.roll(y, -1, axis=1) - np.roll(x, -1, axis=1) * y).sum())) * scale_x * scale_y
    # A mirroring transform flips the winding but not the lamp's -Z: keep the quads facing -Z.
    if np.linalg.det(m[:3, :3]) < 0.0:
        quads = quads[:, ::-1]
    problems = []
    if light.spread < math.pi - 1e-6:
        problems.append((SPREAD, (light_object.name, "%.0f deg" % math.degrees(light.spread))))
    radiance = area_radiance(light, strength, area)
    return vertices, quads, radiance, problems


def area_radiance(light, strength, area):
    """Radiance (3,) of an area lamp of `strength` whose polygon has `area`, as this Blender's
    Cycles converts it (see the top of this file)."""
    if not area > 0.0:
        return np.zeros(3)
    if bpy.app.version < (4, 0, 0):
        return strength / (4.0 * area)
    return strength / (math.pi * (area if getattr(light, "normalize", True) else 1.0))


def _emitting_axis(light_object, matrix):
    axis = -np.array(matrix.col[2][:3], dtype=np.float64)
    length = np.linalg.norm(axis)
    if not length > 0.0 or not np.isfinite(axis).all():
        raise BakeError("Light '%s' has no direction: its object is scaled to 0 along Z" % light_object.name)
    return tuple(axis / length)
