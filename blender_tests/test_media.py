"""Fog, smoke and fire through the artist's path (scene.radiosity settings, bake_radiosity.bake):
the export of a mesh medium and of a Volume object against Cycles' Principled Volume formula,
Kirchhoff's isothermal enclosure, a scattering medium inside black emitting walls, the energy
balance, and the baked Volume object with its OpenVDB file."""

import importlib
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402
import numpy as np  # noqa: E402

import harness  # noqa: E402
import scenes  # noqa: E402

args = harness.arguments()
addon = harness.install_addon(args.addon_zip)
media_export = importlib.import_module(harness.MODULE + ".media_export")
native = importlib.import_module(harness.MODULE + ".engine.native")

core = native.core()
ZONE = 0.25


def principled(name, color, density, absorption=(0.0, 0.0, 0.0), strength=0.0, emission=(1.0, 1.0, 1.0)):
    """A volume-only material: Principled Volume into the Volume socket, no surface."""
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.clear()
    node = nodes.new("ShaderNodeVolumePrincipled")
    node.inputs["Color"].default_value = (*color, 1.0)
    node.inputs["Density"].default_value = density
    node.inputs["Absorption Color"].default_value = (*absorption, 1.0)
    node.inputs["Emission Strength"].default_value = strength
    node.inputs["Emission Color"].default_value = (*emission, 1.0)
    output = nodes.new("ShaderNodeOutputMaterial")
    material.node_tree.links.new(node.outputs[0], output.inputs["Volume"])
    return material


def fog_cube(material, lo=(0.0, 0.0, 0.0), size=1.0):
    """A closed cube (outward normals) filled by `material`'s medium."""
    sides = [((0, 0, 0), (0, 1, 0), (1, 0, 0)), ((0, 0, 1), (1, 0, 0), (0, 1, 0)),
             ((0, 0, 0), (1, 0, 0), (0, 0, 1)), ((0, 1, 0), (0, 0, 1), (1, 0, 0)),
             ((0, 0, 0), (0, 0, 1), (0, 1, 0)), ((1, 0, 0), (0, 1, 0), (0, 0, 1))]
    pieces = [scenes.grid(np.array(lo) + size * np.array(o), size * np.array(u), size * np.array(v), 1, 1) + (0,)
              for o, u, v in sides]
    return scenes.mesh_object("Fog", pieces, [material])


def expected_extinction(color, density, absorption):
    """Cycles' svm_node_principled_volume, written out here independently of the core."""
    color, absorption = np.array(color), np.array(absorption)
    return density * (color + (1.0 - color) * (1.0 - np.sqrt(absorption)))


def exported_media():
    scene = bpy.context.scene
    return media_export.export_media(bpy.context.evaluated_depsgraph_get(), bpy.context.view_layer,
                                     scene.radiosity.zone_size)


def baked_ratio(summary):
    """Zone radiance L = emission / density of the baked VDB (read back from the file onto the
    zones' lattice: the fine cells' box average, which keeps each zone's power), (n, channels)."""
    (path,) = summary["media_files"]
    density = core.read_vdb_grid(path, "density", np.eye(4), ZONE)
    emission = core.read_vdb_grid(path, "emission", np.eye(4), ZONE)
    d = density["values"] if density["values"].ndim == 4 else density["values"][..., None]
    e = emission["values"] if emission["values"].ndim == 4 else emission["values"][..., None]
    inside = d[..., 0] > 0.5 * d[..., 0].max()
    return e[inside] / d[inside]


def test_mesh_medium_export():
    scenes.clear_scene()
    color, density, absorption = (0.8, 0.5, 0.2), 2.0, (0.25, 0.5, 0.0)
    fog_cube(principled("Smoke", color, density, absorption))
    bpy.context.scene.radiosity.zone_size = ZONE
    exported = exported_media()
    (medium,) = exported.media
    K = medium.grid["extinction"]
    assert np.count_nonzero(K.max(axis=-1)) == 64, np.count_nonzero(K.max(axis=-1))  # 4^3 cells of 0.25
    np.testing.assert_allclose(K[K.max(axis=-1) > 0], np.tile(expected_extinction(color, density, absorption), (64, 1)),
                               rtol=1e-5)
    np.testing.assert_allclose(medium.grid["albedo"][K.max(axis=-1) > 0],
                               np.tile(np.array(color) * density / expected_extinction(color, density, absorption),
                                       (64, 1)), rtol=1e-5)


def test_volume_object_export():
    scenes.clear_scene()
    path = os.path.join(args.work, "block.vdb")
    block = np.full((4, 4, 4), 0.5, dtype=np.float32)  # (nz, ny, nx) density 0.5 in a 1 m cube at (2, 0, 0)
    core.write_vdb(path, (2.0, 0.0, 0.0), ZONE, {"density": block})
    volume = bpy.data.volumes.new("Block")
    volume.filepath = path
    obj = bpy.data.objects.new("Block", volume)
    bpy.context.scene.collection.objects.link(obj)
    color, density = (0.5, 0.5, 0.5), 3.0
    volume.materials.append(principled("Block Fog", color, density))
    bpy.context.scene.radiosity.zone_size = ZONE
    exported = exported_media()
    (medium,) = exported.media
    K = medium.grid["extinction"][..., 0].astype(np.float64)
    # Mass is kept by the box-averaged read: total extinction = density * grid mass.
    np.testing.assert_allclose(K.sum() * ZONE ** 3, density * 0.5 * 1.0, rtol=1e-4)
    np.testing.assert_allclose(K.max(), density * 0.5, rtol=1e-4)
    assert medium.input_file == os.path.realpath(path) or os.path.samefile(medium.input_file, path)


def isothermal_scene(L0, rho, omega, K):
    scenes.clear_scene()
    scenes.furnace_box(rho, (1.0 - rho) * L0)
    fog_cube(principled("Glow", (omega,) * 3, K, strength=K * (1.0 - omega) * L0))
    settings = bpy.context.scene.radiosity
    settings.zone_size = ZONE
    settings.media_folder = args.work + "/"


def test_isothermal_enclosure():
    L0, rho, omega, K = 2.0, 0.5, 0.4, 1.5
    isothermal_scene(L0, rho, omega, K)
    summary = addon.bake(bpy.context.scene, method="GAUSS_SEIDEL", element_size=0.25, hemicube_resolution=32,
                         tolerance=1e-6)
    # 4^3 uniform voxels: the core merges them into 2^3 blocks by default (zones_before_merge = 64).
    assert summary["zones"] == 8, summary["zones"]
    corners = harness.corner_colors(bpy.data.objects["Furnace"].data, "Radiosity")
    np.testing.assert_allclose(corners, L0, rtol=5e-3)
    np.testing.assert_allclose(baked_ratio(summary), L0, rtol=5e-3)
    power = summary["energy"]
    # The walls emit from both sides (as in Cycles): their back sides face out of the box, and what
    # they send, pi 6 (1 - rho) L0 (the box's area is 6), leaves it. The rest is absorbed inside.
    outward = math.pi * 6 * (1.0 - rho) * L0
    assert abs(power["absorbed"] / (power["emitted"] - outward) - 1.0) < 1e-3, power
    # The baked Volume object, its file beside the test's work folder, in the bake's collection.
    (obj,) = [o for o in bpy.data.objects if o.type == "VOLUME"]
    assert obj.name in bpy.data.collections["Radiosity Bake"].objects
    assert os.path.isfile(bpy.path.abspath(obj.data.filepath))
    assert sorted(name for name, _ in core.vdb_grids(obj.data.filepath)) == ["density", "emission"]
    # A second bake replaces its own output and nothing else, and writes beside the file the first
    # bake's Volume shows (Blender 4.x would render the grids it loaded from that path before).
    first_file = os.path.realpath(bpy.path.abspath(obj.data.filepath))
    addon.bake(bpy.context.scene, method="GAUSS_SEIDEL", element_size=0.5, hemicube_resolution=32)
    (second,) = [o for o in bpy.data.objects if o.type == "VOLUME"]
    assert "Fog" in bpy.data.objects and "Furnace" in bpy.data.objects
    assert os.path.realpath(bpy.path.abspath(second.data.filepath)) != first_file
    assert os.path.isfile(first_file)  # the first bake's file stays: undo shows it again
    # The third writes the first name again: no Volume shows it any more.
    addon.bake(bpy.context.scene, method="GAUSS_SEIDEL", element_size=0.5, hemicube_resolution=32)
    (third,) = [o for o in bpy.data.objects if o.type == "VOLUME"]
    assert os.path.realpath(bpy.path.abspath(third.data.filepath)) == first_file


def test_scattering_medium_takes_the_walls_radiance():
    L0 = 1.5
    scenes.clear_scene()
    scenes.furnace_box(0.0, L0)
    fog_cube(principled("Scatter", (1.0, 1.0, 1.0), 2.0))
    bpy.context.scene.radiosity.zone_size = ZONE
    bpy.context.scene.radiosity.media_folder = args.work + "/"
    summary = addon.bake(bpy.context.scene, method="GAUSS_SEIDEL", element_size=0.25, hemicube_resolution=32,
                         tolerance=1e-6)
    np.testing.assert_allclose(baked_ratio(summary), L0, rtol=5e-3)


harness.run(test_mesh_medium_export, test_volume_object_export, test_isothermal_enclosure,
            test_scattering_medium_takes_the_walls_radiance)
