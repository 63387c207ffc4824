"""A 2 m room lit through a window, by the World or by lamps, and its comparison with Cycles
(test_world.py, test_world_hdri.py).

The room's six walls face inwards, CELLS x CELLS quads each; the x = ROOM wall has a 0.8 m
window. Seen from inside, a uniform World of radiance W through the window is the same light as
a square area lamp of radiance W filling the window (light that would leave through the window
is lost either way): the lamp's room is the World's room lit by a lamp."""

import math
import os
import tempfile

import bpy
import numpy as np
from mathutils import Vector

import harness
import scenes

ROOM = 2.0
CELLS = 10
# Window in the x = ROOM wall, in cells of its grid: z cells 4..7 (0.8 to 1.6 m), y cells 3..6.
WINDOW_Z, WINDOW_Y = range(4, 8), range(3, 7)
WINDOW_CENTRE, WINDOW_SIZE = (ROOM, 1.0, 1.2), 0.8
ALBEDO = (0.5, 0.5, 0.5)
SKY_RADIANCE = (0.6, 0.8, 1.0)  # the uniform World
# The HDRI: a sky above the horizon, a ground below, a sun disc shining through the window onto the floor.
SUN_DIRECTION = Vector((0.8, 0.0, 1.2)).normalized()  # towards the sun
SUN_RADIUS = math.radians(4.0)
SUN_RADIANCE = 200.0
SKY = (0.25, 0.35, 0.5)
GROUND = (0.05, 0.05, 0.05)
SAMPLES_PER_HALF = 1024
# Cycles samples a World through a small window far less well than a lamp (4% per corner at 1024
# samples a half, against 0.6% for the same light from an area lamp): its noise, measured from
# two seeds over about 2,300 corners, is taken out of the World's error in quadrature.
MAX_CYCLES_NOISE = 0.05


def room():
    """Six inward-facing walls of CELLS x CELLS quads; the x = ROOM wall has a window."""
    r = ROOM
    walls = [((0, 0, 0), (r, 0, 0), (0, r, 0)),    # floor, +z
             ((0, 0, r), (0, r, 0), (r, 0, 0)),    # ceiling, -z
             ((0, 0, 0), (0, r, 0), (0, 0, r)),    # x = 0, +x
             ((0, 0, 0), (0, 0, r), (r, 0, 0)),    # y = 0, +y
             ((0, r, 0), (r, 0, 0), (0, 0, r))]    # y = r, -y
    pieces = [(*scenes.grid(o, u, v, CELLS, CELLS), 0) for o, u, v in walls]
    vertices, quads = scenes.grid((r, 0, 0), (0, 0, r), (0, r, 0), CELLS, CELLS)  # x = r, -x; i along z, j along y
    i, j = np.divmod(np.arange(len(quads)), CELLS)
    window = np.isin(i, WINDOW_Z) & np.isin(j, WINDOW_Y)
    pieces.append((vertices, quads[~window], 0))
    return scenes.mesh_object("Room", pieces, [scenes.diffuse("Wall", ALBEDO)])


def world_nodes():
    """The scene's World with a fresh node tree: a Background into the World Output."""
    world = bpy.context.scene.world or bpy.data.worlds.new("World")
    bpy.context.scene.world = world
    if bpy.app.version < (5, 0, 0):
        world.use_nodes = True
    nodes = world.node_tree.nodes
    nodes.clear()
    background = nodes.new("ShaderNodeBackground")
    output = nodes.new("ShaderNodeOutputWorld")
    world.node_tree.links.new(background.outputs["Background"], output.inputs["Surface"])
    return world, background


def uniform_world(colour, strength=1.0):
    world, background = world_nodes()
    background.inputs["Color"].default_value = (*colour, 1.0)
    background.inputs["Strength"].default_value = strength
    return world


def black_world():
    """No World light (as scenes.clear_scene leaves it, made explicit for a scene that had one)."""
    return uniform_world((0.0, 0.0, 0.0), 0.0)


def sky_image(folder, width=256, height=128):
    """An equirectangular sky (rows bottom first, Cycles' convention) with a bright sun disc,
    saved as OpenEXR and loaded back as an Environment Texture reads it; and the solid angle of
    the sun's pixels."""
    u = (np.arange(width) + 0.5) / width
    v = (np.arange(height) + 0.5) / height
    phi = math.pi - 2 * math.pi * u[None, :]
    theta = math.pi * (1 - v[:, None])
    direction = np.stack([np.sin(theta) * np.cos(phi), np.sin(theta) * np.sin(phi),
                          np.cos(theta) * np.ones_like(phi)], axis=-1)
    pixels = np.where((direction[..., 2] > 0)[..., None], np.array(SKY), np.array(GROUND))
    sun = np.arccos(np.clip(direction @ np.array(SUN_DIRECTION), -1, 1)) < SUN_RADIUS
    pixels[sun] = SUN_RADIANCE
    image = bpy.data.images.new("Sky", width, height, float_buffer=True)
    image.colorspace_settings.is_data = True  # saved as the numbers set, not converted for display
    rgba = np.concatenate([pixels, np.ones((height, width, 1))], axis=-1).astype(np.float32)
    image.pixels.foreach_set(rgba.ravel())
    path = os.path.join(tempfile.mkdtemp(dir=folder), "sky.exr")
    image.filepath_raw = path
    image.file_format = "OPEN_EXR"
    image.save()
    bpy.data.images.remove(image)
    # Each pixel's solid angle: 2 pi / width times the band of cos(theta) its row spans.
    edges = np.cos(math.pi * (1 - np.arange(height + 1) / height))
    pixel_solid_angle = 2 * math.pi / width * (edges[1:] - edges[:-1])
    return bpy.data.images.load(path), float((sun * pixel_solid_angle[:, None]).sum())


def hdri_world(folder):
    """A World whose Background colour is an Environment Texture of sky_image(); and the solid
    angle of its sun."""
    world, background = world_nodes()
    texture = world.node_tree.nodes.new("ShaderNodeTexEnvironment")
    texture.image, sun_solid_angle = sky_image(folder)
    world.node_tree.links.new(texture.outputs["Color"], background.inputs["Color"])
    return world, sun_solid_angle


def add_lamp(name, lamp, location, towards):
    """Links `lamp` as an object at `location` with its +Z axis along `towards`: its light (along
    the lamp's -Z) travels along -`towards`."""
    obj = bpy.data.objects.new(name, lamp)
    obj.location = location
    obj.rotation_euler = Vector(towards).to_track_quat("Z", "Y").to_euler()
    bpy.context.scene.collection.objects.link(obj)
    return obj


def window_lamp(radiance):
    """A square area lamp filling the window, facing into the room with radiance `radiance`:
    Cycles' radiance is power / (4 A) in Blender 3.x and power / (pi A) from 4.0 (lights.py)."""
    lamp = bpy.data.lights.new("Window", "AREA")
    lamp.shape = "SQUARE"
    lamp.size = WINDOW_SIZE
    peak = max(radiance)
    lamp.color = tuple(c / peak for c in radiance)
    area = WINDOW_SIZE ** 2
    lamp.energy = peak * area * (4.0 if bpy.app.version < (4, 0, 0) else math.pi)
    return add_lamp("Window", lamp, WINDOW_CENTRE, (1.0, 0.0, 0.0))


def sun_lamp():
    """A sun lamp along SUN_DIRECTION with the irradiance the HDRI's sun disc gives."""
    lamp = bpy.data.lights.new("Sun", "SUN")
    lamp.energy = SUN_RADIANCE * math.pi * math.sin(SUN_RADIUS) ** 2
    lamp.angle = 0.0
    return add_lamp("Sun", lamp, (0.0, 0.0, 0.0), SUN_DIRECTION)


def cycles_reference(obj):
    """(reference, noise) of `obj`'s corners: the mean of two Cycles bakes with different seeds,
    and their difference's RMS / 2 relative to the reference's RMS."""
    attributes = obj.data.color_attributes
    for seed in (1, 2):  # a room baked before, under other light
        if "Cycles %d" % seed in attributes:
            attributes.remove(attributes["Cycles %d" % seed])
    halves = [harness.cycles_corner_bake(obj, SAMPLES_PER_HALF, seed) for seed in (1, 2)]
    reference = 0.5 * (halves[0] + halves[1])
    scale = np.sqrt(np.mean(reference ** 2))
    noise = np.sqrt(np.mean((halves[0] - halves[1]) ** 2)) / 2 / scale
    assert noise < MAX_CYCLES_NOISE, "Cycles is too noisy to judge: %.2f%%" % (100 * noise)
    return reference, noise


def errors(name, obj, reference, noise):
    """(relative RMS with Cycles' noise taken out, mean error) of the add-on's 'Radiosity' colours."""
    baked = harness.corner_colors(obj.data, "Radiosity")
    scale = np.sqrt(np.mean(reference ** 2))
    rms = math.sqrt(max(np.mean((baked - reference) ** 2) / scale ** 2 - noise ** 2, 0.0))
    mean_error = baked.mean() / reference.mean() - 1
    print("%s: %d corners, Cycles noise %.2f%%, relative RMS %.2f%% (Cycles' noise taken out), mean %+.2f%% "
          "(radiosity %.5f, Cycles %.5f); %s" % (
              name, len(baked), 100 * noise, 100 * rms, 100 * mean_error, baked.mean(), reference.mean(),
              bpy.context.scene.radiosity.last_report), flush=True)
    return rms, mean_error
