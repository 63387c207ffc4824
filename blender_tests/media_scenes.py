"""The fog box for the Cycles comparison: an open-fronted room of diffuse walls, a cube of grey fog
in the middle, a camera looking in, lit by an area lamp filling an opening in its ceiling or by a
point lamp inside the fog."""

import bpy
import numpy as np

import scenes

# 16^3 zones over the fog cube. With one grid cell per zone the baked render was 9.6% (RMS, net of
# Cycles' noise) off the original; grids 3x finer with J interpolated and 0.0625 m wall elements
# bring it to 4.8% (docs/volumes.md).
ZONE = 0.03125
CELLS = 8
# The lamp fills ceiling cells [3, 5) x [3, 5). Cycles' lamps neither block nor reflect light,
# but the bake's lamp polygon does: under a closed ceiling it would shadow the ceiling above it.
LAMP_CELLS = (3, 5)


def fog_box_scene(work, point_lamp_at=None):
    """With `point_lamp_at` a point lamp of radius 0 there lights the room, its ceiling closed."""
    scenes.clear_scene()
    walls = scenes.diffuse("Walls", (0.6, 0.6, 0.6))
    # No wall at y = 0: the camera looks in.
    sides = [((0, 0, 0), (1, 0, 0), (0, 1, 0)), ((0, 1, 0), (1, 0, 0), (0, 0, 1)),
             ((0, 0, 0), (0, 1, 0), (0, 0, 1)), ((1, 0, 0), (0, 0, 1), (0, 1, 0))]
    pieces = [scenes.grid(o, u, v, CELLS, CELLS) + (0,) for o, u, v in sides]
    ceiling_vertices, ceiling_quads = scenes.grid((0, 0, 1), (0, 1, 0), (1, 0, 0), CELLS, CELLS)  # normal -Z
    row, column = np.divmod(np.arange(CELLS * CELLS), CELLS)
    lo, hi = LAMP_CELLS
    opening = (row >= lo) & (row < hi) & (column >= lo) & (column < hi) & (point_lamp_at is None)
    pieces.append((ceiling_vertices, ceiling_quads[~opening], 0))
    scenes.mesh_object("Room", pieces, [walls])
    fog = bpy.data.materials.new("Fog")
    fog.use_nodes = True
    nodes = fog.node_tree.nodes
    nodes.clear()
    node = nodes.new("ShaderNodeVolumePrincipled")
    node.inputs["Color"].default_value = (0.8, 0.8, 0.8, 1.0)
    node.inputs["Density"].default_value = 3.0
    output = nodes.new("ShaderNodeOutputMaterial")
    fog.node_tree.links.new(node.outputs[0], output.inputs["Volume"])
    lo_corner, size = np.array([0.25, 0.25, 0.25]), 0.5
    cube = [((0, 0, 0), (0, 1, 0), (1, 0, 0)), ((0, 0, 1), (1, 0, 0), (0, 1, 0)),
            ((0, 0, 0), (1, 0, 0), (0, 0, 1)), ((0, 1, 0), (0, 0, 1), (1, 0, 0)),
            ((0, 0, 0), (0, 0, 1), (0, 1, 0)), ((1, 0, 0), (0, 1, 0), (0, 0, 1))]
    scenes.mesh_object("Fog", [scenes.grid(lo_corner + size * np.array(o), size * np.array(u),
                                           size * np.array(v), 1, 1) + (0,) for o, u, v in cube], [fog])
    if point_lamp_at is None:
        lamp = bpy.data.lights.new("Lamp", "AREA")
        lamp.shape = "SQUARE"
        lamp.size = (hi - lo) / CELLS
        lamp.energy = 20.0
    else:
        lamp = bpy.data.lights.new("Lamp", "POINT")
        lamp.shadow_soft_size = 0.0
        lamp.energy = 5.0
    lamp_object = bpy.data.objects.new("Lamp", lamp)
    # An area lamp sits in the opening, facing down (-Z).
    lamp_object.location = (0.5, 0.5, 1.0) if point_lamp_at is None else point_lamp_at
    lamp_object.visible_camera = False  # the baked scene shows the opening, not the lamp
    bpy.context.scene.collection.objects.link(lamp_object)
    scenes.camera_looking_along_y((0.5, -1.0, 0.5), 24.0)
    settings = bpy.context.scene.radiosity
    settings.zone_size = ZONE
    settings.media_folder = work + "/"
