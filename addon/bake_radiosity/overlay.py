"""Draws the bake's elements over the 3D viewport while progressive refinement runs, so the
artist sees the solution brighten without anything being written into the file."""

import bpy
import gpu
import numpy as np
from gpu_extras.batch import batch_for_shader


class ProgressOverlay:
    def __init__(self, element_vertices, element_corners, element_back=None):
        tris, element_of_tri = _triangles(element_corners, element_back)
        positions = element_vertices[tris].astype(np.float64)
        normals = np.cross(positions[:, 1] - positions[:, 0], positions[:, 2] - positions[:, 0])
        normals /= np.maximum(np.linalg.norm(normals, axis=1), 1e-12)[:, None]
        # Lift the overlay off the surfaces it covers so depth testing does not make it flicker.
        extent = np.ptp(element_vertices, axis=0).max() if len(element_vertices) else 1.0
        positions += 1e-3 * extent * normals[:, None, :]
        self.positions = positions.reshape(-1, 3).astype(np.float32)
        self.element_of_vertex = np.repeat(element_of_tri, 3)
        self.shader = _smooth_color_shader()
        self.batch = None
        self.handle = bpy.types.SpaceView3D.draw_handler_add(self._draw, (), "WINDOW", "POST_VIEW")

    def show(self, element_radiance):
        # A plain display mapping: the overlay is a preview, the attribute keeps linear radiance.
        display = np.clip(element_radiance, 0.0, 1.0) ** (1.0 / 2.2)
        colors = np.ones((len(self.element_of_vertex), 4), dtype=np.float32)
        colors[:, :3] = display[self.element_of_vertex]
        self.batch = batch_for_shader(self.shader, "TRIS", {"pos": self.positions, "color": colors})
        _redraw_3d_views()

    def remove(self):
        bpy.types.SpaceView3D.draw_handler_remove(self.handle, "WINDOW")
        self.batch = None
        _redraw_3d_views()

    def _draw(self):
        if self.batch is None:
            return
        gpu.state.depth_test_set("LESS_EQUAL")
        self.batch.draw(self.shader)
        gpu.state.depth_test_set("NONE")


def _triangles(element_corners, element_back=None):
    """Fan triangles (T,3) of the element polygons (col 3 = -1 for triangles) and their element,
    without the emitters' back sides (`element_back`): the viewport shows each face's front."""
    elements = np.arange(len(element_corners))
    if element_back is not None:
        elements = elements[~element_back]
    corners = element_corners[elements]
    quads = corners[:, 3] >= 0
    first = corners[:, [0, 1, 2]]
    second = corners[quads][:, [0, 2, 3]]
    return np.concatenate([first, second]), np.concatenate([elements, elements[quads]])


def _smooth_color_shader():
    # Blender 4 renamed the built-in shaders; 3.x only knows the "3D_" names.
    name = "SMOOTH_COLOR" if bpy.app.version >= (4, 0, 0) else "3D_SMOOTH_COLOR"
    return gpu.shader.from_builtin(name)


def _redraw_3d_views():
    for window in bpy.context.window_manager.windows:
        for area in window.screen.areas:
            if area.type == "VIEW_3D":
                area.tag_redraw()
