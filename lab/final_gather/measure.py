"""The final gather on the Cornell box against Cycles: whole add-on bakes at a preset's settings
with the gather off and on (the core's final_gather keyword, patched into the add-on's call), each
against a Cycles reference saved by cycles_reference.py.

    blender -b --factory-startup --python-exit-code 1 --python lab/final_gather/measure.py -- \\
        --addon-zip build/bake_radiosity.zip --reference /tmp/fg/cycles8192.npz

Error: relative RMS over the corners not on the emitter (all three channels), as
docs/charts/bake_vs_cycles.py measures it, the reference's noise (its halves' difference) taken
out in quadrature; also split into corners on a seam (their vertex shared with a face of another
normal: the room's edges and corners, the blocks' edges and contact lines) and the rest.
Time: CPU seconds of this process (all threads) and wall seconds of the whole bake."""

import argparse
import math
import os
import sys

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "blender_tests"))
import harness  # noqa: E402
import scenes  # noqa: E402

EMITTER_MATERIAL = 3

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
parser = argparse.ArgumentParser()
parser.add_argument("--addon-zip", required=True)
parser.add_argument("--reference", required=True)
parser.add_argument("--quality", default="MEDIUM")
parser.add_argument("--light", default="MESH", help="scenes.cornell_box's light: MESH, AREA or POINT")
parser.add_argument("--rays", default="preset,64,256,1024",
                    help="gather rays per corner to try; 'preset': the preset's own")
parser.add_argument("--save", help="folder for each bake's corner colours (.npy)")
args = parser.parse_args(argv)

assert bpy.ops.preferences.addon_install(filepath=os.path.abspath(args.addon_zip), overwrite=True) == {"FINISHED"}
assert bpy.ops.preferences.addon_enable(module="bake_radiosity") == {"FINISHED"}
addon = sys.modules["bake_radiosity"]
auto_settings = sys.modules["bake_radiosity.engine.auto_settings"]

scenes.clear_scene()
box = scenes.cornell_box(args.light)
mesh = box.data
material = np.empty(len(mesh.polygons), dtype=np.int64)
mesh.polygons.foreach_get("material_index", material)
total = np.empty(len(mesh.polygons), dtype=np.int64)
mesh.polygons.foreach_get("loop_total", total)
keep = np.repeat(material != EMITTER_MATERIAL, total)

# Seam corners: the corner's vertex position is shared with a polygon of another normal.
normals = np.empty(len(mesh.polygons) * 3)
mesh.polygons.foreach_get("normal", normals)
normals = normals.reshape(-1, 3)
positions = harness.corner_positions(mesh)
corner_normal = np.repeat(normals, total, axis=0)
keys = [tuple(np.round(p, 5)) for p in positions]
normals_at = {}
for k, n in zip(keys, corner_normal):
    normals_at.setdefault(k, []).append(n)
seam = np.array([any(np.dot(n, m) < 0.99 for m in normals_at[k]) for k, n in zip(keys, corner_normal)])

reference_file = np.load(args.reference)
assert np.allclose(reference_file["positions"], positions), "reference is of another mesh"
half1, half2 = reference_file["half1"][keep], reference_file["half2"][keep]
reference = 0.5 * (half1 + half2)
scale = math.sqrt(np.mean(reference ** 2))
noise = math.sqrt(np.mean((half1 - half2) ** 2)) / 2 / scale


def relative_rms(values, ref, subset=None):
    if subset is not None:
        values, ref = values[subset], ref[subset]
    measured2 = np.mean((values - ref) ** 2) / scale ** 2
    return math.sqrt(max(measured2 - noise ** 2, 0.0))


original = auto_settings.Choice.stability_keywords


def bake(quality, gather_rays):
    def keywords(choice):
        k = original(choice)
        if gather_rays != "preset":
            k.update(final_gather=bool(gather_rays))
            if gather_rays:
                k["gather_rays"] = gather_rays
        return k
    auto_settings.Choice.stability_keywords = keywords
    try:
        with harness.Stopwatch() as seconds:
            summary = addon.bake(bpy.context.scene, attribute_name="Radiosity", quality=quality)
        cpu, wall = seconds.cpu, seconds.wall
    finally:
        auto_settings.Choice.stability_keywords = original
    colors = harness.corner_colors(mesh, "Radiosity")[keep]
    if args.save:
        os.makedirs(args.save, exist_ok=True)
        np.save(os.path.join(args.save, "%s_%s.npy" % (quality, gather_rays or "off")), colors)
        np.save(os.path.join(args.save, "positions.npy"), positions[keep])
        np.save(os.path.join(args.save, "normals.npy"), corner_normal[keep])
        np.save(os.path.join(args.save, "reference.npy"), reference)
        np.save(os.path.join(args.save, "seam.npy"), seam[keep])
    s = seam[keep]
    squared = ((colors - reference) ** 2).sum(axis=1)
    print("%-6s gather %-5s: %d elements, resolution %d, CPU %.2f s, wall %.2f s: relative RMS %.2f%% "
          "(seam corners %d: %.2f%%, others %d: %.2f%%; %.0f%% of the squared error on seams), mean %+.2f%%"
          % (quality, gather_rays or "off", summary["elements"], summary["resolution"], cpu, wall,
             100 * relative_rms(colors, reference), s.sum(), 100 * relative_rms(colors, reference, s),
             (~s).sum(), 100 * relative_rms(colors, reference, ~s), 100 * squared[s].sum() / squared.sum(),
             100 * (colors.mean() / reference.mean() - 1)), flush=True)


print("Cycles reference %s: noise %.3f%%, %d corners compared" % (args.reference, 100 * noise, keep.sum()), flush=True)
qualities = args.quality.split(",")
for quality in qualities:
    bake(quality, 0)
    for rays in [r if r == "preset" else int(r) for r in args.rays.split(",") if r]:
        bake(quality, rays)
