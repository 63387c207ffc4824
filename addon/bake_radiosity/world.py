"""The World's light as the core takes it: an equirectangular map of the radiance arriving from
every direction, in Cycles' convention (direction_to_equirectangular: the map's centre looks
along +X, its left quarter along +Y, its top row up; rows bottom first, as Blender stores images).

A plain Background (colour and strength not driven by nodes, or a World without nodes) is one
radiance from everywhere: no render. Any other node tree (an Environment Texture with an HDRI, a
Sky Texture, gradients, mixes) is rendered once by Cycles with a panoramic equirectangular camera
in a temporary scene that shares the World and holds nothing else, so the scene's objects are
excluded and the scene itself is never touched. The render is read from an OpenEXR file
(linear, as Cycles computed it) with numpy, and the scene, file and data-blocks are removed
again (with the Render Result image when the file had none), on failure too.
"""

import math
import os
import shutil
import tempfile
import time
from dataclasses import dataclass

import bpy
import numpy as np

from .engine.errors import BakeError

# 512 x 256 pixels of 0.7 degrees, 64 samples a pixel: smooth skies to 0.01% (a Sky Texture
# without its sun: the floor under it as Cycles bakes it). A sun disc (Blender's Sky Texture: 0.545
# degrees across) falls into one or two pixels, where 64 samples miss its power by a few percent
# (+2.9% at 30 degrees up): the few pixels that hold SUN_SHARE of the map's power or more are
# rendered again at SUN_SAMPLES a pixel (then -0.2%), when they fit in SUN_REGION pixels a side.
MAP_WIDTH, MAP_HEIGHT = 512, 256
MAP_SAMPLES = 64
SUN_SHARE = 1e-3
SUN_SAMPLES = 4096
SUN_REGION = 32
# The camera rotation (XYZ Euler) at which Cycles' equirectangular camera looks along +X with +Z
# up: its image is then the map of direction_to_equirectangular.
CAMERA_ROTATION = (math.pi / 2, 0.0, -math.pi / 2)


@dataclass
class WorldMap:
    radiance: np.ndarray   # (height, width, 3) float32, bottom row first
    name: str              # the World's name
    rendered: bool         # False for a constant Background
    seconds: float         # time to make the map

    def describe(self):
        if not self.rendered:
            colour = self.radiance[0, 0]
            return "World '%s' (uniform, radiance %.3g %.3g %.3g)" % (self.name, colour[0], colour[1], colour[2])
        return "World '%s' (rendered by Cycles, %d x %d)" % (self.name, self.radiance.shape[1], self.radiance.shape[0])


def uses_nodes(world):
    """Whether Cycles shades `world` by its node tree (Blender 5 has no use_nodes: always)."""
    if world.node_tree is None:
        return False
    return bpy.app.version >= (5, 0, 0) or world.use_nodes


def active_output(tree):
    """The World Output node Cycles uses: the active one for All or Cycles, else None."""
    outputs = [n for n in tree.nodes if n.type == "OUTPUT_WORLD" and getattr(n, "target", "ALL") in ("ALL", "CYCLES")]
    active = [n for n in outputs if n.is_active_output]
    return (active or outputs or [None])[0]


def constant_radiance(world):
    """The World's radiance (3,) when it is the same from every direction, or None when nodes
    vary it (or we cannot tell without rendering it)."""
    if not uses_nodes(world):
        return np.array(world.color[:3], dtype=np.float64)  # Cycles' World without nodes: its colour
    output = active_output(world.node_tree)
    if output is None:
        return np.zeros(3)
    surface = output.inputs["Surface"]
    if not surface.is_linked:
        return np.zeros(3)
    node = surface.links[0].from_node
    if node.type != "BACKGROUND" or node.mute:
        return None
    colour, strength = node.inputs["Color"], node.inputs["Strength"]
    if colour.is_linked or strength.is_linked:
        return None
    return np.array(colour.default_value[:3], dtype=np.float64) * float(strength.default_value)


def diffuse_visible(world):
    """False when the World's Ray Visibility hides it from diffuse rays: then it lights nothing in Cycles."""
    visibility = getattr(world, "cycles_visibility", None)
    return bool(getattr(visibility, "diffuse", True))


def export_world(scene):
    """(WorldMap or None, warnings) for the scene's World; None when it gives no light."""
    world = scene.world
    if world is None:
        return None, []
    if not diffuse_visible(world):
        return None, ["World '%s' is hidden from diffuse rays (Ray Visibility): it lights nothing, as in Cycles"
                      % world.name]
    start = time.perf_counter()
    radiance = constant_radiance(world)
    if radiance is not None:
        if not np.all(np.isfinite(radiance)) or (radiance < 0.0).any():
            raise BakeError("World '%s': its Background colour x strength must be finite and not negative, got %s"
                            % (world.name, ", ".join("%.3g" % c for c in radiance)))
        if not radiance.any():
            return None, []
        world_map = np.array(radiance, dtype=np.float32).reshape(1, 1, 3)
        return WorldMap(world_map, world.name, False, time.perf_counter() - start), []
    world_map = render_map(world)
    world_map = with_sun_rendered_again(world, world_map)
    warnings = []
    if not np.all(np.isfinite(world_map)):
        raise BakeError("World '%s' renders values that are not numbers; check its node tree" % world.name)
    if (world_map < 0.0).any():
        warnings.append("World '%s' renders negative light in places; taken as black there" % world.name)
        world_map = np.maximum(world_map, 0.0)
    if not world_map.any():
        return None, warnings
    return WorldMap(world_map, world.name, True, time.perf_counter() - start), warnings


def pixel_solid_angles(height, width):
    """(height,) solid angle of a pixel in each row: 2 pi / width times its band of cos(theta)."""
    edges = np.cos(np.pi * (1.0 - np.arange(height + 1) / height))
    return 2.0 * np.pi / width * (edges[1:] - edges[:-1])


def with_sun_rendered_again(world, world_map):
    """`world_map` with its brightest few pixels (a sun disc) rendered again at SUN_SAMPLES a pixel."""
    height, width = world_map.shape[:2]
    power = world_map.sum(axis=2) * pixel_solid_angles(height, width)[:, None]
    rows, columns = np.nonzero(power > SUN_SHARE * power.sum())
    if len(rows) == 0:
        return world_map
    # The bright pixels with a margin of 2; the region rendered again has one more pixel around.
    low_row, high_row = max(rows.min() - 2, 0), min(rows.max() + 3, height)
    low_column, high_column = max(columns.min() - 2, 0), min(columns.max() + 3, width)
    if high_row - low_row > SUN_REGION or high_column - low_column > SUN_REGION:
        return world_map  # not one small disc (or across the map's seam): the first render stands
    region = (max(low_column - 1, 0), min(high_column + 1, width), max(low_row - 1, 0), min(high_row + 1, height))
    again = render_map(world, width, height, SUN_SAMPLES, region)
    result = world_map.copy()
    result[low_row:high_row, low_column:high_column] = again[low_row:high_row, low_column:high_column]
    return result


def render_map(world, width=MAP_WIDTH, height=MAP_HEIGHT, samples=MAP_SAMPLES, region=None):
    """The World rendered by Cycles into an equirectangular (height, width, 3) float32 array,
    bottom row first; only the pixels of `region` (first column, end column, first row, end row)
    when given. Everything made for it is removed again, whatever happens."""
    folder = tempfile.mkdtemp(prefix="bake_radiosity_world_")
    scene = camera_data = camera = image = None
    render_results = {i.name for i in bpy.data.images if i.type == "RENDER_RESULT"}
    try:
        scene = bpy.data.scenes.new("Bake Radiosity world map")
        scene.world = world
        camera_data = bpy.data.cameras.new("Bake Radiosity world map")
        camera_data.type = "PANO"
        if hasattr(camera_data, "panorama_type"):  # Blender 4.0 moved it from Cycles' settings to the camera
            camera_data.panorama_type = "EQUIRECTANGULAR"
        else:
            camera_data.cycles.panorama_type = "EQUIRECTANGULAR"
        camera = bpy.data.objects.new("Bake Radiosity world map", camera_data)
        camera.rotation_euler = CAMERA_ROTATION
        scene.collection.objects.link(camera)
        scene.camera = camera
        configure_render(scene, width, height, samples, os.path.join(folder, "world.exr"))
        if region is not None:  # a border in whole pixels (rows from the bottom, as the map's)
            render = scene.render
            render.use_border, render.use_crop_to_border = True, False
            render.border_min_x, render.border_max_x = region[0] / width, region[1] / width
            render.border_min_y, render.border_max_y = region[2] / height, region[3] / height
        try:
            bpy.ops.render.render(write_still=True, scene=scene.name)
        except RuntimeError as error:
            raise BakeError("Could not render World '%s' to bake its light: %s" % (world.name, error)) from error
        path = os.path.join(folder, "world.exr")
        if not os.path.exists(path):
            raise BakeError("Could not render World '%s' to bake its light: Cycles wrote no image" % world.name)
        image = bpy.data.images.load(path, check_existing=False)
        pixels = np.empty(width * height * 4, dtype=np.float32)
        image.pixels.foreach_get(pixels)
        return np.ascontiguousarray(pixels.reshape(height, width, 4)[:, :, :3])
    finally:
        if image is not None:
            bpy.data.images.remove(image)
        if camera is not None:
            bpy.data.objects.remove(camera)
        if camera_data is not None:
            bpy.data.cameras.remove(camera_data)
        if scene is not None:
            bpy.data.scenes.remove(scene)
        for result in [i for i in bpy.data.images if i.type == "RENDER_RESULT" and i.name not in render_results]:
            result.user_clear()  # its user is the render itself, gone now
            bpy.data.images.remove(result)  # the render's own Render Result image, if the file had none
        shutil.rmtree(folder, ignore_errors=True)


def configure_render(scene, width, height, samples, path):
    """Cycles on the CPU, a fixed number of samples a pixel, a box filter one pixel wide (each
    pixel the mean over its own area), no denoising, an opaque film, linear 32-bit OpenEXR."""
    render = scene.render
    render.engine = "CYCLES"
    render.resolution_x, render.resolution_y, render.resolution_percentage = width, height, 100
    render.film_transparent = False
    render.use_compositing = False
    render.use_sequencer = False
    render.filepath = path
    render.image_settings.file_format = "OPEN_EXR"
    render.image_settings.color_depth = "32"
    cycles = scene.cycles
    cycles.device = "CPU"
    cycles.samples = samples
    cycles.use_adaptive_sampling = False
    cycles.use_denoising = False
    cycles.pixel_filter_type = "BOX"
    cycles.filter_width = 1.0
    cycles.film_exposure = 1.0
    cycles.sample_clamp_direct = 0.0
    cycles.sample_clamp_indirect = 0.0
