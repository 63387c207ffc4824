"""Small scenes built as OpenArena's converted levels are (../shared/levels/q3_level_to_blend.py):
one mesh object, rooms whose visible faces are the sides of brushes (no faces hidden inside a
solid), pieces that are not welded to their neighbours (a vertex of one lies inside another's
edge: T-junctions), and point lamps of radius 5 cm. Faces are grids of about `cell` metres."""

import bpy
import numpy as np

import scenes

LAMP_RADIUS = 0.05  # every lamp of the converted levels
GREY = (0.5, 0.5, 0.5)


def rect(origin, a, b, normal, cell):
    """A piece (vertices, quads, 0): the rectangle origin + s a + t b (s, t in [0, 1]) facing
    `normal`, a grid of cells of at most `cell` metres."""
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    if np.dot(np.cross(a, b), normal) < 0:
        a, b = b, a
    counts = [max(1, int(np.ceil(np.linalg.norm(side) / cell - 1e-9))) for side in (a, b)]
    return scenes.grid(origin, a, b, *counts) + (0,)


AXES = np.eye(3)


def box(lo, hi, cell, inward=False, skip=()):
    """The six sides of the box lo..hi as pieces, facing out (a brush) or in (a room), but those
    named in `skip` ('-x', '+z', ...: the side at lo or hi along that axis)."""
    lo, hi = np.asarray(lo, dtype=np.float64), np.asarray(hi, dtype=np.float64)
    pieces = []
    for axis in range(3):
        first, second = AXES[(axis + 1) % 3] * (hi - lo), AXES[(axis + 2) % 3] * (hi - lo)
        for sign, name in ((-1, "-"), (1, "+")):
            if name + "xyz"[axis] in skip:
                continue
            origin = lo.copy()
            if sign > 0:
                origin[axis] = hi[axis]
            pieces.append(rect(origin, first, second, AXES[axis] * (-sign if inward else sign), cell))
    return pieces


def point_lamp(name, location, watts, radius=LAMP_RADIUS):
    lamp = bpy.data.lights.new(name, "POINT")
    lamp.energy, lamp.shadow_soft_size = watts, radius
    lamp_object = bpy.data.objects.new(name, lamp)
    lamp_object.location = location
    bpy.context.scene.collection.objects.link(lamp_object)
    return lamp_object


def level_object(pieces, color=GREY):
    return scenes.mesh_object("Level", pieces, [scenes.diffuse("Brush", color)])


def shade(center, inner, thickness, above, below, cell):
    """An open shade around a lamp at `center`, as one closed shell: a square cup 2 `inner` wide
    inside, its walls and top `thickness` thick, its inner top `above` over the lamp's centre, its
    rim `below` under it, open downwards."""
    cx, cy, cz = center
    o, i = inner + thickness, inner
    top, rim, roof = cz + above, cz - below, cz + above + thickness
    pieces = box((cx - o, cy - o, rim), (cx + o, cy + o, roof), cell, skip=("-z",))  # outside
    pieces += box((cx - i, cy - i, rim), (cx + i, cy + i, top), cell, inward=True, skip=("-z",))  # inside
    down = (0, 0, -1)
    for x0, x1, y0, y1 in ((-o, o, -o, -i), (-o, o, i, o), (-o, -i, -i, i), (i, o, -i, i)):  # the rim
        pieces.append(rect((cx + x0, cy + y0, rim), (x1 - x0, 0, 0), (0, y1 - y0, 0), down, cell))
    return pieces


def wall_with_door(plane_x, y_range, height, door, thickness, cell):
    """A wall brush between x = plane_x and plane_x + thickness across y_range, floor to `height`,
    with a doorway door = (y0, y1, top): its two faces (each three rectangles around the opening,
    not welded to each other), the doorway's jambs and lintel, and the floor through it."""
    (y_lo, y_hi), (y0, y1, top) = y_range, door
    x0, x1 = plane_x, plane_x + thickness
    pieces = []
    for x, normal in ((x0, (-1, 0, 0)), (x1, (1, 0, 0))):
        pieces.append(rect((x, y_lo, 0), (0, y0 - y_lo, 0), (0, 0, height), normal, cell))
        pieces.append(rect((x, y1, 0), (0, y_hi - y1, 0), (0, 0, height), normal, cell))
        pieces.append(rect((x, y0, top), (0, y1 - y0, 0), (0, 0, height - top), normal, cell))
    pieces.append(rect((x0, y0, 0), (thickness, 0, 0), (0, 0, top), (0, 1, 0), cell))
    pieces.append(rect((x0, y1, 0), (thickness, 0, 0), (0, 0, top), (0, -1, 0), cell))
    pieces.append(rect((x0, y0, top), (thickness, 0, 0), (0, y1 - y0, 0), (0, 0, -1), cell))
    pieces.append(rect((x0, y0, 0), (thickness, 0, 0), (0, y1 - y0, 0), (0, 0, 1), cell))
    return pieces
