"""The Cornell box of blender_tests/scenes.py (8 quads a wall edge) with every quad cut into k x k
quads, the scene and its light unchanged, baked at a preset: how the bake's time grows with the
vertices, what each phase cost (the summary's
cost line), and the error at the box's own vertices, which every subdivision keeps, against the
cached deep Cycles truth of the 8-quad box (lab/truth/deep_cycles.py; lab/final_gather/by_category.py
measures the same way). Run inside Blender:

    BAKE_RADIOSITY_TRUTH=/var/cache/bake-radiosity/truth \\
    BLENDER_USER_SCRIPTS=$(mktemp -d) BLENDER_USER_CONFIG=$(mktemp -d) \\
      blender -b --factory-startup --python-exit-code 1 --python lab/dense_cornell/measure.py -- \\
        --addon-zip build/bake_radiosity.zip [--cells 8,16,32] [--quality MEDIUM] [--cache-accuracy A]

--cells: quads per wall edge, multiples of 8. --cache-accuracy replaces the preset's irradiance
caching accuracy (0: every output point gathers its own indirect light).
"""

import argparse
import dataclasses
import glob
import os
import sys
import time

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
sys.path.insert(0, os.path.join(ROOT, "blender_tests"))
sys.path.insert(0, os.path.join(ROOT, "lab", "truth"))

import bmesh  # noqa: E402
import bpy  # noqa: E402
import numpy as np  # noqa: E402

import deep_cycles  # noqa: E402
import harness  # noqa: E402
import scenes  # noqa: E402
import vertex_error  # noqa: E402


def subdivided_box(cells):
    """The 8-quad Cornell box with each quad cut into (cells / 8)^2: its vertices stay where they were."""
    scenes.clear_scene()
    box = scenes.cornell_box()
    cuts = cells // scenes.CORNELL_CELLS - 1
    if cuts > 0:
        mesh = bmesh.new()
        mesh.from_mesh(box.data)
        bmesh.ops.subdivide_edges(mesh, edges=mesh.edges[:], cuts=cuts, use_grid_fill=True)
        mesh.to_mesh(box.data)
        mesh.free()
    return box


class OriginalVertices:
    """The 8-quad box's truth and its vertices, which keep their indices when bmesh subdivides (new
    vertices are appended): vertices at one place on different walls are told apart so."""

    def __init__(self):
        box = subdivided_box(scenes.CORNELL_CELLS)
        luminance = deep_cycles.vertex_luminance_of(box, deep_cycles.CORNELL_EMITTER_MATERIAL)
        cached = sorted(glob.glob(os.path.join(deep_cycles.cache_folder(), "cornell-%s-*spp.npz"
                                               % deep_cycles.scene_hash(box)[:12])))
        assert cached, "no cached truth of the box: set BAKE_RADIOSITY_TRUTH or run lab/truth/deep_cycles.py"
        self.truth = vertex_error.Truth([luminance(c) for c in np.load(cached[0])["colors"]])
        self.vertices = luminance.vertices
        self.positions = vertex_positions(box)[self.vertices]

    def error(self, box, colors):
        """Relative RMS luminance error (the truth's noise taken out) at the original vertices."""
        assert np.array_equal(vertex_positions(box)[self.vertices], self.positions), "vertices moved"
        luminance = deep_cycles.vertex_luminance_of(box, deep_cycles.CORNELL_EMITTER_MATERIAL)
        slot = {vertex: i for i, vertex in enumerate(luminance.vertices)}
        return self.truth.error(luminance(colors)[[slot[v] for v in self.vertices]])[1]


def vertex_positions(box):
    positions = np.empty(3 * len(box.data.vertices))
    box.data.vertices.foreach_get("co", positions)
    return positions.reshape(-1, 3)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--addon-zip", required=True)
    parser.add_argument("--cells", default="8,16,32", help="quads per wall edge (multiples of 8)")
    parser.add_argument("--quality", default="MEDIUM")
    parser.add_argument("--cache-accuracy", type=float, default=None)
    args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:])
    addon = harness.install_addon(args.addon_zip)
    if args.cache_accuracy is not None:
        presets = sys.modules[harness.MODULE + ".engine.auto_settings"].PRESETS
        preset = presets[args.quality]
        presets[args.quality] = dataclasses.replace(
            preset, gathered=dataclasses.replace(preset.gathered, cache_accuracy=args.cache_accuracy))
    original = OriginalVertices()
    for cells in [int(c) for c in args.cells.split(",")]:
        box = subdivided_box(cells)
        wall, cpu = time.perf_counter(), time.process_time()
        summary = addon.bake(bpy.context.scene, attribute_name="Radiosity", quality=args.quality)
        wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
        error = original.error(box, harness.corner_colors(box.data, "Radiosity"))
        print("%d cells, %d vertices: %s, %d elements, %.1f wall s, %.1f CPU s, load %.1f; %.2f%% at the box's "
              "own vertices" % (cells, len(box.data.vertices), summary["method"], summary["elements"], wall, cpu,
                                os.getloadavg()[0], 100 * error), flush=True)
        print("  " + bpy.context.scene.radiosity.last_cost, flush=True)


main()
