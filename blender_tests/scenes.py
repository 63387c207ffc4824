"""Test and demo scenes built from numpy arrays (no add-on needed): quads, grids, the Cornell box.

Every mesh is made with foreach_set; normals follow the quads' winding (u x v)."""

import math
import os
import tempfile

import bpy
import numpy as np

import harness

WHITE = (0.73, 0.73, 0.73)
RED = (0.63, 0.065, 0.05)
GREEN = (0.14, 0.45, 0.091)
# Opening of the Cornell box's ceiling light, in cells of the 8 x 8 ceiling grid.
CORNELL_CELLS = 8
CORNELL_LIGHT_CELLS = (3, 5)
ROOM_SIDES = [  # (origin, u, v) of a closed 2 m room, u x v pointing inwards: floor, ceiling, walls
    ((0, 0, 0), (2, 0, 0), (0, 2, 0)), ((0, 0, 2), (0, 2, 0), (2, 0, 0)),
    ((0, 0, 0), (0, 0, 2), (2, 0, 0)), ((0, 2, 0), (2, 0, 0), (0, 0, 2)),
    ((0, 0, 0), (0, 2, 0), (0, 0, 2)), ((2, 0, 0), (0, 0, 2), (0, 2, 0)),
]


def clear_scene():
    for collection in (bpy.data.objects, bpy.data.meshes, bpy.data.materials, bpy.data.lights,
                       bpy.data.cameras, bpy.data.images):
        for item in list(collection):
            collection.remove(item)
    for collection in list(bpy.data.collections):
        bpy.data.collections.remove(collection)
    world = bpy.context.scene.world
    if world is not None:
        # A black world: light that leaves the scene is lost, as in a radiosity solution.
        world.color = (0.0, 0.0, 0.0)
        if bpy.app.version >= (5, 0, 0):
            # Blender 5 deprecated World.use_nodes (setting it does nothing): a world always
            # renders its node tree, whose default Background is grey. Make that black.
            for node in world.node_tree.nodes if world.node_tree else ():
                if node.type == "BACKGROUND":
                    node.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
                    node.inputs["Strength"].default_value = 0.0
        else:
            world.use_nodes = False


def grid(origin, u, v, nu, nv):
    """Vertices and quads of an nu x nv grid spanning origin + s*u + t*v, normal along u x v."""
    origin, u, v = (np.asarray(a, dtype=np.float64) for a in (origin, u, v))
    s, t = np.meshgrid(np.linspace(0, 1, nu + 1), np.linspace(0, 1, nv + 1), indexing="ij")
    vertices = origin + s.reshape(-1, 1) * u + t.reshape(-1, 1) * v
    i, j = np.meshgrid(np.arange(nu), np.arange(nv), indexing="ij")
    first = (i * (nv + 1) + j).ravel()
    quads = np.stack([first, first + nv + 1, first + nv + 2, first + 1], axis=1)
    return vertices, quads


def mesh_object(name, pieces, materials=()):
    """An object from [(vertices, polygons (P,k), material_index)], built with foreach_set."""
    vertices, polygons, material_index, offset = [], [], [], 0
    for piece_vertices, piece_polygons, material in pieces:
        vertices.append(piece_vertices)
        polygons.append(np.asarray(piece_polygons) + offset)
        material_index.append(np.full(len(piece_polygons), material))
        offset += len(piece_vertices)
    corners = np.concatenate([p.ravel() for p in polygons]).astype(np.int32)
    counts = np.concatenate([np.full(len(p), p.shape[1]) for p in polygons]).astype(np.int32)
    mesh = bpy.data.meshes.new(name)
    mesh.vertices.add(offset)
    mesh.vertices.foreach_set("co", np.concatenate(vertices).astype(np.float32).ravel())
    mesh.loops.add(len(corners))
    mesh.loops.foreach_set("vertex_index", corners)
    mesh.polygons.add(len(counts))
    mesh.polygons.foreach_set("loop_start", np.concatenate([[0], np.cumsum(counts)[:-1]]).astype(np.int32))
    mesh.polygons.foreach_set("loop_total", counts)
    mesh.polygons.foreach_set("material_index", np.concatenate(material_index).astype(np.int32))
    mesh.update(calc_edges=True)
    assert not mesh.validate(verbose=True), "built an invalid mesh"
    for material in materials:
        mesh.materials.append(material)
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def diffuse(name, color):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.clear()
    bsdf = nodes.new("ShaderNodeBsdfDiffuse")
    bsdf.inputs["Color"].default_value = (*color, 1.0)
    output = nodes.new("ShaderNodeOutputMaterial")
    material.node_tree.links.new(bsdf.outputs["BSDF"], output.inputs["Surface"])
    return material


def save_png(name, rgb):
    """An (height, width, 3) image, bottom row first, saved as an 8-bit sRGB PNG `name`.png in a new
    temporary folder; returns its path."""
    height, width = rgb.shape[:2]
    image = bpy.data.images.new(name, width, height)
    rgba = np.ones((height, width, 4), dtype=np.float32)
    rgba[:, :, :3] = rgb
    image.pixels.foreach_set(rgba.ravel())
    path = os.path.join(tempfile.mkdtemp(), name + ".png")
    image.filepath_raw = path
    image.file_format = "PNG"
    image.save()
    bpy.data.images.remove(image)
    return path


def image_texture_material(name, image, color, interpolation):
    """diffuse(name, color) with an Image Texture of `image` on its Color."""
    material = diffuse(name, color)
    nodes = material.node_tree.nodes
    texture = nodes.new("ShaderNodeTexImage")
    texture.image = image
    texture.interpolation = interpolation
    bsdf = next(n for n in nodes if n.bl_idname == "ShaderNodeBsdfDiffuse")
    material.node_tree.links.new(texture.outputs["Color"], bsdf.inputs["Color"])
    return material


def floor_with_uv_map(size, cells, material):
    """A size x size floor of cells x cells faces at z = 0 whose UV map spans the whole image once."""
    floor = mesh_object("Floor", [grid((0, 0, 0), (size, 0, 0), (0, size, 0), cells, cells) + (0,)], [material])
    uv = floor.data.uv_layers.new(name="UVMap")
    uv.data.foreach_set("uv", (harness.corner_positions(floor.data)[:, :2] / size).astype(np.float32).ravel())
    return floor


def wall_and_point_lamp(size, cells, albedo):
    """Beside floor_with_uv_map's floor: a grey wall in the plane x = 0 (size x size, cells x cells
    faces) and a 200 W point lamp of radius 0 over the floor. Returns the wall."""
    wall = mesh_object("Wall", [grid((0, 0, 0), (0, size, 0), (0, 0, size), cells, cells) + (0,)],
                       [diffuse("Grey Wall", (albedo,) * 3)])
    lamp = bpy.data.lights.new("Lamp", "POINT")
    lamp.shadow_soft_size = 0.0
    lamp.energy = 200.0
    lamp_object = bpy.data.objects.new("Lamp", lamp)
    lamp_object.location = (1.2, 0.9, 1.3)
    bpy.context.scene.collection.objects.link(lamp_object)
    return wall


def emission(name, color, strength):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.clear()
    shader = nodes.new("ShaderNodeEmission")
    shader.inputs["Color"].default_value = (*color, 1.0)
    shader.inputs["Strength"].default_value = strength
    output = nodes.new("ShaderNodeOutputMaterial")
    material.node_tree.links.new(shader.outputs["Emission"], output.inputs["Surface"])
    return material


def fog_material(name="Fog"):
    """A material with only a Principled Volume (its defaults) on the output's Volume input."""
    fog = bpy.data.materials.new(name)
    fog.use_nodes = True
    nodes = fog.node_tree.nodes
    nodes.remove(nodes["Principled BSDF"])
    volume = nodes.new("ShaderNodeVolumePrincipled")
    fog.node_tree.links.new(volume.outputs[0], nodes["Material Output"].inputs["Volume"])
    return fog


def furnace_material(rho, emitted):
    """Diffuse + Emission through an Add Shader, which the export must sum."""
    material = bpy.data.materials.new("Furnace")
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.clear()
    bsdf = nodes.new("ShaderNodeBsdfDiffuse")
    bsdf.inputs["Color"].default_value = (rho, rho, rho, 1)
    light = nodes.new("ShaderNodeEmission")
    light.inputs["Strength"].default_value = emitted
    add = nodes.new("ShaderNodeAddShader")
    output = nodes.new("ShaderNodeOutputMaterial")
    links = material.node_tree.links
    links.new(bsdf.outputs[0], add.inputs[0])
    links.new(light.outputs[0], add.inputs[1])
    links.new(add.outputs[0], output.inputs["Surface"])
    return material


def furnace_box(rho, emitted, cells=4):
    """A closed unit cube seen from inside (normals inward), each side a cells x cells grid, every
    face emitting `emitted` and reflecting `rho`: the exact radiance is emitted / (1 - rho)."""
    sides = [  # (origin, u, v) with u x v pointing into the box
        ((0, 0, 0), (1, 0, 0), (0, 1, 0)), ((0, 0, 1), (0, 1, 0), (1, 0, 0)),
        ((0, 0, 0), (0, 0, 1), (1, 0, 0)), ((0, 1, 0), (1, 0, 0), (0, 0, 1)),
        ((0, 0, 0), (0, 1, 0), (0, 0, 1)), ((1, 0, 0), (0, 0, 1), (0, 1, 0)),
    ]
    return mesh_object("Furnace", [grid(o, u, v, cells, cells) + (0,) for o, u, v in sides],
                       [furnace_material(rho, emitted)])


def cornell_box(light="MESH", radiance=8.0, cells=CORNELL_CELLS):
    """The Cornell box as one mesh object (open at -Y, 1 m wide, floor at z = 0), lit by
    'MESH' (an emitting opening in the ceiling, radiance `radiance`), 'AREA' (an area lamp
    filling that opening, same radiance) or 'POINT' (a point lamp under a closed ceiling,
    emitting the same power as the opening). Returns the mesh object."""
    white, red, green = diffuse("White", WHITE), diffuse("Red", RED), diffuse("Green", GREEN)
    materials = [white, red, green]
    d = 1.0 / cells
    blocks = (((0.5, 0.125), (0.875, 0.5), 3 * d),    # short block: corners (x, y), height
              ((0.125, 0.5), (0.5, 0.875), 6 * d))    # tall block
    floor_vertices, floor_quads = grid((0, 0, 0), (1, 0, 0), (0, 1, 0), cells, cells)   # normal +Z
    # No floor under the blocks: faces hidden inside a solid would share their corners with the
    # lit floor around it and darken it there (see docs/user-guide.md, "Hidden faces").
    centers = floor_vertices[floor_quads].mean(axis=1)
    hidden = np.zeros(len(floor_quads), dtype=bool)
    for (x0, y0), (x1, y1), _ in blocks:
        hidden |= (centers[:, 0] > x0) & (centers[:, 0] < x1) & (centers[:, 1] > y0) & (centers[:, 1] < y1)
    pieces = [
        (floor_vertices, floor_quads[~hidden], 0),
        grid((0, 1, 0), (1, 0, 0), (0, 0, 1), cells, cells) + (0,),        # back wall, normal -Y
        grid((0, 0, 0), (0, 1, 0), (0, 0, 1), cells, cells) + (1,),        # left wall (red), normal +X
        grid((1, 0, 0), (0, 0, 1), (0, 1, 0), cells, cells) + (2,),        # right wall (green), normal -X
    ]
    ceiling_vertices, ceiling_quads = grid((0, 0, 1), (0, 1, 0), (1, 0, 0), cells, cells)  # normal -Z
    cell_i, cell_j = np.divmod(np.arange(cells * cells), cells)  # grid rows run along +Y, columns along +X
    lo, hi = CORNELL_LIGHT_CELLS
    opening = (cell_i >= lo) & (cell_i < hi) & (cell_j >= lo) & (cell_j < hi)
    if light == "POINT":
        pieces.append((ceiling_vertices, ceiling_quads, 0))
    else:
        pieces.append((ceiling_vertices, ceiling_quads[~opening], 0))
        if light == "MESH":
            materials.append(emission("Light", (1.0, 1.0, 1.0), radiance))
            pieces.append((ceiling_vertices, ceiling_quads[opening], 3))
    for corner0, corner1, height in blocks:
        pieces += block(corner0, corner1, height, d)
    box = mesh_object("Cornell Box", pieces, materials)

    opening_side = (hi - lo) * d
    opening_area = opening_side ** 2
    if light == "AREA":
        lamp = bpy.data.lights.new("Area Lamp", "AREA")
        lamp.shape = "SQUARE"
        lamp.size = opening_side
        # Cycles gives an area lamp radiance power / (4 * area).
        lamp.energy = 4.0 * opening_area * radiance
        lamp_object = bpy.data.objects.new("Area Lamp", lamp)
        lamp_object.location = (0.5, 0.5, 1.0)   # lamps emit along their -Z: down
        bpy.context.scene.collection.objects.link(lamp_object)
    elif light == "POINT":
        lamp = bpy.data.lights.new("Point Lamp", "POINT")
        lamp.shadow_soft_size = 0.0
        # The opening emits pi * L * A watts; a point lamp of power P emits P.
        lamp.energy = math.pi * radiance * opening_area
        lamp_object = bpy.data.objects.new("Point Lamp", lamp)
        # Over open floor, 0.2 m under the ceiling: no surface so close to the lamp that 1/r^2
        # changes across one element (docs/user-guide.md, "Known limits").
        lamp_object.location = (0.7, 0.7, 0.8)
        bpy.context.scene.collection.objects.link(lamp_object)
    return box


def cornell_box_under_lamps(count):
    """The Cornell box and `count` point lamps 'Lamp 0', 'Lamp 1', ... of 2 W each, 0.15 m under the
    ceiling on a 0.5 m circle (the lab's light-group and re-bake timings). Returns the box."""
    clear_scene()
    box = cornell_box()
    for i in range(count):
        light = bpy.data.lights.new("Lamp %d" % i, "POINT")
        light.energy, light.shadow_soft_size = 2.0, 0.0
        lamp = bpy.data.objects.new("Lamp %d" % i, light)
        angle = 2.0 * math.pi * i / count
        lamp.location = (0.5 + 0.25 * math.cos(angle), 0.5 + 0.25 * math.sin(angle), 0.85)
        bpy.context.scene.collection.objects.link(lamp)
    return box


def room_with_panel(albedo=0.5):
    """A closed 2 m room (ROOM_SIDES, 4 x 4 quads a side) of the given albedo, lit by a 50 cm
    emitting panel facing down 10 cm under the ceiling."""
    clear_scene()
    walls = diffuse("Walls", (albedo, albedo, albedo))
    room = mesh_object("Room", [grid(o, u, v, 4, 4) + (0,) for o, u, v in ROOM_SIDES], [walls])
    mesh_object("Panel", [grid((0.75, 0.75, 1.9), (0, 0.5, 0), (0.5, 0, 0), 1, 1) + (0,)],
                [emission("Panel", (1.0, 1.0, 1.0), 5.0)])
    return room


def small_lamp_over_floor(side, height=1.5, rho=0.5, radiance=1000.0):
    """A 2 x 2 m floor (8 x 8 faces, normal +Z, reflectance `rho`) under a small emitting square of
    `side` metres at `height`, facing down, centred. The lamp is black and the floor does not see
    itself, so the floor's radiance is direct light: rho x radiance x the point-to-square factor.
    Returns the object and the lamp's four corners."""
    x0 = 1.0 - side / 2
    lamp = grid((x0, x0, height), (0, side, 0), (side, 0, 0), 1, 1)   # (0, s, 0) x (s, 0, 0): -Z
    obj = mesh_object("Floor and Lamp", [grid((0, 0, 0), (2, 0, 0), (0, 2, 0), 8, 8) + (0,), lamp + (1,)],
                      [diffuse("Grey", (rho, rho, rho)), emission("Lamp", (1.0, 1.0, 1.0), radiance)])
    return obj, lamp[0][lamp[1][0]]


def slab_over_floor(gap):
    """A 0.8 x 0.8 x 0.05 m white slab `gap` metres over a white 2 x 2 m floor (8 x 8 faces,
    reflectance 0.8), lit by a 0.5 m emitting square (radiance 10, material 1) 1.5 m up, facing
    down: the contact shadow where elements are larger than the gap between them. Returns the
    object."""
    x0, x1, z0, z1 = 0.6, 1.4, gap, gap + 0.05
    slab = [
        grid((x0, x0, z1), (x1 - x0, 0, 0), (0, x1 - x0, 0), 4, 4),   # top, +Z
        grid((x0, x0, z0), (0, x1 - x0, 0), (x1 - x0, 0, 0), 4, 4),   # bottom, -Z
        grid((x0, x0, z0), (x1 - x0, 0, 0), (0, 0, z1 - z0), 4, 1),   # -Y
        grid((x0, x1, z0), (0, 0, z1 - z0), (x1 - x0, 0, 0), 1, 4),   # +Y
        grid((x0, x0, z0), (0, 0, z1 - z0), (0, x1 - x0, 0), 1, 4),   # -X
        grid((x1, x0, z0), (0, x1 - x0, 0), (0, 0, z1 - z0), 4, 1),   # +X
    ]
    pieces = [grid((0, 0, 0), (2, 0, 0), (0, 2, 0), 8, 8) + (0,)] + [piece + (0,) for piece in slab]
    pieces.append(grid((0.75, 0.75, 1.5), (0, 0.5, 0), (0.5, 0, 0), 2, 2) + (1,))
    return mesh_object("Slab over Floor", pieces,
                       [diffuse("White", (0.8, 0.8, 0.8)), emission("Lamp", (1.0, 1.0, 1.0), 10.0)])


def under_and_around_slab(corners, gap):
    """Which of slab_over_floor(gap)'s face corners (positions, (loops, 3)) are on the floor within
    0.6 m of the slab's centre in x and y, or on the slab's underside: where its contact shadow falls."""
    on_floor = (corners[:, 2] == 0) & (np.abs(corners[:, 0] - 1) <= 0.6) & (np.abs(corners[:, 1] - 1) <= 0.6)
    return on_floor | (np.abs(corners[:, 2] - gap) < 1e-6)


def block(xy0, xy1, height, cell):
    """The five visible faces of an axis-aligned block standing on the floor (outward normals)."""
    (x0, y0), (x1, y1) = xy0, xy1
    nx, ny, nz = (max(1, round(extent / cell)) for extent in (x1 - x0, y1 - y0, height))
    return [
        grid((x0, y0, height), (x1 - x0, 0, 0), (0, y1 - y0, 0), nx, ny) + (0,),   # top, +Z
        grid((x0, y0, 0), (x1 - x0, 0, 0), (0, 0, height), nx, nz) + (0,),         # front, -Y
        grid((x0, y1, 0), (0, 0, height), (x1 - x0, 0, 0), nz, nx) + (0,),         # back, +Y
        grid((x0, y0, 0), (0, 0, height), (0, y1 - y0, 0), nz, ny) + (0,),         # left, -X
        grid((x1, y0, 0), (0, y1 - y0, 0), (0, 0, height), ny, nz) + (0,),         # right, +X
    ]


def camera_looking_along_y(location, lens):
    """The scene's camera at `location`, looking along +Y (into a box open at -Y)."""
    camera = bpy.data.cameras.new("Camera")
    camera.lens = lens
    obj = bpy.data.objects.new("Camera", camera)
    obj.location = location
    obj.rotation_euler = (math.pi / 2, 0.0, 0.0)
    bpy.context.scene.collection.objects.link(obj)
    bpy.context.scene.camera = obj
    return obj


def camera_for_cornell_box():
    return camera_looking_along_y((0.5, -1.02, 0.5), 35.0)


def wall_light(room, colors):
    """The cluttered room's walls' light from its mesh `room` and (loops, 3) `colors`: the corners'
    grey averaged per face, then over the wall faces (normal within 60 degrees of horizontal) by area."""
    count = len(room.polygons)
    loop_total, areas, normals = np.empty(count, dtype=np.int64), np.empty(count), np.empty(3 * count)
    room.polygons.foreach_get("loop_total", loop_total)
    room.polygons.foreach_get("area", areas)
    room.polygons.foreach_get("normal", normals)
    loop_face = np.repeat(np.arange(count), loop_total)
    face = np.bincount(loop_face, colors.mean(axis=1)) / np.bincount(loop_face)
    walls = np.abs(normals.reshape(-1, 3)[:, 2]) < 0.5
    return float((face[walls] * areas[walls]).sum() / areas[walls].sum())


def cluttered_room(blocks, size=0.02, cells=1):
    """A cluttered room: the inside of a 2 m cube (one object 'Room', rho 0.7, normals inward,
    `cells` x `cells` quads a side),
    a 0.5 m square 1 cm under the ceiling emitting radiance 10 downwards ('Panel', black, 7.85 W),
    and `blocks` closed 2 cm cubes (six faces each, rho 0.7) standing on the floor in one object
    'Blocks', scattered as an artist's scatter leaves them (native/core/hierarchy/tests/test_hierarchy.cpp's
    scatter_blocks, the same generator): some overlap, one in eight is pressed against the one
    before (a shared face), one in sixteen stands beside it 30 um off flush (the floor's contact
    cuts then leave a sliver thinner than the hierarchy's weld between their outlines)."""
    white = diffuse("White", (0.7, 0.7, 0.7))
    sides = [((0, 0, 0), (2, 0, 0), (0, 2, 0)), ((0, 0, 2), (0, 2, 0), (2, 0, 0)),   # floor, ceiling
             ((0, 0, 0), (0, 2, 0), (0, 0, 2)), ((2, 0, 0), (0, 0, 2), (0, 2, 0)),   # walls, inward
             ((0, 2, 0), (2, 0, 0), (0, 0, 2)), ((0, 0, 0), (0, 0, 2), (2, 0, 0))]
    mesh_object("Room", [grid(o, u, v, cells, cells) + (0,) for o, u, v in sides], [white])
    mesh_object("Panel", [grid((0.75, 0.75, 1.99), (0, 0.5, 0), (0.5, 0, 0), 1, 1) + (0,)],
                [emission("Panel", (1.0, 1.0, 1.0), 10.0)])
    if not blocks:
        return
    cube = [((0, 0, 0), (0, 1, 0), (1, 0, 0)), ((0, 0, 1), (1, 0, 0), (0, 1, 0)),
            ((0, 0, 0), (1, 0, 0), (0, 0, 1)), ((0, 1, 0), (0, 0, 1), (1, 0, 0)),
            ((0, 0, 0), (0, 0, 1), (0, 1, 0)), ((1, 0, 0), (0, 1, 0), (0, 0, 1))]
    seed, x, y, pieces = 12345, 0.0, 0.0, []

    def uniform():
        nonlocal seed
        seed = (seed * 1664525 + 1013904223) % 2 ** 32
        return np.float32((seed >> 8) / 16777216.0)

    for b in range(blocks):
        if b % 8 == 1:
            x = np.float32(x + np.float32(size))
        elif b % 16 == 2:
            x, y = np.float32(x + np.float32(3 * size)), np.float32(y + np.float32(3e-5))
        else:
            x = np.float32(np.float32(0.05) + np.float32(1.9) * uniform())
            y = np.float32(np.float32(0.05) + np.float32(1.9) * uniform())
        corner = np.array([x, y, 0.0])
        pieces += [grid(corner + size * np.array(o), size * np.array(u), size * np.array(v), 1, 1) + (0,)
                   for o, u, v in cube]
    mesh_object("Blocks", pieces, [white])


LAMP_ROOM_SIZE, LAMP_ROOM_HEIGHT = 10.0, 3.0


def lamp_room(count, radius, watts=1000.0, cells=20, cells_up=6):
    """A 10 x 10 x 3 m grey room (albedo 0.6, `cells` x `cells` quads on the floor and ceiling,
    `cells` x `cells_up` on each wall, one mesh, normals inside) lit by `count` point lamps of
    `radius`, `watts` in all: one 2 m over the centre of the floor, or many on a jittered grid
    between 1 m from the walls and heights of 1 to 2.5 m. Returns the room."""
    s, h = LAMP_ROOM_SIZE, LAMP_ROOM_HEIGHT
    pieces = [
        grid((0, 0, 0), (s, 0, 0), (0, s, 0), cells, cells),      # floor, facing +z
        grid((0, 0, h), (0, s, 0), (s, 0, 0), cells, cells),      # ceiling, facing -z
        grid((0, 0, 0), (0, 0, h), (s, 0, 0), cells_up, cells),   # y = 0, facing +y
        grid((0, s, 0), (s, 0, 0), (0, 0, h), cells, cells_up),   # y = s, facing -y
        grid((0, 0, 0), (0, s, 0), (0, 0, h), cells, cells_up),   # x = 0, facing +x
        grid((s, 0, 0), (0, 0, h), (0, s, 0), cells_up, cells),   # x = s, facing -x
    ]
    room = mesh_object("Room", [piece + (0,) for piece in pieces], [diffuse("Grey", (0.6,) * 3)])
    for k, position in enumerate(lamp_room_positions(count)):
        lamp = bpy.data.lights.new("Bulb %d" % k, "POINT")
        lamp.energy, lamp.shadow_soft_size = watts / count, radius
        obj = bpy.data.objects.new(lamp.name, lamp)
        obj.location = tuple(position)
        bpy.context.scene.collection.objects.link(obj)
    return room


def lamp_room_positions(count):
    if count == 1:
        return np.array([[LAMP_ROOM_SIZE / 2, LAMP_ROOM_SIZE / 2, 2.0]])
    side = int(np.ceil(np.sqrt(count)))
    random = np.random.default_rng(7)
    cells = np.array([(i, j) for i in range(side) for j in range(side)][:count], dtype=np.float64)
    xy = 1.0 + (cells + random.uniform(0.0, 1.0, cells.shape)) * (LAMP_ROOM_SIZE - 2.0) / side
    return np.column_stack([xy, random.uniform(1.0, 2.5, count)])


def lamp_room_surfaces(positions):
    """{name: mask} of the floor, the ceiling and the four walls for lamp_room's `positions`."""
    eps, s, h = 1e-4, LAMP_ROOM_SIZE, LAMP_ROOM_HEIGHT
    x, y, z = positions.T
    names = {"floor": z < eps, "ceiling": z > h - eps}
    side = ~names["floor"] & ~names["ceiling"]
    names.update({"wall y=0": side & (y < eps), "wall y=10": side & (y > s - eps),
                  "wall x=0": side & (x < eps), "wall x=10": side & (x > s - eps)})
    return names
