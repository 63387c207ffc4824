"""The solved light into the file: a FLOAT_COLOR face-corner attribute on the baked meshes
(ORIGINAL) or on new meshes built from the bake's elements (COPIES)."""

import bpy
import numpy as np

from .engine.light_groups import attribute_name as layer_attribute_name
from .export import COPY_TAG

COLLECTION_NAME = "Radiosity Bake"


LIGHT_SUFFIX = " Light"


def light_attribute_name(attribute_name):
    """The attribute that holds the light-only output beside `attribute_name`."""
    return attribute_name + LIGHT_SUFFIX


def write(scene, exported, result, settings, layer_groups=()):
    """Writes `result` as `settings` ask, with the light group layers of `layer_groups` (the groups of
    result["layers"], in order) beside it, and returns warnings about what could not be written."""
    name = settings["attribute_name"]
    outputs = [(name, "corner_radiance", "element_corner_radiance")]
    if settings.get("write_light_only"):
        outputs.append((light_attribute_name(name), "corner_light", "element_corner_light"))
    for k, group in enumerate(layer_groups):
        outputs.append((layer_attribute_name(name, group), ("layers", k, "corner_radiance"),
                        ("layers", k, "element_corner_radiance")))
    if settings["target"] == "ORIGINAL":
        return _write_original(exported, result, outputs, settings["separate_linked_duplicates"])
    return _write_copies(scene, exported, result, outputs)


def _values(result, key):
    """result[key], or for a layer's key ("layers", k, name) result["layers"][k][name]."""
    if isinstance(key, tuple):
        _, k, name = key
        return result["layers"][k][name]
    return result[key]


def set_color_attribute(mesh, name, rgb):
    """Stores (loops,3) linear RGB as the mesh's active and render FLOAT_COLOR corner attribute."""
    attributes = mesh.color_attributes
    existing = attributes.get(name)
    if existing is not None and (existing.domain != "CORNER" or existing.data_type != "FLOAT_COLOR"):
        attributes.remove(existing)
        existing = None
    attribute = existing or attributes.new(name, "FLOAT_COLOR", "CORNER")
    rgba = np.ones((len(rgb), 4), dtype=np.float32)
    rgba[:, :3] = rgb
    attribute.data.foreach_set("color", rgba.ravel())
    attributes.active_color = attribute
    attributes.render_color_index = list(attributes).index(attribute)
    mesh.update()


def _write_original(exported, result, outputs, separate_linked_duplicates):
    """`outputs`: (attribute name, result key of its input corners, of its element corners); the first
    becomes the active and render colour."""
    written, refused, shared, separated = set(), {}, [], []
    for part in exported.parts:
        if part.unwritable:
            refused.setdefault(part.unwritable, []).append(part.object_name)
            continue
        if part.shares_mesh and not separate_linked_duplicates:
            shared.append(part.object_name)
            continue
        obj = bpy.data.objects.get((part.object_name, part.object_library or None))
        if obj is None or obj.type != "MESH" or part.object_name in written:
            continue
        if part.shares_mesh and obj.data.users > 1:
            obj.data = obj.data.copy()  # materials and attributes come along
            separated.append(part.object_name)
        mesh = obj.data
        taken = [name for name, _, _ in outputs if name_taken_by_other_attribute(mesh, name)]
        if taken:
            refused.setdefault("a non-colour attribute is named '%s'" % taken[0], []).append(part.object_name)
            continue
        for name, key, _ in reversed(outputs):  # the first written last: it stays the active colour
            rgb = np.empty((len(mesh.loops), 3), dtype=np.float32)
            rgb[part.corner_order] = _values(result, key)[part.corner_start:part.corner_stop]
            set_color_attribute(mesh, name, rgb)
        written.add(part.object_name)
    warnings = []
    if shared:
        warnings.append("Not written onto %d linked duplicate(s) (%s), objects that share one mesh, which holds one "
                        "lighting. They still light the scene; turn on Separate Linked Duplicates to give each its "
                        "own mesh, or use Target: Subdivided Copies" % (len(set(shared)), _listed(shared)))
    if separated:
        warnings.append("Gave %d linked duplicate(s) a mesh of their own to hold their light (%s)"
                        % (len(separated), _listed(separated)))
    for reason, names in refused.items():
        warnings.append("Not written onto %d object(s) (%s): %s. They still light the scene; Target: Subdivided "
                        "Copies bakes their light" % (len(set(names)), _listed(names), reason))
    return warnings


def _listed(names):
    names = sorted(set(names))
    return ", ".join(names[:5]) + (", ..." if len(names) > 5 else "")


def name_taken_by_other_attribute(mesh, name):
    attribute = mesh.attributes.get(name)
    return attribute is not None and mesh.color_attributes.get(name) is None


def remove_copies():
    """Deletes the objects and meshes a COPIES bake made, and nothing else."""
    for obj in [o for o in bpy.data.objects if o.get(COPY_TAG)]:
        mesh = obj.data
        bpy.data.objects.remove(obj)
        if mesh is not None and mesh.users == 0:
            bpy.data.meshes.remove(mesh)


def _copies_collection(scene):
    collection = bpy.data.collections.get(COLLECTION_NAME)
    if collection is None:
        collection = bpy.data.collections.new(COLLECTION_NAME)
    if collection.name not in scene.collection.children:
        scene.collection.children.link(collection)
    return collection


def _write_copies(scene, exported, result, outputs):
    remove_copies()
    collection = _copies_collection(scene)
    # An emitter's back side (element_back) is solved but not drawn: the copy shows each face's front.
    front = np.flatnonzero(~result["element_back"])
    element_polygon = result["element_polygon"][front]
    by_polygon = front[np.argsort(element_polygon, kind="stable")]
    sorted_polygon = result["element_polygon"][by_polygon]
    for part in exported.parts:
        first, last = np.searchsorted(sorted_polygon, [part.polygon_start, part.polygon_stop])
        elements = by_polygon[first:last]
        if len(elements) == 0:
            continue
        mesh = _element_mesh("%s %s" % (part.object_name, outputs[0][0]), outputs, result, elements, part)
        obj = bpy.data.objects.new(mesh.name, mesh)
        obj[COPY_TAG] = part.object_name
        collection.objects.link(obj)
    return []


def _element_mesh(mesh_name, outputs, result, elements, part):
    corners = result["element_corners"][elements]
    used = corners >= 0
    counts = used.sum(axis=1).astype(np.int32)
    vertex_ids, loop_vertex = np.unique(corners[used], return_inverse=True)

    mesh = bpy.data.meshes.new(mesh_name)
    mesh.vertices.add(len(vertex_ids))
    mesh.vertices.foreach_set("co", result["element_vertices"][vertex_ids].astype(np.float32).ravel())
    mesh.loops.add(len(loop_vertex))
    mesh.loops.foreach_set("vertex_index", loop_vertex.astype(np.int32))
    mesh.polygons.add(len(elements))
    mesh.polygons.foreach_set("loop_start", np.concatenate([[0], np.cumsum(counts)[:-1]]).astype(np.int32))
    if not bpy.types.MeshPolygon.bl_rna.properties["loop_total"].is_readonly:  # Blender < 4.0
        mesh.polygons.foreach_set("loop_total", counts)
    source_polygon = result["element_polygon"][elements] - part.polygon_start
    mesh.polygons.foreach_set("material_index", part.polygon_material_index[source_polygon].astype(np.int32))
    mesh.update(calc_edges=True)
    for material_name in part.material_names:
        mesh.materials.append(bpy.data.materials.get(material_name) if material_name else None)
    for name, _, key in reversed(outputs):  # the first written last: it stays the active colour
        set_color_attribute(mesh, name, _values(result, key)[elements][used])
    return mesh
