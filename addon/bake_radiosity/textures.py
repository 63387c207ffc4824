"""Image textures as the core reads them: each image's texels once per bake (numpy, through
foreach_get), how the Image Texture node looks them up, and which UVs it reads (a UV map, through
Mapping nodes: uv_mapping.py).

Colour: `Image.pixels` gives what the image stores. For an 8-bit sRGB image that is the
sRGB-encoded value, which Cycles blends between texels and then decodes to linear: the core is
told so (`srgb`) and does the same. Float images and 8-bit images in Non-Color or a linear space
are linear already."""

import os
from dataclasses import dataclass

import bpy
import numpy as np

from . import uv_mapping

# Colour spaces whose stored values Cycles reads without conversion.
LINEAR_SPACES = {"Non-Color", "Raw", "Linear", "Linear Rec.709", "Linear CIE-XYZ E", "Linear ACES", "Linear ACEScg"}
ACTIVE_RENDER = ""  # the mesh's active render UV map, as an Image Texture with no vector input reads


@dataclass
class Image:
    """An image's texels (height, width, 3) float32, bottom row first; `mean` is linear."""
    name: str
    rgb: np.ndarray
    srgb: bool
    mean: np.ndarray


class Images:
    """Loads each image once per bake. `load` gives an Image, or a problem naming the image (and
    its file when that is missing)."""

    def __init__(self):
        self._loaded = {}

    def load(self, image):
        if image.name not in self._loaded:
            self._loaded[image.name] = _load(image)
        return self._loaded[image.name]


def _load(image):
    width, height = image.size
    channels = image.channels
    if width * height == 0 or channels < 1:
        if image.source in {"FILE", "SEQUENCE", "MOVIE"} and not image.packed_file:
            path = bpy.path.abspath(image.filepath, library=image.library)
            if not os.path.exists(path):
                return "the file of image '%s' is missing (%s)" % (image.name, image.filepath)
        return "image '%s' has no pixels" % image.name
    pixels = np.empty(width * height * channels, dtype=np.float32)
    image.pixels.foreach_get(pixels)
    pixels = pixels.reshape(height, width, channels)
    rgb = np.ascontiguousarray(pixels[:, :, :3] if channels >= 3 else np.repeat(pixels[:, :, :1], 3, axis=2))
    del pixels
    if not np.isfinite(rgb).all():
        return "image '%s' has pixels that are not numbers" % image.name
    srgb = not image.is_float and image.colorspace_settings.name not in LINEAR_SPACES
    mean = _byte_srgb_mean(rgb) if srgb else rgb.reshape(-1, 3).mean(axis=0, dtype=np.float64)
    return Image(image.name, rgb, srgb, mean)


def _byte_srgb_mean(rgb):
    """The linear mean of an 8-bit sRGB image's texels (k / 255), from how often each byte occurs:
    exact, without a decoded copy of a large image."""
    levels = srgb_to_linear(np.arange(256) / 255.0)
    flat = rgb.reshape(-1, 3)
    counts = [np.bincount(np.rint(flat[:, c] * 255.0).astype(np.uint8), minlength=256) for c in range(3)]
    return np.array([count @ levels for count in counts]) / len(flat)


def srgb_to_linear(values):
    return np.where(values < 0.04045, np.maximum(values, 0.0) / 12.92, ((values + 0.055) / 1.055) ** 2.4)


def lookup(node):
    """(filter, extension) of an Image Texture node, as the core names them: Cubic and Smart are
    looked up as Linear."""
    extension = node.extension.lower() if node.extension in {"REPEAT", "EXTEND", "CLIP", "MIRROR"} else "repeat"
    return ("closest" if node.interpolation == "Closest" else "linear"), extension


def uv_map_of(node, groups, source_of):
    """The UVs an Image Texture node reads: (ACTIVE_RENDER or a UV map's name, the (2, 3) affine
    map of (u, v, 1) that Mapping nodes on the way apply, ""), or (None, None, the reason) when its
    Vector input is driven by something else. `source_of(socket, groups)` follows links through
    reroutes and groups (materials._source)."""
    if node.projection != "FLAT":
        return None, None, "its projection is %s, not Flat" % node.projection.title()
    transform = uv_mapping.IDENTITY
    source, groups = source_of(node.inputs["Vector"], groups)
    while source.is_output and source.node.type == "MAPPING":
        mapping = source.node
        step, why_not = uv_mapping.node_matrix(mapping, lambda socket: _value(source_of(socket, groups)[0]))
        if step is None:
            return None, None, why_not
        transform = transform @ step
        source, groups = source_of(mapping.inputs["Vector"], groups)
        if not source.is_output:  # Cycles maps the socket's constant vector: no UVs at all
            return None, None, "nothing drives the Vector of Mapping '%s'" % mapping.name
    if not source.is_output:
        return ACTIVE_RENDER, uv_mapping.uv_transform(transform), ""
    feeder = source.node
    if feeder.type == "UVMAP":
        return feeder.uv_map or ACTIVE_RENDER, uv_mapping.uv_transform(transform), ""
    if feeder.type == "TEX_COORD" and source.name == "UV":
        return ACTIVE_RENDER, uv_mapping.uv_transform(transform), ""
    return None, None, "its Vector input is driven by '%s' (%s)" % (feeder.name, feeder.bl_label)


def _value(socket):
    """The vector of an input socket nothing drives; None for an output (nodes drive it)."""
    return None if socket.is_output else tuple(socket.default_value)


def corner_uvs(mesh, name, order):
    """The (corners, 2) UVs of the UV map `name` (ACTIVE_RENDER: the active render one) of `mesh`
    in the export's corner order, or None when the mesh has no such map."""
    layers = mesh.uv_layers
    if name == ACTIVE_RENDER:
        layer = next((layer for layer in layers if layer.active_render), None)
    else:
        layer = layers.get(name)
    if layer is None:
        return None
    uv = np.empty(len(mesh.loops) * 2, dtype=np.float32)
    layer.data.foreach_get("uv", uv)
    return uv.reshape(-1, 2)[order]
