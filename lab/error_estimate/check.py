"""The summary's error estimate against the truth: bakes Draft, Medium and High on the Cornell box
and on the interior of lab/interior and prints, for each, the estimate the bake reports
(summary["error_estimate"]: its sampling and the solution's bias) next to its measured error per
vertex against the cached deep Cycles truth, the truth's noise taken out (lab/truth/vertex_error.py).
Run inside Blender (command in lab/error_estimate/README.md):

    blender -b --factory-startup --python-exit-code 1 --python lab/error_estimate/check.py -- \\
        --addon-zip build/bake_radiosity.zip --cornell-truth DIR [--interior-truth FILE]
"""

import argparse
import os
import sys

import bpy
import numpy as np

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
sys.path[:0] = [os.path.join(ROOT, "blender_tests"), os.path.join(ROOT, "lab", "truth"),
                os.path.join(ROOT, "lab", "interior")]
import deep_cycles  # noqa: E402
import harness  # noqa: E402
import level  # noqa: E402
import scenes  # noqa: E402
import vertex_error  # noqa: E402

QUALITIES = ("DRAFT", "MEDIUM", "HIGH")


def cornell(truth_folder):
    """(mesh object, VertexLuminance, Truth) of the Cornell box and its cached deep truth."""
    scenes.clear_scene()
    box = scenes.cornell_box("MESH")
    luminance = deep_cycles.vertex_luminance_of(box, deep_cycles.CORNELL_EMITTER_MATERIAL)
    # No time for new seeds: the cached truth as it is.
    _, truth = deep_cycles.deep_truth(box, "cornell", 4096, 0.003, 0.0, luminance, truth_folder)
    return box, luminance, truth


def interior(truth_file):
    """The same for lab/interior's level; its truth (lab/interior/measure.py's cache) holds each
    seed's luminance per vertex, every corner of a vertex averaged."""
    obj = level.build()
    stored = np.load(truth_file)
    positions = np.empty(len(obj.data.vertices) * 3)
    obj.data.vertices.foreach_get("co", positions)
    assert np.allclose(stored["positions"], positions), "%s is of another mesh" % truth_file
    corner_vertex, _, _ = deep_cycles.mesh_arrays(obj)
    luminance = vertex_error.VertexLuminance(corner_vertex, np.ones(len(corner_vertex), dtype=bool))
    assert len(luminance.vertices) == len(obj.data.vertices), "a vertex without corners"
    return obj, luminance, vertex_error.Truth(stored["runs"])


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    parser = argparse.ArgumentParser()
    parser.add_argument("--addon-zip", required=True)
    parser.add_argument("--cornell-truth", help="folder of the Cornell box's cached truth (default: "
                                                "$BAKE_RADIOSITY_TRUTH or build/truth)")
    parser.add_argument("--interior-truth", help="lab/interior/measure.py's truth file (none: no interior)")
    parser.add_argument("--quality", default=",".join(QUALITIES))
    args = parser.parse_args(argv)
    addon = harness.install_addon(args.addon_zip)
    print("scene     quality   estimate (sampling, solution's bias, field's light; solve bound)   "
          "measured (truth's noise out)   estimate / measured")
    scenes = [("cornell", lambda: cornell(args.cornell_truth))]
    if args.interior_truth:
        scenes.append(("interior", lambda: interior(args.interior_truth)))
    for name, load in scenes:
        obj, luminance, truth = load()
        for quality in args.quality.split(","):
            summary = addon.bake(bpy.context.scene, attribute_name="Radiosity", quality=quality)
            estimate = summary["error_estimate"]
            _, measured = truth.error(luminance(harness.corner_colors(obj.data, "Radiosity")))
            print("%-9s %-9s %s %.2f%% (%.2f%%, %.2f%%, %.2f%%; %.2g%%)   %.2f%% (truth's noise %.2f%%)   %.2f" % (
                name, quality, estimate["relation"], 100 * estimate["typical"], 100 * estimate["sampling"],
                100 * estimate["solution_bias"], 100 * estimate["field_light"], 100 * estimate["solve_bound"],
                100 * measured, 100 * truth.noise(), estimate["typical"] / measured), flush=True)
    print("load %.1f" % os.getloadavg()[0])


main()
