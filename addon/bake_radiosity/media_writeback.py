"""The solved media into the file: per medium an OpenVDB file with grids `density` (extinction
K_t) and `emission` (K_t J), loaded as a Volume object in the "Radiosity Bake" collection with a
purely absorbing, emitting material, so Cycles renders the zonal method's ray integral
(Rushmeier & Torrance 1987; bake/media_bake.h).
The grids come from the core finer than the zones (`_core.bake`'s grid_subdivision, 3 cells
per zone edge by default), J interpolated between zones (zonal_grids.h), with their own origin
and voxel size."""

import os
import re
import tempfile

import bpy
import numpy as np

from .engine import native
from .media_export import MEDIUM_TAG
from .writeback import _copies_collection

MATERIAL_NAME = "Radiosity Medium"
FILE_SUFFIX = ".radiosity.vdb"


def output_folder(folder_setting):
    """The chosen folder ('//' = beside the .blend); a temporary folder for an unsaved file."""
    if folder_setting.startswith("//") and not bpy.data.filepath:
        return os.path.join(tempfile.gettempdir(), "bake_radiosity")
    return bpy.path.abspath(folder_setting or "//")


def unwritable_reason(folder_setting):
    """Why the baked grids could not be written to the chosen folder, or None if they can: asked
    before the solve, so a bake never fails after minutes of work on where its files go."""
    folder = output_folder(folder_setting)
    try:
        os.makedirs(folder, exist_ok=True)
        with tempfile.TemporaryFile(dir=folder):
            pass
    except OSError as error:
        return "Media Folder '%s' is not writable (%s): choose another folder" % (folder, error.strerror or error)
    return None


def write_files(exported_media, result, folder_setting):
    """Writes one OpenVDB file per medium and returns their paths; touches no Blender data and no
    file a Volume shows, so a failure here leaves the file as it was."""
    folder = output_folder(folder_setting)
    os.makedirs(folder, exist_ok=True)
    taken = set(exported_media.input_files) | _shown_files()
    paths = []
    for medium, grids in zip(exported_media.media, result["grids"]):
        path = _output_path(folder, medium.object_name, taken)
        taken.add(os.path.realpath(path))
        native.core().write_vdb(path, grids["origin"], grids["voxel_size"], _file_grids(grids))
        paths.append(path)
    return paths


def load(scene, exported_media, paths):
    """Replaces the previous bake's Volume objects with ones showing the files `write_files` wrote."""
    remove_media()
    collection = _copies_collection(scene)
    material = _medium_material()
    for medium, path in zip(exported_media.media, paths):
        volume = bpy.data.volumes.new("%s Radiosity" % medium.object_name)
        volume.filepath = path
        volume.materials.append(material)
        obj = bpy.data.objects.new(volume.name, volume)
        obj[MEDIUM_TAG] = medium.object_name
        collection.objects.link(obj)


def remove_media():
    """Deletes the Volume objects (and their data) a bake made, and nothing else. Files stay."""
    for obj in [o for o in bpy.data.objects if o.get(MEDIUM_TAG)]:
        volume = obj.data
        bpy.data.objects.remove(obj)
        if volume is not None and volume.users == 0:
            bpy.data.volumes.remove(volume)


def _shown_files():
    """The files the Volume data of this Blender file show (the last bake's among them)."""
    return {os.path.realpath(bpy.path.abspath(volume.filepath)) for volume in bpy.data.volumes if volume.filepath}


def _output_path(folder, object_name, protected):
    """<object>.radiosity.vdb in `folder`, numbered on while that is in `protected`: the user's input
    files, and the files a Volume shows. Blender 4.x keeps the grids it loaded by their file's path,
    so a bake written over the file the last bake's Volume showed rendered the last bake's grids."""
    stem = re.sub(r"[^\w.-]+", "_", object_name)
    path, number = os.path.join(folder, stem + FILE_SUFFIX), 1
    while os.path.realpath(path) in protected:
        path, number = os.path.join(folder, "%s.%d%s" % (stem, number, FILE_SUFFIX)), number + 1
    return path


def _file_grids(grids):
    """`density` and `emission` as float grids when every channel of both agrees, else both RGB.

    Never one of each: Cycles samples a vector grid as if its edge voxels reached half a voxel
    further out, where a float grid falls to 0, so RGB emission over a float density outlived
    the medium's edge by a voxel (a fog 8 voxels across rendered 12.5% too bright)."""
    if _is_grey(grids["density"]) and _is_grey(grids["emission"]):
        return {name: np.ascontiguousarray(grids[name][..., 0]) for name in ("density", "emission")}
    return {"density": grids["density"], "emission": grids["emission"]}


def _is_grey(rgb):
    return np.array_equal(rgb[..., 0], rgb[..., 1]) and np.array_equal(rgb[..., 0], rgb[..., 2])


def _medium_material():
    """Volume Absorption of colour 1 - density (absorbs K_t per channel) + Emission of the
    `emission` grid at strength 1: radiance per metre K_t L, attenuated as the original medium."""
    material = bpy.data.materials.get(MATERIAL_NAME)
    if material is not None:
        return material
    material = bpy.data.materials.new(MATERIAL_NAME)
    if bpy.app.version < (5, 0, 0):  # 5.0 deprecated use_nodes: materials always use nodes
        material.use_nodes = True
    nodes, links = material.node_tree.nodes, material.node_tree.links
    nodes.clear()
    output = nodes.new("ShaderNodeOutputMaterial")
    density = nodes.new("ShaderNodeAttribute")
    density.attribute_name = "density"
    one_minus = nodes.new("ShaderNodeVectorMath")
    one_minus.operation = "SUBTRACT"
    one_minus.inputs[0].default_value = (1.0, 1.0, 1.0)
    absorption = nodes.new("ShaderNodeVolumeAbsorption")
    absorption.inputs["Density"].default_value = 1.0
    emitted = nodes.new("ShaderNodeAttribute")
    emitted.attribute_name = "emission"
    emission = nodes.new("ShaderNodeEmission")
    emission.inputs["Strength"].default_value = 1.0
    add = nodes.new("ShaderNodeAddShader")
    links.new(density.outputs["Vector"], one_minus.inputs[1])
    links.new(one_minus.outputs["Vector"], absorption.inputs["Color"])
    links.new(emitted.outputs["Color"], emission.inputs["Color"])
    links.new(absorption.outputs[0], add.inputs[0])
    links.new(emission.outputs[0], add.inputs[1])
    links.new(add.outputs[0], output.inputs["Volume"])
    return material
