"""The scene as the engine takes it: flat arrays of world-space polygons with their materials,
plus lamps, and where each exported object's polygons sit in them (export.py fills it in Blender)."""

from dataclasses import dataclass, field

import numpy as np


@dataclass
class Part:
    """One exported mesh instance and where its polygons and corners sit in the flat arrays."""
    object_name: str
    mesh_name: str
    is_instance: bool
    polygon_start: int
    polygon_stop: int
    corner_start: int
    corner_stop: int
    # corner_order[k] = the mesh loop stored at flat corner corner_start + k (winding reversed
    # for mirrored instances so normals point the way Blender shows them).
    corner_order: np.ndarray
    polygon_material_index: np.ndarray
    material_names: list
    matrix_world: np.ndarray
    unwritable: str = ""  # why ORIGINAL cannot write its light onto the object's mesh ("" = it can)
    shares_mesh: bool = False  # another baked object shows the same mesh (a linked duplicate, Alt+D)
    object_library: str = ""  # the library file the object is linked from ("" = this file's own object)


@dataclass
class ExportedScene:
    positions: np.ndarray       # (V,3) float32, world space
    face_offsets: np.ndarray    # (F+1,) int32
    corner_vertices: np.ndarray  # (C,) int32
    reflectance: np.ndarray     # (F,3) float32
    emission: np.ndarray        # (F,3) float32
    material: np.ndarray        # (F,) int32: one id per material, lamps get their own
    front_only: np.ndarray      # (F,) uint8: 1 = emits from its front only (area lamps; faces emit from both sides)
    lights: list
    parts: list
    warnings: list = field(default_factory=list)
    # The `textures` keyword of _core.bake (images, corner_uv, per-face texture and scale for
    # reflectance and emission); None when no face is textured.
    textures: dict = None
    # Light groups (Blender 3.2 and later): polygon f's is light_group_names[polygon_light_group[f]],
    # lamp l's lamp_light_groups[l]; "" for none.
    light_group_names: list = field(default_factory=lambda: [""])
    polygon_light_group: np.ndarray = None
    lamp_light_groups: list = field(default_factory=list)

    @property
    def polygon_count(self):
        return len(self.face_offsets) - 1

    def polygon_name(self, polygon):
        """'<object> face <n>' for an exported polygon index ('a lamp' for lamp polygons, 'no one face' for -1)."""
        if polygon < 0:
            return "no one face"
        part = next((p for p in self.parts if p.polygon_start <= polygon < p.polygon_stop), None)
        return "%s face %d" % (part.object_name, polygon - part.polygon_start) if part else "a lamp"

    def scene_arrays(self):
        """The arrays `_core.plan` and `_core.bake` take first, in their order."""
        return (self.positions, self.face_offsets, self.corner_vertices, self.reflectance, self.emission,
                self.material)
