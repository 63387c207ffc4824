"""A converted level (or any scene) baked at Medium with its gathered solution's settings varied,
against a deep Cycles truth that lab/interior/measure.py cached: the mean over the lit vertices and
the median and RMS per vertex (the truth's noise taken out as lab/interior/measure.py does), and
the luminance-weighted ratio to the truth by distance from the nearest lamp (bounce-lit rooms lie
far from every lamp), each with the truth's own standard error. Run inside Blender:

    BLENDER_USER_SCRIPTS=$(mktemp -d) BLENDER_USER_CONFIG=$(mktemp -d) \\
      blender -b --factory-startup --python-exit-code 1 --python lab/levels/variants.py -- \\
        --addon-zip build/bake_radiosity.zip --blend /tmp/oa/q3dm6ish.blend \\
        --truth /var/cache/bake-radiosity/levels/q3dm6ish_1024.npz --variants 16/4/3136/64,32/4/3136/64

A variant is divisions/cells/rays/field_rays of Medium's gathered solution (auto_settings.Gathered);
"-" bakes Medium as it is.
"""

import argparse
import dataclasses
import os
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "..", "blender_tests"))

import bpy  # noqa: E402
import numpy as np  # noqa: E402

import harness  # noqa: E402

BANDS = ((0.0, 1.0), (1.0, 2.0), (2.0, 4.0), (4.0, 8.0), (8.0, float("inf")))


def luminance_per_vertex(mesh, corner_colors):
    """Mean over each vertex's corners of the luminance (Rec. 709) of (loops, 3) colours."""
    vertex = np.empty(len(mesh.loops), dtype=np.int64)
    mesh.loops.foreach_get("vertex_index", vertex)
    y = corner_colors @ np.array([0.2126, 0.7152, 0.0722])
    return np.bincount(vertex, y, len(mesh.vertices)) / np.maximum(np.bincount(vertex, None, len(mesh.vertices)), 1)


def report(name, baked, truth_runs, positions, lamps, cpu):
    truth = truth_runs.mean(axis=0)
    lit = truth > 0.01 * truth.mean()
    distance = np.min(np.linalg.norm(positions[:, None, :] - lamps[None, :, :], axis=2), axis=1)
    median = float(np.median(np.abs(baked[lit] / truth[lit] - 1)))
    noise = np.sqrt(np.mean((truth_runs[:, lit].std(axis=0, ddof=1) / np.sqrt(len(truth_runs)) / truth[lit]) ** 2))
    rms = np.sqrt(max(np.mean((baked[lit] / truth[lit] - 1) ** 2) - noise ** 2, 0.0))
    print("%s: %.1f CPU s, mean %.4f of the truth, median per vertex %.2f%%, RMS per vertex %.2f%% (truth's noise "
          "%.2f%% out)" % (name, cpu, baked[lit].sum() / truth[lit].sum(), 100 * median, 100 * rms, 100 * noise),
          flush=True)
    for low, high in BANDS:
        band = lit & (distance >= low) & (distance < high)
        if not band.any():
            continue
        error = np.sqrt(truth_runs[:, band].sum(axis=1).var(ddof=1) / len(truth_runs)) / truth[band].sum()
        print("  %4.1f to %4.1f m from a lamp: %4d vertices, %.4f +- %.4f"
              % (low, high, band.sum(), baked[band].sum() / truth[band].sum(), error), flush=True)


def level_arguments(truth=True):
    """The arguments every level script takes: the add-on, the level, its mesh and, with `truth`,
    its truth."""
    parser = argparse.ArgumentParser()
    parser.add_argument("--addon-zip", required=True)
    parser.add_argument("--blend", required=True)
    parser.add_argument("--object", default="BakeMesh")
    if truth:
        parser.add_argument("--truth", required=True, help="a truth cached by lab/interior/measure.py")
    return parser


def lamp_positions():
    """Where the open file's lamps are, (lamps, 3)."""
    return np.array([o.matrix_world.translation[:] for o in bpy.data.objects if o.type == "LIGHT"])


def main():
    parser = level_arguments()
    parser.add_argument("--variants", default="-")
    args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:])
    addon = harness.install_addon(args.addon_zip)
    bpy.ops.wm.open_mainfile(filepath=args.blend)
    obj = bpy.data.objects[args.object]
    cached = np.load(args.truth)
    positions = cached["positions"].reshape(-1, 3)
    lamps = lamp_positions()
    auto_settings = sys.modules[harness.MODULE + ".engine.auto_settings"]
    for variant in args.variants.split(","):
        presets = dict(auto_settings.PRESETS)
        if variant != "-":
            divisions, cells, rays, field_rays = variant.split("/")
            gathered = dataclasses.replace(presets["MEDIUM"].gathered, divisions=int(divisions), cells=float(cells),
                                           rays=int(rays), field_rays=int(field_rays))
            presets["MEDIUM"] = dataclasses.replace(presets["MEDIUM"], gathered=gathered)
        with harness.patched_setting("PRESETS", presets):
            with harness.Stopwatch() as seconds:
                summary = addon.bake(bpy.context.scene, quality="MEDIUM")
        baked = luminance_per_vertex(obj.data, harness.corner_colors(obj.data, "Radiosity"))
        report("%s (%d elements, %s, resolution %d)" % (variant, summary["elements"], summary["method"],
                                                        summary["resolution"]), baked,
               cached["runs"], positions, lamps, seconds.cpu)


if __name__ == "__main__":  # lab/levels/core_variants.py and subdivided.py import its pieces
    main()
