"""A game-level-like interior for measuring against Cycles: six rooms (5 x 4 m, 3 m high) in a
3 x 2 grid, joined by doorways in 15 cm walls, with pillars and crates, 24 point lamps and 3 area
lamps, coloured Lambert materials, inside corners everywhere. Built with numpy and foreach_set
(blender_tests/scenes.py); every face is a quad of at most 0.5 m.

    import level; level.build()   # inside Blender, with lab/interior and blender_tests on sys.path
"""

import math

import bpy

import scenes

ROOM_X, ROOM_Y, HEIGHT = 5.0, 4.0, 3.0
ROOMS_X, ROOMS_Y = 3, 2
WALL = 0.15                # interior wall thickness
DOOR_WIDTH, DOOR_HEIGHT = 1.0, 2.2
CELL = 0.5                 # largest face edge
LAMP_WATTS = 40.0
AREA_LAMP_WATTS = 150.0
MATERIALS = [("Plaster", (0.70, 0.68, 0.62)), ("Brick", (0.55, 0.25, 0.18)), ("Tiles", (0.25, 0.45, 0.55)),
             ("Moss", (0.30, 0.50, 0.22)), ("Wood", (0.45, 0.32, 0.20)), ("Stone", (0.40, 0.40, 0.42))]


def _cells(extent):
    return max(1, math.ceil(extent / CELL - 1e-9))


def box(lo, hi, material, open_bottom=False):
    """The faces of an axis-aligned box (outward normals), each split into cells of at most CELL."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    dx, dy, dz = x1 - x0, y1 - y0, z1 - z0
    nx, ny, nz = _cells(dx), _cells(dy), _cells(dz)
    faces = [
        scenes.grid((x0, y0, z1), (dx, 0, 0), (0, dy, 0), nx, ny),   # top, +Z
        scenes.grid((x0, y0, z0), (dx, 0, 0), (0, 0, dz), nx, nz),   # -Y
        scenes.grid((x0, y1, z0), (0, 0, dz), (dx, 0, 0), nz, nx),   # +Y
        scenes.grid((x0, y0, z0), (0, 0, dz), (0, dy, 0), nz, ny),   # -X
        scenes.grid((x1, y0, z0), (0, dy, 0), (0, 0, dz), ny, nz),   # +X
    ]
    if not open_bottom:
        faces.append(scenes.grid((x0, y0, z0), (0, dy, 0), (dx, 0, 0), ny, nx))  # bottom, -Z
    return [f + (material,) for f in faces]


def shell(material_floor, material_walls, material_ceiling):
    """Floor, ceiling and outer walls of the whole level, normals inward."""
    sx, sy, h = ROOMS_X * ROOM_X, ROOMS_Y * ROOM_Y, HEIGHT
    g = scenes.grid
    return [
        g((0, 0, 0), (sx, 0, 0), (0, sy, 0), _cells(sx), _cells(sy)) + (material_floor,),
        g((0, 0, h), (0, sy, 0), (sx, 0, 0), _cells(sy), _cells(sx)) + (material_ceiling,),
        g((0, 0, 0), (0, 0, h), (sx, 0, 0), _cells(h), _cells(sx)) + (material_walls,),   # y = 0, +Y
        g((0, sy, 0), (sx, 0, 0), (0, 0, h), _cells(sx), _cells(h)) + (material_walls,),  # y = sy, -Y
        g((0, 0, 0), (0, sy, 0), (0, 0, h), _cells(sy), _cells(h)) + (material_walls,),   # x = 0, +X
        g((sx, 0, 0), (0, 0, h), (0, sy, 0), _cells(h), _cells(sy)) + (material_walls,),  # x = sx, -X
    ]


def wall_with_door(start, end, axis, material):
    """A 15 cm wall along `axis` (0: x, 1: y) from `start` to `end` (its centre line), floor to
    ceiling, with a doorway in its middle: two full-height pieces and a lintel."""
    (a0, a1), c = (start[axis], end[axis]), start[1 - axis]
    middle = 0.5 * (a0 + a1)
    pieces = [(a0, middle - DOOR_WIDTH / 2, 0.0, HEIGHT), (middle + DOOR_WIDTH / 2, a1, 0.0, HEIGHT),
              (middle - DOOR_WIDTH / 2, middle + DOOR_WIDTH / 2, DOOR_HEIGHT, HEIGHT)]
    faces = []
    for p0, p1, z0, z1 in pieces:
        lo, hi = [0.0, 0.0, z0], [0.0, 0.0, z1]
        lo[axis], hi[axis] = p0, p1
        lo[1 - axis], hi[1 - axis] = c - WALL / 2, c + WALL / 2
        faces += box(lo, hi, material)
    return faces


def build():
    """Clears the scene and builds the level; returns the level's mesh object."""
    scenes.clear_scene()
    materials = [scenes.diffuse(name, color) for name, color in MATERIALS]
    pieces = shell(4, 0, 5)
    for i in range(1, ROOMS_X):  # walls between rooms across x, one per row of rooms
        for j in range(ROOMS_Y):
            pieces += wall_with_door((i * ROOM_X, j * ROOM_Y), (i * ROOM_X, (j + 1) * ROOM_Y), 1, 1 + (i + j) % 3)
    for i in range(ROOMS_X):     # walls between the two rows
        pieces += wall_with_door((i * ROOM_X, ROOM_Y), ((i + 1) * ROOM_X, ROOM_Y), 0, 2 + i % 2)
    for i in range(ROOMS_X):     # a pillar and a crate in every room, a second crate stacked on some
        for j in range(ROOMS_Y):
            x, y = i * ROOM_X, j * ROOM_Y
            pieces += box((x + 1.2, y + 1.0, 0.0), (x + 1.6, y + 1.4, HEIGHT), 5, open_bottom=True)
            pieces += box((x + 3.2, y + 2.4, 0.0), (x + 3.9, y + 3.1, 0.7), 4, open_bottom=True)
            if (i + j) % 2 == 0:
                pieces += box((x + 3.35, y + 2.55, 0.7), (x + 3.75, y + 2.95, 1.1), 3, open_bottom=True)
    level = scenes.mesh_object("Level", pieces, materials)
    for i in range(ROOMS_X):     # four point lamps a room under the ceiling, an area lamp in three rooms
        for j in range(ROOMS_Y):
            x, y = i * ROOM_X, j * ROOM_Y
            for k, (u, v) in enumerate(((0.8, 0.7), (4.2, 0.7), (0.8, 3.3), (4.2, 3.3))):
                lamp = bpy.data.lights.new("Lamp %d%d%d" % (i, j, k), "POINT")
                lamp.energy = LAMP_WATTS
                lamp.shadow_soft_size = 0.0
                lamp.color = ((1.0, 0.85, 0.7), (0.8, 0.9, 1.0))[(i + j + k) % 2]
                obj = bpy.data.objects.new(lamp.name, lamp)
                obj.location = (x + u, y + v, 2.6)
                bpy.context.scene.collection.objects.link(obj)
            if (i + j) % 2 == 1:
                lamp = bpy.data.lights.new("Panel %d%d" % (i, j), "AREA")
                lamp.shape, lamp.size, lamp.energy = "SQUARE", 0.6, AREA_LAMP_WATTS
                obj = bpy.data.objects.new(lamp.name, lamp)
                obj.location = (x + 2.5, y + 2.0, HEIGHT - 0.05)  # area lamps emit along their -Z: down
                bpy.context.scene.collection.objects.link(obj)
    return level
