"""Export against Blender's own numbers: world-space areas and normals of meshes with modifiers,
a mirrored object and a collection instance; material and lamp conversion."""

import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402
import numpy as np  # noqa: E402
from mathutils import Matrix  # noqa: E402

import harness  # noqa: E402
import scenes  # noqa: E402

args = harness.arguments()
addon = harness.install_addon(args.addon_zip)
export = sys.modules[harness.MODULE + ".export"]
polygons = sys.modules[harness.MODULE + ".engine.polygons"]
pipeline = sys.modules[harness.MODULE + ".pipeline"]


def exported_scene():
    view_layer, depsgraph = pipeline.view_layer_and_depsgraph(bpy.context.scene)
    return export.export_scene(depsgraph, view_layer), depsgraph


def blender_world_polygons(obj, matrix, depsgraph):
    """Areas, unit normals and centres Blender itself computes for the evaluated mesh placed by `matrix`."""
    mesh = bpy.data.meshes.new_from_object(obj.evaluated_get(depsgraph))
    local_normals = np.empty(len(mesh.polygons) * 3)
    mesh.polygons.foreach_get("normal", local_normals)
    mesh.transform(matrix)
    areas = np.empty(len(mesh.polygons))
    mesh.polygons.foreach_get("area", areas)
    centers = np.empty(len(mesh.polygons) * 3)
    mesh.polygons.foreach_get("center", centers)
    bpy.data.meshes.remove(mesh)
    # Normals transform by the inverse transpose, which keeps mirrored objects facing outwards.
    normal_matrix = np.array(matrix.to_3x3().inverted().transposed())
    normals = local_normals.reshape(-1, 3) @ normal_matrix.T
    return areas, normals / np.linalg.norm(normals, axis=1)[:, None], centers.reshape(-1, 3)


def build_geometry_scene():
    scenes.clear_scene()
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=(1, 2, 3), rotation=(0.3, 0.2, 0.1), scale=(1, 2, 0.5))
    modified = bpy.context.active_object
    modified.name = "Modified"
    array = modified.modifiers.new("Array", "ARRAY")
    array.count = 3
    modified.modifiers.new("Bevel", "BEVEL").width = 0.05

    bpy.ops.mesh.primitive_plane_add(size=2.0, location=(-2, 0, 0))
    mirrored = bpy.context.active_object
    mirrored.name = "Mirrored"
    mirrored.scale = (-1.0, 1.5, 1.0)

    # A collection that is not in the scene, shown only through an instancing empty.
    source = bpy.data.collections.new("Source")
    bpy.ops.mesh.primitive_ico_sphere_add(subdivisions=2, radius=0.5)
    instanced = bpy.context.active_object
    instanced.name = "Instanced"
    for collection in list(instanced.users_collection):
        collection.objects.unlink(instanced)
    source.objects.link(instanced)
    instanced.location = (0.2, 0, 0)
    source.instance_offset = (0.1, 0.0, 0.0)
    empty = bpy.data.objects.new("Instancer", None)
    empty.instance_type = "COLLECTION"
    empty.instance_collection = source
    empty.matrix_world = Matrix.LocRotScale((0, -3, 1), Matrix.Rotation(0.7, 3, "Z").to_quaternion(), (2, 2, 2))
    bpy.context.scene.collection.objects.link(empty)
    bpy.context.view_layer.update()
    return modified, mirrored, instanced, empty


def test_geometry_matches_blender():
    modified, mirrored, instanced, empty = build_geometry_scene()
    exported, depsgraph = exported_scene()
    normals, areas = polygons.polygon_normals_areas(exported.positions, exported.face_offsets, exported.corner_vertices)
    counts = np.diff(exported.face_offsets)
    polygon_of_corner = np.repeat(np.arange(len(counts)), counts)
    centers = np.zeros((len(counts), 3))
    np.add.at(centers, polygon_of_corner, exported.positions[exported.corner_vertices])
    centers /= counts[:, None]
    instance_matrix = empty.matrix_world @ Matrix.Translation((-0.1, 0, 0)) @ instanced.matrix_world
    truths = {"Modified": (modified, modified.matrix_world), "Mirrored": (mirrored, mirrored.matrix_world),
              "Instanced": (instanced, instance_matrix)}
    assert sorted(p.object_name for p in exported.parts) == sorted(truths), [p.object_name for p in exported.parts]
    for part in exported.parts:
        obj, matrix = truths[part.object_name]
        true_areas, true_normals, true_centers = blender_world_polygons(obj, matrix, depsgraph)
        rows = slice(part.polygon_start, part.polygon_stop)
        assert len(true_areas) == part.polygon_stop - part.polygon_start
        area_error = np.abs(areas[rows] - true_areas).max()
        normal_error = np.abs(normals[rows] - true_normals).max()
        center_error = np.abs(centers[rows] - true_centers).max()
        print("%s: %d faces, total area %.6f (Blender %.6f), max errors: area %.2e, normal %.2e, centre %.2e"
              % (part.object_name, len(true_areas), areas[rows].sum(), true_areas.sum(), area_error,
                 normal_error, center_error))
        assert area_error < 1e-5 * max(1.0, true_areas.max())
        assert normal_error < 1e-4
        assert center_error < 1e-5
    assert len(modified.evaluated_get(depsgraph).data.polygons) > 3 * 6, "modifiers were not applied"
    writable = {p.object_name: not p.unwritable for p in exported.parts}
    assert writable == {"Modified": False, "Mirrored": True, "Instanced": False}, writable


def test_materials():
    scenes.clear_scene()
    principled = bpy.data.materials.new("Principled")
    principled.use_nodes = True
    node = principled.node_tree.nodes["Principled BSDF"]
    node.inputs["Base Color"].default_value = (0.6, 0.4, 0.2, 1)
    node.inputs["Metallic"].default_value = 0.25
    # Blender 4.0 renamed the Principled BSDF's "Emission" socket "Emission Color".
    emission = node.inputs["Emission Color" if bpy.app.version >= (4, 0, 0) else "Emission"]
    emission.default_value = (1.0, 0.5, 0.25, 1)
    node.inputs["Emission Strength"].default_value = 3.0

    textured = bpy.data.materials.new("Textured")
    textured.use_nodes = True
    image = bpy.data.images.new("Checker", 2, 2)  # 8-bit, sRGB
    image.pixels.foreach_set(np.array([1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 1, 0.5, 0.5, 0.5, 1], dtype=np.float32))
    texture = textured.node_tree.nodes.new("ShaderNodeTexImage")
    texture.image = image
    textured.node_tree.links.new(texture.outputs["Color"],
                                 textured.node_tree.nodes["Principled BSDF"].inputs["Base Color"])

    glossy = bpy.data.materials.new("Glossy")
    glossy.use_nodes = True
    nodes = glossy.node_tree.nodes
    nodes.remove(nodes["Principled BSDF"])
    glossy.node_tree.links.new(nodes.new("ShaderNodeBsdfGlossy").outputs[0], nodes["Material Output"].inputs["Surface"])

    quads = [scenes.grid((0, 0, i), (1, 0, 0), (0, 1, 0), 1, 1) + (i,) for i in range(3)]
    scenes.mesh_object("Plates", quads, [principled, textured, glossy])
    exported, _ = exported_scene()

    # From 4.0 on Cycles takes the Principled's specular layer albedo off its diffuse: at its
    # defaults (IOR 1.5, roughness 0.5) 1 / 1.0388 of Lambert, measured by blender_test_lamps in 5.2.
    layer = 1.0 if bpy.app.version < (4, 0, 0) else 1.0 - 0.04 * 0.934
    np.testing.assert_allclose(exported.reflectance[0], np.array([0.6, 0.4, 0.2]) * 0.75 * layer, rtol=1e-6)
    np.testing.assert_allclose(exported.emission[0], [3.0, 1.5, 0.75], rtol=1e-6)
    # The byte image stores sRGB; the mean is taken of linear values: (1 + 0 + 0 + lin(0.5)) / 4.
    stored_half = np.round(0.5 * 255) / 255
    half = ((stored_half + 0.055) / 1.055) ** 2.4
    np.testing.assert_allclose(exported.reflectance[1], [(1 + half) / 4 * layer] * 3, rtol=1e-4)
    np.testing.assert_allclose(exported.reflectance[2], [0.8, 0.8, 0.8], rtol=1e-6)
    assert any("'Glossy'" in w and "Glossy" in w.split(":", 1)[1] for w in exported.warnings), exported.warnings
    assert not any("'Principled'" in w or "'Textured'" in w for w in exported.warnings), exported.warnings


def test_lamps_in_cycles_units():
    scenes.clear_scene()
    scenes.mesh_object("Floor", [scenes.grid((0, 0, 0), (1, 0, 0), (0, 1, 0), 1, 1) + (0,)])

    def lamp(name, kind, energy, color, matrix, **settings):
        data = bpy.data.lights.new(name, kind)
        data.energy, data.color = energy, color
        for key, value in settings.items():
            setattr(data, key, value)
        obj = bpy.data.objects.new(name, data)
        obj.matrix_world = matrix
        bpy.context.scene.collection.objects.link(obj)

    tilt = Matrix.Rotation(0.5, 4, "X")
    lamp("Point", "POINT", 100.0, (1, 0.5, 0.25), Matrix.Translation((1, 2, 3)), shadow_soft_size=0.05)
    lamp("Spot", "SPOT", 50.0, (1, 1, 1), Matrix.Translation((0, 0, 2)) @ tilt,
         shadow_soft_size=0.0, spot_size=1.0, spot_blend=0.3)
    lamp("Sun", "SUN", 3.0, (1, 1, 0.5), tilt, angle=0.2)
    lamp("Area", "AREA", 20.0, (1, 1, 1), Matrix.Translation((0, 0, 2)) @ tilt @ Matrix.Diagonal((2, 1, 1, 1)),
         shape="RECTANGLE", size=0.5, size_y=0.25)
    exported, _ = exported_scene()
    by_type = {light["type"]: light for light in exported.lights}
    down_tilted = -np.array(tilt.col[2][:3])

    np.testing.assert_allclose(by_type["POINT"]["intensity"], np.array([100, 50, 25]) / (4 * math.pi), rtol=1e-6)
    np.testing.assert_allclose(by_type["POINT"]["position"], (1, 2, 3))
    # Cycles' disk facing the point (3.x; 4.x with Soft Falloff, the default), or a sphere.
    assert abs(by_type["POINT"]["radius"] - 0.05) < 1e-6 and by_type["POINT"]["shape"] == "DISK", by_type["POINT"]
    assert by_type["SPOT"]["radius"] == 0.0, by_type["SPOT"]
    assert abs(by_type["SUN"]["half_angle"] - 0.1) < 1e-6, by_type["SUN"]
    assert by_type["SUN"]["disk_directions"] == (bpy.app.version < (4, 0, 0)), by_type["SUN"]
    np.testing.assert_allclose(by_type["SPOT"]["intensity"], [50 / (4 * math.pi)] * 3, rtol=1e-6)
    np.testing.assert_allclose(by_type["SPOT"]["direction"], down_tilted, atol=1e-6)
    assert abs(by_type["SPOT"]["half_angle"] - 0.5) < 1e-6 and abs(by_type["SPOT"]["blend"] - 0.3) < 1e-6
    np.testing.assert_allclose(by_type["SUN"]["irradiance"], (3, 3, 1.5), rtol=1e-6)
    np.testing.assert_allclose(by_type["SUN"]["direction"], down_tilted, atol=1e-6)

    lamp_polygon = exported.polygon_count - 1
    normals, areas = polygons.polygon_normals_areas(exported.positions, exported.face_offsets, exported.corner_vertices)
    area = (0.5 * 2) * 0.25
    assert abs(areas[lamp_polygon] - area) < 1e-6, areas[lamp_polygon]
    np.testing.assert_allclose(normals[lamp_polygon], down_tilted, atol=1e-6)
    # Cycles' radiance: power / (4 area) in Blender 3.x, power / (pi area) from 4.0 on (lights.py).
    per_area = 4.0 if bpy.app.version < (4, 0, 0) else math.pi
    np.testing.assert_allclose(exported.emission[lamp_polygon], [20 / (per_area * area)] * 3, rtol=1e-6)
    np.testing.assert_allclose(exported.reflectance[lamp_polygon], 0.0)


harness.run(test_geometry_matches_blender, test_materials, test_lamps_in_cycles_units)
