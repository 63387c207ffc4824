"""Image textures in the bake, as an artist sets them up: an 8-bit sRGB PNG on a floor's Diffuse
BSDF, read through its UV map.

- The floor's corners show the texture: baked colour / light-only is the texel at each corner's UV,
  computed here from the image's stored bytes as Cycles looks them up (bilinear blend of the
  encoded values, then decoded to linear).
- The bake agrees with Cycles' Combined bake of the same floor within the Medium preset's
  accuracy; the same floor baked with the texture's mean colour (what the bake did before it read
  textures) does not.
- The hierarchical method reads the texture as the uniform methods do (each element's mean for the
  solve, the texel at each corner it writes): baked colour / light-only is the texel at each
  corner, and the floor agrees with Cycles within the hierarchy's own accuracy against Cycles
  (blender_test_cycles), where the texture's mean colour is far off.
- A bake with fog reads it too: the texel at each corner, and the floor as the same scene's bake
  without the fog has it, within what a thin fog can take from the light.
- A Mapping node between the UVs and the texture (Point, Texture, Vector; fed by a Texture
  Coordinate's UV or a UV Map node) moves the texture as Cycles moves it: the texel at each corner's
  mapped UV (mapped here by Blender's own matrices), and Cycles' bake of the mapped floor. A
  Mapping of type Normal, or one whose Scale nodes drive, is a warning naming the material and the
  node; the texture then counts as its mean colour.
- A missing image file is a warning naming the material and the file; the bake goes on with the
  Color input's own value. A mesh without a UV map is a warning naming the object."""

import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402
import numpy as np  # noqa: E402
from mathutils import Euler, Matrix, Vector  # noqa: E402

import harness  # noqa: E402
import scenes  # noqa: E402

args = harness.arguments()
addon = harness.install_addon(args.addon_zip)

ROOM, CELLS, TEXELS, WALL_ALBEDO = 2.0, 8, 32, 0.5
SAMPLES_PER_HALF = 1024
MAX_CYCLES_NOISE = 0.01
# The Medium preset against Cycles with its final gather: blender_test_cycles' limit for all of the
# Cornell box's corners (relative RMS).
MEDIUM_ACCURACY = 0.01
# The hierarchical method against Cycles: blender_test_cycles' limit for its Cornell box (relative RMS).
HIERARCHY_ACCURACY = 0.035
# A thin fog (Principled Volume density, per metre) in a 0.5 m cube in the floor's light.
FOG_DENSITY = 0.05
# The floor baked with that fog against the same bake without it: at most what the fog takes from a
# ray along the cube's diagonal.
FOG_EFFECT = 1.0 - math.exp(-FOG_DENSITY * 0.5 * math.sqrt(3.0))
# Mapping nodes as an artist sets them: (type, what feeds it, Location, Rotation, Scale).
MAPPINGS = (("POINT", "TEX_COORD", (0.1, 0.3, 0.0), (0.3, 0.0, math.radians(30.0)), (2.0, 1.5, 1.0)),
            ("TEXTURE", "UVMAP", (0.2, -0.1, 0.5), (0.0, 0.2, math.radians(-50.0)), (0.5, 0.8, 2.0)),
            ("VECTOR", "UVMAP", (5.0, 5.0, 5.0), (0.0, 0.0, math.radians(90.0)), (1.0, -2.0, 1.0)))


def stored_texels():
    """(TEXELS, TEXELS, 3) sRGB-encoded values, bottom row first: smooth and periodic in u and v, so
    that Repeat joins the edges without a step, and varying within each floor face."""
    u = (np.arange(TEXELS) + 0.5) / TEXELS
    uu, vv = np.meshgrid(u, u, indexing="xy")  # rows along v
    return np.stack([0.55 + 0.35 * np.sin(2 * np.pi * uu), 0.55 + 0.35 * np.cos(2 * np.pi * vv),
                     0.45 + 0.2 * np.sin(2 * np.pi * (uu + vv))], axis=2).astype(np.float32)


def srgb_to_linear(values):
    return np.where(values < 0.04045, np.maximum(values, 0.0) / 12.92, ((values + 0.055) / 1.055) ** 2.4)


def texel_at(stored, uv):
    """Cycles' Linear lookup with Repeat: the four texel centres around each UV blended, then decoded."""
    height, width, _ = stored.shape
    x, y = uv[:, 0] * width - 0.5, uv[:, 1] * height - 0.5
    x0, y0 = np.floor(x), np.floor(y)
    tx, ty = (x - x0)[:, None], (y - y0)[:, None]
    ix, iy = x0.astype(int) % width, y0.astype(int) % height
    jx, jy = (ix + 1) % width, (iy + 1) % height
    blend = ((1 - ty) * ((1 - tx) * stored[iy, ix] + tx * stored[iy, jx])
             + ty * ((1 - tx) * stored[jy, ix] + tx * stored[jy, jx]))
    return srgb_to_linear(blend.astype(np.float64))


def scene(material_name, png_name):
    """A 2 m floor of 8 x 8 faces with a UV map over the whole texture (a new PNG `png_name`, on the
    floor's material), a grey wall standing on one edge and a point lamp above. Returns (floor,
    image, the PNG's path)."""
    scenes.clear_scene()
    path = scenes.save_png(png_name, stored_texels())
    image = bpy.data.images.load(path)
    floor = scenes.floor_with_uv_map(ROOM, CELLS, scenes.image_texture_material(material_name, image, (0.8, 0.8, 0.8),
                                                                                "Linear"))
    scenes.wall_and_point_lamp(ROOM, CELLS, WALL_ALBEDO)
    return floor, image, path


def floor_uv(floor):
    uv = np.empty(len(floor.data.loops) * 2, dtype=np.float32)
    floor.data.uv_layers["UVMap"].data.foreach_get("uv", uv)
    return uv.reshape(-1, 2).astype(np.float64)


def relative_rms(baked, reference):
    return np.sqrt(np.mean((baked - reference) ** 2)) / np.sqrt(np.mean(reference ** 2))


def cycles_reference(floor):
    """The mean of two Cycles bakes of `floor` with different seeds, and its noise (relative RMS)."""
    halves = [harness.cycles_corner_bake(floor, SAMPLES_PER_HALF, seed) for seed in (1, 2)]
    reference = 0.5 * (halves[0] + halves[1])
    noise = relative_rms(halves[0], reference)
    assert noise < MAX_CYCLES_NOISE, "Cycles is too noisy to judge: %.2f%%" % (100 * noise)
    return reference, noise


def stored_pixels(image):
    """The image's stored RGB (height, width, 3), bottom row first."""
    stored = np.empty(TEXELS * TEXELS * 4, dtype=np.float32)
    image.pixels.foreach_get(stored)
    return stored.reshape(TEXELS, TEXELS, 4)[:, :, :3]


def test_textured_floor_follows_the_texture_and_cycles():
    floor, image, _ = scene("Textured Floor", "Smooth")
    settings = bpy.context.scene.radiosity
    settings.quality = "MEDIUM"
    settings.write_light_only = True
    assert bpy.ops.radiosity.bake() == {"FINISHED"}, settings.last_report
    baked = harness.corner_colors(floor.data, "Radiosity")
    light = harness.corner_colors(floor.data, "Radiosity Light")
    # The image's own bytes, as Blender read them from the PNG.
    stored = stored_pixels(image)
    texel = texel_at(stored, floor_uv(floor))
    shown = baked / light
    print("floor: texel at the corners %.4f..%.4f, baked / light %.4f..%.4f, max difference %.2e"
          % (texel.min(), texel.max(), shown.min(), shown.max(), np.abs(shown - texel).max()), flush=True)
    np.testing.assert_allclose(shown, texel, rtol=1e-4)

    reference, noise = cycles_reference(floor)
    error = relative_rms(baked, reference)

    # Before the bake read textures, the floor was its texture's mean colour everywhere.
    mean = texel_at(stored,
                    np.stack(np.meshgrid((np.arange(TEXELS) + 0.5) / TEXELS, (np.arange(TEXELS) + 0.5) / TEXELS),
                             axis=-1).reshape(-1, 2)).mean(axis=0)
    floor.data.materials[0] = scenes.diffuse("Mean Floor", tuple(mean))
    addon.bake(bpy.context.scene, quality="MEDIUM")
    mean_error = relative_rms(harness.corner_colors(floor.data, "Radiosity"), reference)
    print("floor against Cycles' Combined bake (noise %.2f%%): textured %.2f%% RMS, of the mean colour %.2f%%, "
          "limit %.2f%%" % (100 * noise, 100 * error, 100 * mean_error, 100 * MEDIUM_ACCURACY), flush=True)
    assert error < MEDIUM_ACCURACY
    assert mean_error > MEDIUM_ACCURACY


def test_hierarchical_bake_follows_the_texture_and_cycles():
    floor, image, _ = scene("Hierarchical Floor", "Leaves")
    summary = addon.bake(bpy.context.scene, quality="CUSTOM", method="HIERARCHICAL", element_size=0.0625,
                         refine_tolerance=0.02, tolerance=1e-4, write_light_only=True)
    assert summary["method"] == "hierarchical", summary["method"]
    assert not any("mean colour" in w for w in summary["warnings"]), summary["warnings"]
    baked = harness.corner_colors(floor.data, "Radiosity")
    shown = baked / harness.corner_colors(floor.data, "Radiosity Light")
    texel = texel_at(stored_pixels(image), floor_uv(floor))
    print("hierarchical floor: texel at the corners %.4f..%.4f, baked / light max difference %.2e"
          % (texel.min(), texel.max(), np.abs(shown - texel).max()), flush=True)
    np.testing.assert_allclose(shown, texel, rtol=1e-4)
    reference, noise = cycles_reference(floor)
    error = relative_rms(baked, reference)
    print("hierarchical floor against Cycles' Combined bake (noise %.2f%%): %.2f%% RMS, limit %.2f%%"
          % (100 * noise, 100 * error, 100 * HIERARCHY_ACCURACY), flush=True)
    assert error < HIERARCHY_ACCURACY


def panel_and_fog(with_fog):
    """The textured floor and wall lit by a 50 cm emitting panel 1.5 m up (media are not lit by
    point lamps), and, `with_fog`, a thin fog in a 0.5 m cube in the panel's light."""
    floor, image, _ = scene("Foggy Floor", "Fog")
    bpy.data.objects.remove(bpy.data.objects["Lamp"])
    scenes.mesh_object("Panel", [scenes.grid((0.75, 0.75, 1.5), (0, 0.5, 0), (0.5, 0, 0), 1, 1) + (0,)],
                       [scenes.emission("Panel", (1.0, 1.0, 1.0), 20.0)])
    if with_fog:
        fog = scenes.fog_material("Thin Fog")
        volume = next(n for n in fog.node_tree.nodes if n.bl_idname == "ShaderNodeVolumePrincipled")
        volume.inputs["Density"].default_value = FOG_DENSITY
        sides = [((0, 0, 0), (0, 1, 0), (1, 0, 0)), ((0, 0, 1), (1, 0, 0), (0, 1, 0)),
                 ((0, 0, 0), (1, 0, 0), (0, 0, 1)), ((0, 1, 0), (0, 0, 1), (1, 0, 0)),
                 ((0, 0, 0), (0, 0, 1), (0, 1, 0)), ((1, 0, 0), (0, 1, 0), (0, 0, 1))]
        scenes.mesh_object("Fog", [scenes.grid(np.array((1.3, 1.3, 0.5)) + 0.5 * np.array(o), 0.5 * np.array(u),
                                               0.5 * np.array(v), 1, 1) + (0,) for o, u, v in sides], [fog])
        bpy.context.scene.radiosity.zone_size = 0.25
        bpy.context.scene.radiosity.media_folder = args.work + "/"
    return floor, image


def test_fog_bake_follows_the_texture():
    settings = dict(quality="CUSTOM", method="GAUSS_SEIDEL", element_size=0.125, hemicube_resolution=128,
                    tolerance=1e-6, final_gather=False)
    floor, _ = panel_and_fog(with_fog=False)
    addon.bake(bpy.context.scene, **settings)
    clear = harness.corner_colors(floor.data, "Radiosity")
    floor, image = panel_and_fog(with_fog=True)
    summary = addon.bake(bpy.context.scene, write_light_only=True, **settings)
    assert summary["media_files"], summary
    assert not any("mean colour" in w for w in summary["warnings"]), summary["warnings"]
    baked = harness.corner_colors(floor.data, "Radiosity")
    shown = baked / harness.corner_colors(floor.data, "Radiosity Light")
    texel = texel_at(stored_pixels(image), floor_uv(floor))
    effect = relative_rms(baked, clear)
    print("floor with fog: baked / light max difference from the texel %.2e; against the bake without the fog "
          "%.3f%% RMS, limit %.2f%%" % (np.abs(shown - texel).max(), 100 * effect, 100 * FOG_EFFECT), flush=True)
    np.testing.assert_allclose(shown, texel, rtol=1e-4)
    assert 0.0 < effect < FOG_EFFECT


def add_mapping(material, vector_type, feeder, location, rotation, scale):
    """Texture Coordinate UV (feeder "TEX_COORD") or a UV Map node ("UVMAP") -> a Mapping node ->
    the Vector of `material`'s Image Texture; returns the Mapping node."""
    nodes, links = material.node_tree.nodes, material.node_tree.links
    texture = next(n for n in nodes if n.type == "TEX_IMAGE")
    mapping = nodes.new("ShaderNodeMapping")
    mapping.vector_type = vector_type
    # By identifier: Blender 5.2 does not find a socket the type hides (Vector and Normal have no
    # Location) by its name.
    sockets = {socket.identifier: socket for socket in mapping.inputs}
    for name, value in (("Location", location), ("Rotation", rotation), ("Scale", scale)):
        sockets[name].default_value = value
    if feeder == "UVMAP":
        coordinates = nodes.new("ShaderNodeUVMap")
        coordinates.uv_map = "UVMap"
    else:
        coordinates = nodes.new("ShaderNodeTexCoord")
    links.new(coordinates.outputs["UV"], mapping.inputs["Vector"])
    links.new(mapping.outputs["Vector"], texture.inputs["Vector"])
    return mapping


def mapped_uv(uv, vector_type, location, rotation, scale):
    """(x, y) of each (u, v, 0) through a Mapping node, by Blender's own matrices: Point is
    T R S, Texture its inverse, Vector R S."""
    point = Matrix.LocRotScale(Vector(location), Euler(rotation), Vector(scale))
    matrix = {"POINT": point, "TEXTURE": point.inverted(),
              "VECTOR": Matrix.LocRotScale(None, Euler(rotation), Vector(scale))}[vector_type]
    return np.array([(matrix @ Vector((u, v, 0.0)))[:2] for u, v in uv])


def test_mapping_node_moves_the_texture_as_cycles_does():
    for vector_type, feeder, location, rotation, scale in MAPPINGS:
        floor, image, _ = scene("Mapped Floor", "Mapped")
        add_mapping(floor.data.materials[0], vector_type, feeder, location, rotation, scale)
        settings = bpy.context.scene.radiosity
        settings.quality = "MEDIUM"
        settings.write_light_only = True
        assert bpy.ops.radiosity.bake() == {"FINISHED"}, settings.last_report
        baked = harness.corner_colors(floor.data, "Radiosity")
        shown = baked / harness.corner_colors(floor.data, "Radiosity Light")
        stored = stored_pixels(image)
        texel = texel_at(stored, mapped_uv(floor_uv(floor), vector_type, location, rotation, scale))
        print("Mapping %s from %s: texel at the mapped corners %.4f..%.4f, max difference %.2e"
              % (vector_type, feeder, texel.min(), texel.max(), np.abs(shown - texel).max()), flush=True)
        np.testing.assert_allclose(shown, texel, rtol=1e-4)
        if vector_type != "POINT":
            continue
        reference, noise = cycles_reference(floor)
        error = relative_rms(baked, reference)
        # The same texture read at the unmapped UVs, as if the Mapping node were not there.
        unmapped = relative_rms(baked / texel * texel_at(stored, floor_uv(floor)), reference)
        print("mapped floor against Cycles' Combined bake (noise %.2f%%): %.2f%% RMS, read unmapped %.2f%%, limit "
              "%.2f%%" % (100 * noise, 100 * error, 100 * unmapped, 100 * MEDIUM_ACCURACY), flush=True)
        assert error < MEDIUM_ACCURACY
        assert unmapped > MEDIUM_ACCURACY


def test_unsupported_mapping_is_named():
    floor, image, _ = scene("Normal Mapped", "Normal")
    material = floor.data.materials[0]
    mapping = add_mapping(material, "NORMAL", "TEX_COORD", (0, 0, 0), (0, 0, 0), (1, 1, 1))
    mapping.name = "Bent Normals"
    summary = addon.bake(bpy.context.scene, quality="DRAFT", write_light_only=True)
    assert any("'Normal Mapped'" in w and "'Bent Normals'" in w for w in summary["warnings"]), summary["warnings"]
    shown = harness.corner_colors(floor.data, "Radiosity") / harness.corner_colors(floor.data, "Radiosity Light")
    texel_centres = (np.arange(TEXELS) + 0.5) / TEXELS
    mean = texel_at(stored_pixels(image), np.stack(np.meshgrid(texel_centres, texel_centres), axis=-1).reshape(-1, 2))
    np.testing.assert_allclose(shown, np.broadcast_to(mean.mean(axis=0), shown.shape), rtol=1e-4)

    mapping.vector_type = "POINT"
    value = material.node_tree.nodes.new("ShaderNodeValue")
    material.node_tree.links.new(value.outputs["Value"], mapping.inputs["Scale"])
    summary = addon.bake(bpy.context.scene, quality="DRAFT")
    assert any("'Normal Mapped'" in w and "'Bent Normals'" in w and "Scale" in w for w in summary["warnings"]), \
        summary["warnings"]


def test_missing_image_and_uv_map_are_named():
    floor, image, path = scene("Tiles", "Gone")
    os.remove(path)
    image.reload()
    assert tuple(image.size) == (0, 0)
    summary = addon.bake(bpy.context.scene, quality="DRAFT", write_light_only=True)
    named = [w for w in summary["warnings"] if "'Tiles'" in w and path in w]
    assert named, summary["warnings"]
    # The Color input's own value, 0.8 (scenes.diffuse): the floor reflects 0.8 of its light.
    ratio = harness.corner_colors(floor.data, "Radiosity") / harness.corner_colors(floor.data, "Radiosity Light")
    np.testing.assert_allclose(ratio, 0.8, rtol=1e-5)
    assert bpy.ops.radiosity.bake() == {"FINISHED"}  # the operator too bakes on

    floor, _, _ = scene("Unmapped", "Kept")
    floor.data.uv_layers.remove(floor.data.uv_layers["UVMap"])
    summary = addon.bake(bpy.context.scene, quality="DRAFT")
    assert any("UV map" in w and "'Floor'" in w for w in summary["warnings"]), summary["warnings"]


harness.run(test_textured_floor_follows_the_texture_and_cycles, test_hierarchical_bake_follows_the_texture_and_cycles,
            test_fog_bake_follows_the_texture, test_mapping_node_moves_the_texture_as_cycles_does,
            test_unsupported_mapping_is_named, test_missing_image_and_uv_map_are_named)
