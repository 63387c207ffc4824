"""The rendered scene as flat arrays for the core: world-space polygons with their materials,
plus lamps. Reads evaluated meshes (modifiers applied, instances included) with foreach_get.
Which objects and lamps take part is what Cycles renders (visibility.py)."""

import bpy
import numpy as np

from . import lights, materials, media_materials, preview, textures, uv_mapping, visibility
from .engine.scene import ExportedScene, Part

# Objects made by a COPIES bake carry this property; they are output, never input.
COPY_TAG = "radiosity_bake_copy"
# Volume objects a bake made (media_writeback.py) carry this one; output too.
MEDIUM_TAG = "radiosity_bake_medium"
GEOMETRY_TYPES = {"MESH", "CURVE", "SURFACE", "META", "FONT"}


def export_scene(depsgraph, view_layer):
    builder = _Builder(preview.materials_behind(depsgraph.scene))
    for instance in visibility.rendered_instances(depsgraph, view_layer, builder.warnings, is_bake_output):
        obj = instance.object
        if obj.type == "LIGHT":
            builder.add_light(obj, instance.matrix_world)
        elif (obj.type in GEOMETRY_TYPES and isinstance(obj.data, bpy.types.Mesh)
              and not is_bake_output(obj.original) and not media_materials.is_medium_only(obj)):
            # Cycles renders an object only if its evaluated data is a mesh (blender/object.cpp,
            # object_is_geometry): curves, text, surfaces and metaballs come again as a mesh instance.
            builder.add_geometry(instance)  # a medium-only mesh has no surface in Cycles; media_export reads it
    return builder.finish()


def light_group(obj):
    """The light group an object or lamp names (Blender 3.2 and later), "" for none."""
    return getattr(obj.original, "lightgroup", "")


def is_bake_output(original):
    """Whether an (original) object is one a bake made."""
    return bool(original.get(COPY_TAG) or original.get(MEDIUM_TAG))


class _Builder:
    def __init__(self, materials_behind):
        self.materials_behind = materials_behind  # the real materials under the baked-light preview
        self.positions, self.counts, self.corners = [], [], []
        self.polygon_material = []
        self.material_ids = {}          # material name (None = no material) -> id
        self.surfaces = []              # id -> Surface
        self.lamp_ids = []              # the ids of area lamps, which emit from their front only
        self.parts, self.lights, self.warnings = [], [], []
        self.lamp_problems = {}         # problem -> [lamp name or (name, detail)], said once each
        self.vertex_total = self.polygon_total = self.corner_total = 0
        self.textures = _Textures()
        self.light_groups = {"": 0}     # light group name -> index
        self.polygon_groups = []        # per exported mesh or area lamp: (polygons, its group's index)
        self.lamp_groups = []           # per exported point, spot or sun lamp: its light group

    def material_id(self, material):
        key = material.name if material is not None else None
        if key not in self.material_ids:
            surface = materials.surface_of(material, self.textures.images)
            warning = materials.warning_for(key, surface)
            if warning:
                self.warnings.append(warning)
            self.material_ids[key] = len(self.surfaces)
            self.surfaces.append(surface)
        return self.material_ids[key]

    def add_geometry(self, instance):
        obj = instance.object
        mesh = obj.to_mesh()
        try:
            self._add_mesh(instance, obj, mesh)
        finally:
            obj.to_mesh_clear()

    def _add_mesh(self, instance, obj, mesh):
        if len(mesh.polygons) == 0:
            return
        matrix = np.array(instance.matrix_world, dtype=np.float64)
        co = _read(mesh.vertices, "co", np.float32, 3)
        loop_start = _read(mesh.polygons, "loop_start", np.int32)
        loop_total = _read(mesh.polygons, "loop_total", np.int32)
        loop_vertex = _read(mesh.loops, "vertex_index", np.int32)
        material_index = _read(mesh.polygons, "material_index", np.int32)

        world = co.astype(np.float64) @ matrix[:3, :3].T + matrix[:3, 3]
        order = _corner_order(loop_start, loop_total, mirrored=np.linalg.det(matrix[:3, :3]) < 0.0)

        original = obj.original
        slots = [self.materials_behind.get((original.name, index), slot.material)
                 for index, slot in enumerate(obj.material_slots)]
        slot_ids = np.array([self.material_id(m) for m in slots] or [self.material_id(None)], dtype=np.int32)
        material_index = np.clip(material_index, 0, len(slot_ids) - 1)

        self.parts.append(Part(
            object_name=original.name,
            mesh_name=original.data.name if original.type == "MESH" else "",
            is_instance=instance.is_instance,
            polygon_start=self.polygon_total, polygon_stop=self.polygon_total + len(loop_start),
            corner_start=self.corner_total, corner_stop=self.corner_total + len(loop_vertex),
            corner_order=order,
            polygon_material_index=material_index,
            material_names=[m.name if m is not None else None for m in slots],
            matrix_world=matrix,
            unwritable=_unwritable_reason(instance, original, mesh),
            object_library=original.library.filepath if original.library is not None else "",
        ))
        self.positions.append(world)
        self.counts.append(loop_total)
        self.corners.append(loop_vertex[order] + self.vertex_total)
        self.polygon_material.append(slot_ids[material_index])
        self.textures.add_part(original.name, mesh, order, loop_total, material_index,
                               [self.surfaces[i] for i in slot_ids])
        self._note_light_group(obj, len(loop_start))
        self.vertex_total += len(world)
        self.polygon_total += len(loop_start)
        self.corner_total += len(loop_vertex)

    def add_light(self, obj, matrix_world):
        if obj.data.type == "AREA" and getattr(getattr(obj.data, "cycles", None), "is_portal", False):
            return
        strength, problems = lights.lamp_strength(obj)
        self._note_lamp_problems(problems)
        if not strength.any():
            return  # Cycles leaves out a lamp of strength 0; an area lamp then blocks no light either
        if obj.data.type == "AREA":
            vertices, quads, radiance, problems = lights.area_quads(obj, matrix_world, strength)
            self._note_lamp_problems(problems)
            # Each lamp is its own black emitter (own material id: no blending with neighbours).
            self.surfaces.append(materials.Surface(np.zeros(3), radiance))
            self.lamp_ids.append(len(self.surfaces) - 1)
            self.positions.append(vertices)
            self.counts.append(np.full(len(quads), 4, dtype=np.int32))
            self.corners.append(quads.ravel().astype(np.int32) + self.vertex_total)
            self.polygon_material.append(np.full(len(quads), len(self.surfaces) - 1, dtype=np.int32))
            self.textures.add_plain(len(quads), quads.size)
            self._note_light_group(obj, len(quads))
            self.vertex_total += len(vertices)
            self.polygon_total += len(quads)
            self.corner_total += quads.size
            return
        entry, problems = lights.point_like(obj, matrix_world, strength)
        self._note_lamp_problems(problems)
        self.lights.append(entry)
        self.lamp_groups.append(light_group(obj))

    def _note_light_group(self, obj, polygons):
        group = self.light_groups.setdefault(light_group(obj), len(self.light_groups))
        self.polygon_groups.append(np.full(polygons, group, dtype=np.int32))

    def _note_lamp_problems(self, problems):
        for problem, item in problems:
            self.lamp_problems.setdefault(problem, []).append(item)

    def finish(self):
        # One warning per problem, however many lamps have it (thirty bulbs with a radius: one line).
        self.warnings += [visibility.listing(problem, "lamp", items) for problem, items in self.lamp_problems.items()]
        self.warnings += self.textures.warnings()
        self._mark_shared_meshes()
        counts = np.concatenate(self.counts) if self.counts else np.zeros(0, np.int32)
        material = np.concatenate(self.polygon_material) if self.polygon_material else np.zeros(0, np.int32)
        reflectance = np.array([s.reflectance for s in self.surfaces], dtype=np.float32).reshape(-1, 3)
        emission = np.array([s.emission for s in self.surfaces], dtype=np.float32).reshape(-1, 3)
        return ExportedScene(
            positions=(np.concatenate(self.positions) if self.positions else np.zeros((0, 3))).astype(np.float32),
            face_offsets=np.concatenate([[0], np.cumsum(counts)]).astype(np.int32),
            corner_vertices=(np.concatenate(self.corners) if self.corners else np.zeros(0)).astype(np.int32),
            reflectance=reflectance[material] if len(material) else np.zeros((0, 3), np.float32),
            emission=emission[material] if len(material) else np.zeros((0, 3), np.float32),
            material=material.astype(np.int32),
            front_only=np.isin(material, self.lamp_ids).astype(np.uint8),
            lights=self.lights, parts=self.parts, warnings=self.warnings, textures=self.textures.keyword(),
            light_group_names=list(self.light_groups),
            polygon_light_group=np.concatenate(self.polygon_groups) if self.polygon_groups else np.zeros(0, np.int32),
            lamp_light_groups=self.lamp_groups,
        )

    def _mark_shared_meshes(self):
        """A mesh shown by several objects can hold only one lighting: ORIGINAL writes it only when
        each object is to get a mesh of its own (writeback)."""
        users = {}
        for part in self.parts:
            users.setdefault(part.mesh_name, []).append(part)
        for name, parts in users.items():
            if name and len(parts) > 1:
                for part in parts:
                    part.shares_mesh = True


class _Textures:
    """The faces' textures as the core takes them: the images each once, and per face which texture
    varies its reflectance and emission, with the UVs of its corners."""

    def __init__(self):
        self.images = textures.Images()
        self.index = {}             # (image name, filter, extension) -> texture index
        self.entries = []           # the `images` list of the keyword
        self.uv, self.texture, self.scale = [], {"reflectance": [], "emission": []}, {"reflectance": [], "emission": []}
        self.missing_uv = {}        # problem -> [object names]

    def add_plain(self, polygons, corners):
        """Polygons without textures (lamps)."""
        self.uv.append(np.zeros((corners, 2), np.float32))
        for role in self.texture:
            self.texture[role].append(np.full(polygons, -1, np.int32))
            self.scale[role].append(np.zeros((polygons, 3), np.float32))

    def add_part(self, object_name, mesh, order, loop_total, material_index, slot_surfaces):
        """The textures of one mesh's polygons (`material_index` into `slot_surfaces`)."""
        self.add_plain(len(loop_total), len(order))
        uv = self.uv[-1]
        texture = {role: arrays[-1] for role, arrays in self.texture.items()}
        scale = {role: arrays[-1] for role, arrays in self.scale.items()}
        polygon_of_corner = np.repeat(np.arange(len(loop_total)), loop_total)
        maps = {}
        for slot, surface in enumerate(slot_surfaces):
            uses = {"reflectance": surface.reflectance_texture, "emission": surface.emission_texture}
            uses = {role: use for role, use in uses.items() if use is not None}
            faces = material_index == slot
            if not uses or not faces.any():
                continue
            first = next(iter(uses.values()))
            uv_map = first.uv_map
            for role, use in list(uses.items()):
                if not use.reads_uvs_of(first):  # one UV per corner: the first role's wins
                    self.missing_uv.setdefault("An image texture reads other UVs (another UV map or Mapping) than the "
                                               "material's other texture and counts as its mean colour",
                                               []).append(object_name)
                    del uses[role]
            if uv_map not in maps:
                maps[uv_map] = textures.corner_uvs(mesh, uv_map, order)
            if maps[uv_map] is None:
                which = "UV map" if uv_map == textures.ACTIVE_RENDER else "UV map '%s'" % uv_map
                self.missing_uv.setdefault("Image textures count as their mean colour where the mesh has no %s (Cycles "
                                           "reads the texel at UV 0, 0 there)" % which, []).append(object_name)
                continue
            corners = faces[polygon_of_corner]
            uv[corners] = uv_mapping.apply(first.uv_transform, maps[uv_map][corners])
            for role, use in uses.items():
                texture[role][faces] = self._texture_index(use)
                scale[role][faces] = use.scale

    def _texture_index(self, use):
        filter_name, extension = textures.lookup(use.node)
        key = (use.image.name, filter_name, extension)
        if key not in self.index:
            self.index[key] = len(self.entries)
            self.entries.append({"rgb": use.image.rgb, "srgb": use.image.srgb, "filter": filter_name,
                                 "extension": extension})
        return self.index[key]

    def warnings(self):
        return [visibility.listing(problem, "object", list(dict.fromkeys(names)))
                for problem, names in self.missing_uv.items()]

    def keyword(self):
        if not self.entries:
            return None
        textured = {"images": self.entries, "corner_uv": np.concatenate(self.uv).astype(np.float32)}
        for role in self.texture:
            textured[role + "_texture"] = np.concatenate(self.texture[role]).astype(np.int32)
            textured[role + "_scale"] = np.concatenate(self.scale[role]).astype(np.float32)
        return textured


def _unwritable_reason(instance, original, mesh):
    """Why the light of this part cannot go onto the original object's mesh corners, or ""."""
    if instance.is_instance:
        return "instances"
    if original.type != "MESH":
        return "not meshes"
    if len(original.data.loops) != len(mesh.loops) or len(original.data.polygons) != len(mesh.polygons):
        changing = [m.name for m in original.modifiers if m.show_render]
        return "modifiers change their faces (%s)" % ", ".join(changing) if changing else "modifiers change their faces"
    return ""


def _corner_order(loop_start, loop_total, mirrored):
    """Mesh loop indices in polygon order (Blender does not promise loop_start is sorted),
    each polygon's loops reversed when the transform mirrors."""
    polygon = np.repeat(np.arange(len(loop_start)), loop_total)
    first_flat = np.concatenate([[0], np.cumsum(loop_total)[:-1]])
    offset = np.arange(int(loop_total.sum())) - first_flat[polygon]
    if mirrored:
        offset = loop_total[polygon] - 1 - offset
    return (loop_start[polygon] + offset).astype(np.int64)


def _read(collection, attribute, dtype, width=1):
    values = np.empty(len(collection) * width, dtype=dtype)
    collection.foreach_get(attribute, values)
    return values.reshape(-1, width) if width > 1 else values
