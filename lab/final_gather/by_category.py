"""Where a gathered bake's error sits on the Cornell box: per vertex against the cached deep Cycles
truth (lab/truth/deep_cycles.py; run it first), split into the blocks' feet (vertices on the lines
where the blocks stand on the floor), the room's edges and corners, the blocks' other edges, and the
open surfaces. Run inside Blender:

    BLENDER_USER_SCRIPTS=/tmp/profile/scripts BLENDER_USER_CONFIG=/tmp/profile/config \\
      blender -b --factory-startup --python-exit-code 1 --python lab/final_gather/by_category.py -- \\
        --addon-zip build/bake_radiosity.zip --quality MEDIUM,HIGH [--rays 2048,4096] [--worst 10] \\
        [--cache-accuracy 0,0.2] [--cells 1,2]

Error: lab/truth/vertex_error.py's (relative RMS luminance per vertex, the truth's noise taken out
per category); also each category's mean signed error and its share of the squared error. --rays
bakes the first quality again with other gather rays; --worst lists each category's worst vertices."""

import argparse
import dataclasses
import glob
import os
import sys

import bpy
import numpy as np

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
sys.path.insert(0, os.path.join(ROOT, "blender_tests"))
sys.path.insert(0, os.path.join(ROOT, "lab", "truth"))
import deep_cycles  # noqa: E402
import harness  # noqa: E402
import scenes  # noqa: E402
import vertex_error  # noqa: E402

BLOCKS = (((0.5, 0.125), (0.875, 0.5)), ((0.125, 0.5), (0.5, 0.875)))  # scenes.cornell_box's footprints
EPS = 1e-5


def on_outline(x, y):
    for (x0, y0), (x1, y1) in BLOCKS:
        along_x = x0 - EPS <= x <= x1 + EPS and (abs(y - y0) < EPS or abs(y - y1) < EPS)
        along_y = y0 - EPS <= y <= y1 + EPS and (abs(x - x0) < EPS or abs(x - x1) < EPS)
        if along_x or along_y:
            return True
    return False


def categories(box, vertices):
    positions = np.empty(len(box.data.vertices) * 3)
    box.data.vertices.foreach_get("co", positions)
    p = positions.reshape(-1, 3)[vertices]
    _, place, count = np.unique(np.round(p, 6), axis=0, return_inverse=True, return_counts=True)
    seam = count[place.ravel()] > 1
    feet = np.array([abs(z) < EPS and on_outline(x, y) for x, y, z in p])
    planes = sum(np.abs(p[:, axis] - value) < EPS for axis, value in ((0, 0), (0, 1), (1, 1), (2, 0), (2, 1)))
    room = seam & ~feet & (planes >= 2)
    return p, [("all", np.ones_like(seam)), ("feet", feet), ("room edges", room),
               ("block edges", seam & ~feet & ~room), ("open", ~seam)]


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    parser = argparse.ArgumentParser()
    parser.add_argument("--addon-zip", required=True)
    parser.add_argument("--quality", default="MEDIUM")
    parser.add_argument("--rays", default="")
    parser.add_argument("--field-rays", default="", help="bake the first quality again with these field rays")
    parser.add_argument("--shadow-rays", default="", help="bake the first quality again with these shadow rays")
    parser.add_argument("--divisions", default="", help="bake the first quality again with these solutions' divisions")
    parser.add_argument("--cache-accuracy", default="",
                        help="bake the first quality again with these irradiance caching accuracies (0: none)")
    parser.add_argument("--cells", default="",
                        help="bake the first quality again with these hemi-cube cells (the solution's resolution)")
    parser.add_argument("--worst", type=int, default=0)
    args = parser.parse_args(argv)
    addon = harness.install_addon(args.addon_zip)
    scenes.clear_scene()
    box = scenes.cornell_box("MESH")
    luminance = deep_cycles.vertex_luminance_of(box, deep_cycles.CORNELL_EMITTER_MATERIAL)
    cached = sorted(glob.glob(os.path.join(deep_cycles.cache_folder(), "cornell-%s-*spp.npz"
                                           % deep_cycles.scene_hash(box)[:12])))
    assert cached, "no cached truth of this box: run lab/truth/deep_cycles.py"
    stored = np.load(cached[0])
    truth = vertex_error.Truth([luminance(c) for c in stored["colors"]])
    positions, masks = categories(box, luminance.vertices)
    print("truth %s: %d seeds, noise %.3f%%" % (cached[0], len(stored["seeds"]), 100 * truth.noise()))
    auto_settings = sys.modules[harness.MODULE + ".engine.auto_settings"]

    def bake(quality, report=True, **gathered_settings):
        """Bakes `quality` with its preset's Gathered fields replaced by `gathered_settings`."""
        presets = dict(auto_settings.PRESETS)
        gathered = dataclasses.replace(presets[quality].gathered, **gathered_settings)
        presets[quality] = dataclasses.replace(presets[quality], gathered=gathered)
        with harness.patched_setting("PRESETS", presets), harness.Stopwatch() as seconds:
            summary = addon.bake(bpy.context.scene, attribute_name="Radiosity", quality=quality, final_gather=True)
        if not report:
            return
        values = luminance(harness.corner_colors(box.data, "Radiosity"))
        relative = np.where(truth.judged, (values - truth.mean) / truth.mean, 0.0)
        parts = ["%s %d: %.2f%% (mean %+.2f%%, %.0f%% of the squared error)"
                 % (name, (truth.judged & mask).sum(), 100 * truth.error(values, mask)[1],
                    100 * relative[truth.judged & mask].mean(),
                    100 * np.sum(relative[mask] ** 2) / np.sum(relative ** 2)) for name, mask in masks]
        print("%s, %d rays, %d field rays, %d shadow rays, cache accuracy %g, %g cells, %d elements, %.2f CPU s, "
              "load %.1f: %s" % (quality, summary.get("gather_rays", 0), gathered.field_rays, gathered.shadow_rays,
                                 gathered.cache_accuracy, gathered.cells, summary["elements"], seconds.cpu,
                                 os.getloadavg()[0], "; ".join(parts)),
              flush=True)
        for name, mask in masks[1:]:
            for i in [i for i in np.argsort(-np.abs(relative)) if mask[i]][:args.worst]:
                print("  %s: vertex at %s, %.5f against %.5f, %+.1f%%"
                      % (name, np.round(positions[i], 4), values[i], truth.mean[i], 100 * relative[i]))

    bake("DRAFT", report=False)  # not measured: the first bake pays the native module's loading
    qualities = args.quality.split(",")
    for quality in qualities:
        bake(quality)
    for field, kind in (("rays", int), ("field_rays", int), ("shadow_rays", int), ("divisions", int),
                        ("cache_accuracy", float), ("cells", float)):
        for value in filter(None, getattr(args, field).split(",")):
            bake(qualities[0], **{field: kind(value)})


main()
