"""A fog box lit by an area lamp, and one lit by a point lamp inside the fog, rendered by Cycles as
built and as baked (lamp off, walls emitting their colour attribute, the baked OpenVDB absorbing by
`density` and emitting `emission`), same camera, 64 x 64. Cycles' own noise is measured between two
seeds of each scene."""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402
import bpy_extras.object_utils  # noqa: E402
import mathutils  # noqa: E402
import numpy as np  # noqa: E402

import harness  # noqa: E402
import media_scenes  # noqa: E402

args = harness.arguments()
addon = harness.install_addon(args.addon_zip)

SIZE = 64
SAMPLES = 256
MAX_RELATIVE_RMS_BEYOND_NOISE = 0.05
ELEMENT_SIZE = 0.0625


def render(seed, samples=SAMPLES):
    # A medium's boundary is a transparent hit for shadow rays: with 0 transparent bounces Cycles
    # stops the lamp's light at the fog's surface and the original fog renders 3 to 4x too dark.
    harness.use_unbiased_cycles(samples, seed, bounces=64, volume_bounces=64, transparent_bounces=64)
    scene = bpy.context.scene
    scene.render.resolution_x = scene.render.resolution_y = SIZE
    scene.render.resolution_percentage = 100
    scene.render.filepath = os.path.join(args.work, "render_%d.exr" % seed)
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.view_settings.view_transform = "Standard"
    assert bpy.ops.render.render(write_still=True) == {"FINISHED"}
    image = bpy.data.images.load(scene.render.filepath, check_existing=False)
    pixels = np.empty(SIZE * SIZE * 4, dtype=np.float32)
    image.pixels.foreach_get(pixels)
    bpy.data.images.remove(image)
    return pixels.reshape(-1, 4)[:, :3].astype(np.float64)


def relative_rms(a, b):
    return float(np.sqrt(np.mean((a - b) ** 2)) / np.mean(0.5 * (a + b)))


def pixels_away_from(location, radius):
    """Which pixels (bottom row first, as Blender stores them) lie farther than `radius` pixels
    from the image of `location`."""
    scene = bpy.context.scene
    bpy.context.view_layer.update()  # the camera's matrix_world from its location and rotation
    x, y, _ = bpy_extras.object_utils.world_to_camera_view(scene, scene.camera, mathutils.Vector(location))
    row, column = np.divmod(np.arange(SIZE * SIZE), SIZE)
    return np.hypot(column + 0.5 - x * SIZE, row + 0.5 - y * SIZE) > radius


def show_baked_scene():
    """Lamp off, the fog mesh hidden, every wall emitting its baked attribute at strength 1."""
    for obj in bpy.data.objects:
        if obj.type == "LIGHT" or obj.name == "Fog":
            obj.hide_render = True
    material = bpy.data.materials.new("Baked")
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.clear()
    attribute = nodes.new("ShaderNodeAttribute")
    attribute.attribute_name = "Radiosity"
    emission = nodes.new("ShaderNodeEmission")
    output = nodes.new("ShaderNodeOutputMaterial")
    material.node_tree.links.new(attribute.outputs["Color"], emission.inputs["Color"])
    material.node_tree.links.new(emission.outputs[0], output.inputs["Surface"])
    room = bpy.data.objects["Room"]
    for slot in room.material_slots:
        slot.material = material


def baked_against_original(name, samples=SAMPLES, seen=slice(None)):
    """Renders the scene as built, bakes it, renders it as baked; asserts their difference beyond
    Cycles' noise over the pixels `seen`."""
    first, second = render(1, samples)[seen], render(2, samples)[seen]
    summary = addon.bake(bpy.context.scene, method="GAUSS_SEIDEL", element_size=ELEMENT_SIZE, hemicube_resolution=64,
                         tolerance=1e-5)
    show_baked_scene()
    third, fourth = render(3, samples)[seen], render(4, samples)[seen]
    original, baked = 0.5 * (first + second), 0.5 * (third + fourth)
    # Each scene's noise from its own two seeds: the baked scene (emitters and an absorbing
    # volume) is far less noisy than the scattering original, so one noise for both would
    # overstate the noise and hide systematic error. Noise and systematic error add in
    # quadrature; the difference of the two means carries half of each scene's variance.
    noise_original = relative_rms(first, second) / np.sqrt(2.0)
    noise_baked = relative_rms(third, fourth) / np.sqrt(2.0)
    expected_noise = np.sqrt(0.5 * noise_original ** 2 + 0.5 * noise_baked ** 2)
    difference = relative_rms(original, baked)
    systematic = float(np.sqrt(max(0.0, difference ** 2 - expected_noise ** 2)))
    print("%s: zones %d, relative RMS baked vs original %.4f, Cycles noise of one render: original %.4f, "
          "baked %.4f (of the difference %.4f), systematic %.4f, mean ratio %.4f"
          % (name, summary["zones"], difference, noise_original, noise_baked, expected_noise, systematic,
             baked.mean() / original.mean()), flush=True)
    assert systematic <= MAX_RELATIVE_RMS_BEYOND_NOISE, (difference, noise_original, noise_baked, systematic)


def test_fog_box_renders_like_the_original():
    media_scenes.fog_box_scene(args.work)
    baked_against_original("fog box")


def test_point_lamp_in_the_fog_renders_like_the_original():
    # A point lamp's light scattered towards the eye grows as 1 / b for a ray passing b from it,
    # finer than the zones (blocks of 0.0625 m, about 2.7 pixels here), so the pixels within 4 of the
    # lamp's image are left out; Cycles' noise in the fog needs 1,024 samples.
    lamp = (0.45, 0.55, 0.6)
    media_scenes.fog_box_scene(args.work, point_lamp_at=lamp)
    baked_against_original("point lamp in the fog", 1024, pixels_away_from(lamp, 4.0))


harness.run(test_fog_box_renders_like_the_original, test_point_lamp_in_the_fog_renders_like_the_original)
