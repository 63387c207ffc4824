"""Blender lamps in the core's units, converted exactly as Cycles converts them.

Cycles (intern/cycles/blender/light.cpp, scene/light.cpp, kernel/light/*) sets a lamp's
strength to colour x power and then:
- point and spot: a sphere of radius r with radiance strength / (4 pi * pi r^2), so a point's
  radiant intensity is strength / (4 pi) W/sr. A spot uses the same intensity inside its cone
  (its cone does not concentrate the power), with Cycles' smoothstep blend at the rim.
- sun: irradiance strength W/m^2 on a surface facing it.
- area: one-sided radiance strength / (4 A) from the lamp's -Z side, A = size_x * size_y
  (times the object's scale, times pi/4 for disk and ellipse).
"""

import math

import numpy as np

# Disk and ellipse lamps become polygons with this many sides (0.6% less area than the ellipse;
# the radiance is kept, so the emitted power is 0.6% low).
ELLIPSE_SIDES = 32


def point_like(light_object, matrix):
    """A core light dict for a point, spot or sun lamp, and a list of warnings."""
    light = light_object.data
    strength = np.array(light.color[:3]) * light.energy
    warnings = []
    if light.type in {"POINT", "SPOT"}:
        if light.shadow_soft_size > 0.0:
            warnings.append("Light '%s': radius %.3g m is treated as a point (hard shadows)"
                            % (light_object.name, light.shadow_soft_size))
        entry = {"type": light.type, "position": tuple(matrix.translation),
                 "intensity": tuple(strength / (4.0 * math.pi))}
        if light.type == "SPOT":
            entry.update(direction=_emitting_axis(matrix), half_angle=0.5 * light.spot_size,
                         blend=light.spot_blend)
        return entry, warnings
    if light.angle > 0.0:
        warnings.append("Light '%s': sun angle %.3g deg is treated as 0 (hard shadows)"
                        % (light_object.name, math.degrees(light.angle)))
    return {"type": "SUN", "direction": _emitting_axis(matrix), "irradiance": tuple(strength)}, warnings


def area_polygon(light_object, matrix):
    """World-space corners (N,3) of an area lamp, ordered so the polygon faces the lamp's -Z,
    its emitted radiance (3,), and a list of warnings."""
    light = light_object.data
    size_x = light.size
    size_y = light.size_y if light.shape in {"RECTANGLE", "ELLIPSE"} else light.size
    round_shape = light.shape in {"DISK", "ELLIPSE"}
    if round_shape:
        angles = np.linspace(0.0, -2.0 * math.pi, ELLIPSE_SIDES, endpoint=False)
        local = np.column_stack([0.5 * size_x * np.cos(angles), 0.5 * size_y * np.sin(angles)])
    else:
        # Clockwise seen from +Z, so the polygon's normal is -Z.
        local = 0.5 * np.array([[-size_x, -size_y], [-size_x, size_y], [size_x, size_y], [size_x, -size_y]])
    m = np.array(matrix)
    corners = local @ m[:3, :2].T + m[:3, 3]
    scale_x = np.linalg.norm(m[:3, 0])
    scale_y = np.linalg.norm(m[:3, 1])
    area = size_x * scale_x * size_y * scale_y * (math.pi / 4.0 if round_shape else 1.0)
    # A mirroring transform flips the winding but not the lamp's -Z: keep the polygon facing -Z.
    if np.linalg.det(m[:3, :3]) < 0.0:
        corners = corners[::-1]
    warnings = []
    if light.spread < math.pi - 1e-6:
        warnings.append("Light '%s': spread %.0f deg is ignored (emits over the full hemisphere)"
                        % (light_object.name, math.degrees(light.spread)))
    strength = np.array(light.color[:3]) * light.energy
    radiance = strength / (4.0 * area) if area > 0.0 else np.zeros(3)
    return corners, radiance, warnings


def _emitting_axis(matrix):
    axis = -np.array(matrix.col[2][:3], dtype=np.float64)
    return tuple(axis / np.linalg.norm(axis))
