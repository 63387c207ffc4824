"""Image textures in the bake, as an artist sets them up: an 8-bit sRGB PNG on a floor's Diffuse
BSDF, read through its UV map.

- The floor's corners show the texture: baked colour / light-only is the texel at each corner's UV,
  computed here from the image's stored bytes as Cycles looks them up (bilinear blend of the
  encoded values, then decoded to linear).
- The bake agrees with Cycles' Combined bake of the same floor within the Medium preset's
  accuracy; the same floor baked with the texture's mean colour (what the bake did before it read
  textures) does not.
- A missing image file is a warning naming the material and the file; the bake goes on with the
  Color input's own value. A mesh without a UV map is a warning naming the object."""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402
import numpy as np  # noqa: E402

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
    scenes.mesh_object("Wall", [scenes.grid((0, 0, 0), (0, ROOM, 0), (0, 0, ROOM), CELLS, CELLS) + (0,)],
                       [scenes.diffuse("Grey Wall", (WALL_ALBEDO,) * 3)])
    lamp = bpy.data.lights.new("Lamp", "POINT")
    lamp.shadow_soft_size = 0.0
    lamp.energy = 200.0
    lamp_object = bpy.data.objects.new("Lamp", lamp)
    lamp_object.location = (1.2, 0.9, 1.3)
    bpy.context.scene.collection.objects.link(lamp_object)
    return floor, image, path


def floor_uv(floor):
    uv = np.empty(len(floor.data.loops) * 2, dtype=np.float32)
    floor.data.uv_layers["UVMap"].data.foreach_get("uv", uv)
    return uv.reshape(-1, 2).astype(np.float64)


def relative_rms(baked, reference):
    return np.sqrt(np.mean((baked - reference) ** 2)) / np.sqrt(np.mean(reference ** 2))


def test_textured_floor_follows_the_texture_and_cycles():
    floor, image, _ = scene("Textured Floor", "Smooth")
    settings = bpy.context.scene.radiosity
    settings.quality = "MEDIUM"
    settings.write_light_only = True
    assert bpy.ops.radiosity.bake() == {"FINISHED"}, settings.last_report
    baked = harness.corner_colors(floor.data, "Radiosity")
    light = harness.corner_colors(floor.data, "Radiosity Light")
    # The image's own bytes, as Blender read them from the PNG.
    stored = np.empty(TEXELS * TEXELS * 4, dtype=np.float32)
    image.pixels.foreach_get(stored)
    texel = texel_at(stored.reshape(TEXELS, TEXELS, 4)[:, :, :3], floor_uv(floor))
    shown = baked / light
    print("floor: texel at the corners %.4f..%.4f, baked / light %.4f..%.4f, max difference %.2e"
          % (texel.min(), texel.max(), shown.min(), shown.max(), np.abs(shown - texel).max()), flush=True)
    np.testing.assert_allclose(shown, texel, rtol=1e-4)

    halves = [harness.cycles_corner_bake(floor, SAMPLES_PER_HALF, seed) for seed in (1, 2)]
    reference = 0.5 * (halves[0] + halves[1])
    noise = relative_rms(halves[0], reference)
    assert noise < MAX_CYCLES_NOISE, "Cycles is too noisy to judge: %.2f%%" % (100 * noise)
    error = relative_rms(baked, reference)

    # Before the bake read textures, the floor was its texture's mean colour everywhere.
    mean = texel_at(stored.reshape(TEXELS, TEXELS, 4)[:, :, :3],
                    np.stack(np.meshgrid((np.arange(TEXELS) + 0.5) / TEXELS, (np.arange(TEXELS) + 0.5) / TEXELS),
                             axis=-1).reshape(-1, 2)).mean(axis=0)
    floor.data.materials[0] = scenes.diffuse("Mean Floor", tuple(mean))
    addon.bake(bpy.context.scene, quality="MEDIUM")
    mean_error = relative_rms(harness.corner_colors(floor.data, "Radiosity"), reference)
    print("floor against Cycles' Combined bake (noise %.2f%%): textured %.2f%% RMS, of the mean colour %.2f%%, "
          "limit %.2f%%" % (100 * noise, 100 * error, 100 * mean_error, 100 * MEDIUM_ACCURACY), flush=True)
    assert error < MEDIUM_ACCURACY
    assert mean_error > MEDIUM_ACCURACY


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


harness.run(test_textured_floor_follows_the_texture_and_cycles, test_missing_image_and_uv_map_are_named)
