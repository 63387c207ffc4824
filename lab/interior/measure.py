"""The interior of lab/interior/level.py (or any scene: --blend, --object) against Cycles, in one run:
a deep Cycles truth (many seeds, cached in --truth; seeds are added until its own noise is below
--truth-noise or --seeds is reached), Cycles at a ladder of sample counts and the add-on's presets,
each timed (CPU seconds of this process: all threads). Error: relative RMS luminance per vertex
(corner colours averaged per vertex; vertices the truth sees below 1% of the mean left out), as
measured and with the truth's own noise taken out in quadrature.

    blender -b --factory-startup --python-exit-code 1 --python lab/interior/measure.py -- \\
        --addon-zip build/bake_radiosity.zip --truth /tmp/interior/truth.npz [--truth-samples 1024] \\
        [--seeds 16] [--ladder 64,256,1024] [--quality DRAFT,MEDIUM,HIGH]
"""

import argparse
import os
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [here, os.path.join(here, "..", "..", "blender_tests")]

import bpy  # noqa: E402
import numpy as np  # noqa: E402

import harness  # noqa: E402
import level  # noqa: E402


def luminance_per_vertex(mesh, corner_colors):
    """Mean over each vertex's corners of the luminance (Rec. 709) of (loops, 3) colours."""
    vertex = np.empty(len(mesh.loops), dtype=np.int64)
    mesh.loops.foreach_get("vertex_index", vertex)
    y = corner_colors @ np.array([0.2126, 0.7152, 0.0722])
    return np.bincount(vertex, y, len(mesh.vertices)) / np.maximum(np.bincount(vertex, None, len(mesh.vertices)), 1)


def timed(function):
    """(what `function` returns, its CPU seconds, its wall seconds)."""
    with harness.Stopwatch() as seconds:
        result = function()
    return result, seconds.cpu, seconds.wall


def deep_truth(obj, path, samples, seeds, target_noise):
    """Per-seed vertex luminances, cached in `path` (its vertex positions must match)."""
    positions = np.empty(len(obj.data.vertices) * 3)
    obj.data.vertices.foreach_get("co", positions)
    runs, seconds = [], []
    if os.path.exists(path):
        cached = np.load(path)
        assert np.allclose(cached["positions"], positions) and int(cached["samples"]) == samples, \
            "the cached truth is of another mesh or sample count: delete %s" % path
        runs, seconds = list(cached["runs"]), list(cached["seconds"])
    while len(runs) < seeds:
        if len(runs) >= 4 and noise_of(np.array(runs)) < target_noise:
            break
        colors, cpu, _ = timed(lambda: harness.cycles_corner_bake(obj, samples, 1000 + len(runs)))
        runs.append(luminance_per_vertex(obj.data, colors))
        seconds.append(cpu)
        os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
        np.savez(path, positions=positions, samples=samples, runs=np.array(runs), seconds=np.array(seconds))
        print("truth: %d seeds of %d samples, noise %.2f%%" % (len(runs), samples, 100 * noise_of(np.array(runs))),
              flush=True)
    return np.array(runs), float(np.mean(seconds))


def noise_of(runs):
    """Relative RMS noise per vertex of the mean of `runs` (from their spread), over lit vertices."""
    mean = runs.mean(axis=0)
    lit = mean > 0.01 * mean.mean()
    spread = runs.std(axis=0, ddof=1) / np.sqrt(len(runs))
    return float(np.sqrt(np.mean((spread[lit] / mean[lit]) ** 2)))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--addon-zip", required=True)
    parser.add_argument("--truth", required=True)
    parser.add_argument("--truth-samples", type=int, default=1024)
    parser.add_argument("--seeds", type=int, default=16)
    parser.add_argument("--truth-noise", type=float, default=0.003)
    parser.add_argument("--ladder", default="64,256,1024")
    parser.add_argument("--quality", default="DRAFT,MEDIUM,HIGH")
    parser.add_argument("--blend", help="measure this scene (e.g. a level of ../shared/levels) instead of level.py's")
    parser.add_argument("--object", default="BakeMesh", help="with --blend: the mesh object measured")
    parser.add_argument("--save", help="a .npz to keep each preset's per-vertex luminance, the truth and the "
                                       "vertices' positions in (for looking at where the error sits)")
    args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:])
    addon = harness.install_addon(args.addon_zip)
    if args.blend:
        bpy.ops.wm.open_mainfile(filepath=args.blend)
        obj = bpy.data.objects[args.object]
    else:
        obj = level.build()
    runs, seconds_per_seed = deep_truth(obj, args.truth, args.truth_samples, args.seeds, args.truth_noise)
    truth = runs.mean(axis=0)
    truth_noise = noise_of(runs)
    lit = truth > 0.01 * truth.mean()

    def error(values):
        measured = float(np.sqrt(np.mean(((values[lit] - truth[lit]) / truth[lit]) ** 2)))
        return measured, float(np.sqrt(max(measured ** 2 - truth_noise ** 2, 0.0)))

    print("%s: %d faces, %d vertices (%d lit), %d lamps; truth %d seeds x %d samples (%.0f CPU s a seed), "
          "its noise %.2f%%; load %.1f"
          % (os.path.basename(args.blend or "interior"), len(obj.data.polygons), len(truth), lit.sum(),
             len(bpy.data.lights), len(runs), args.truth_samples, seconds_per_seed, 100 * truth_noise,
             os.getloadavg()[0]), flush=True)
    for samples in [int(s) for s in args.ladder.split(",") if s]:
        colors, cpu, wall = timed(lambda: harness.cycles_corner_bake(obj, samples, samples))  # not the truth's seeds
        measured, clean = error(luminance_per_vertex(obj.data, colors))
        print("Cycles %5d samples: %6.1f CPU s, %6.1f wall s: %.2f%% (%.2f%% without the truth's noise)"
              % (samples, cpu, wall, 100 * measured, 100 * clean), flush=True)
    positions = np.empty(len(obj.data.vertices) * 3)
    obj.data.vertices.foreach_get("co", positions)
    saved = {"truth": truth, "truth_runs": runs, "positions": positions.reshape(-1, 3),
             "lamps": np.array([o.matrix_world.translation[:] for o in bpy.data.objects if o.type == "LIGHT"])}
    for quality in args.quality.split(","):
        summary, cpu, wall = timed(lambda: addon.bake(bpy.context.scene, quality=quality))
        colors = harness.corner_colors(obj.data, "Radiosity")
        measured, clean = error(luminance_per_vertex(obj.data, colors))
        baked = luminance_per_vertex(obj.data, colors)
        mean_ratio = float(baked[lit].mean() / truth[lit].mean())
        median = float(np.median(np.abs(baked[lit] / truth[lit] - 1)))
        print("%-6s %5d elements, %s, resolution %d: %6.1f CPU s, %6.1f wall s: %.2f%% (%.2f%% without the "
              "truth's noise), mean %.4f of the truth, median per vertex %.2f%%"
              % (quality, summary["elements"], summary["method"], summary["resolution"], cpu, wall, 100 * measured,
                 100 * clean, mean_ratio, 100 * median), flush=True)
        print("seconds:", {k: round(v, 2) for k, v in summary.get("seconds", {}).items()}, flush=True)
        estimate = summary.get("error_estimate") or {}
        print("the summary's estimate: %s %s per corner (sampling %s, solution's bias %s, field's light %s)"
              % tuple(estimate.get(k) for k in ("relation", "typical", "sampling", "solution_bias", "field_light")),
              flush=True)
        saved[quality] = baked
    if args.save:
        np.savez(args.save, **saved)
    print("load %.1f" % os.getloadavg()[0])


main()
