"""A converted level with every face of its mesh cut into (cuts + 1)^2 (bmesh's grid fill: the level's
own vertices keep their places and indices), baked at Medium: triangles, vertices, method, elements,
time and peak memory, and the error at the level's own vertices against its deep Cycles truth
(lab/interior/measure.py caches it; the light is the same at every density). What a million
triangles cost. Run inside Blender:

    BLENDER_USER_SCRIPTS=$(mktemp -d) BLENDER_USER_CONFIG=$(mktemp -d) \\
      blender -b --factory-startup --python-exit-code 1 --python lab/levels/subdivided.py -- \\
        --addon-zip build/bake_radiosity.zip --blend /tmp/oa/q3dm6ish.blend \\
        --truth /var/cache/bake-radiosity/levels/q3dm6ish_1024.npz --cuts 17

One --cuts per process, so that the peak memory is that bake's.
"""

import os
import resource
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
sys.path.insert(0, os.path.join(here, "..", "..", "blender_tests"))

import bmesh  # noqa: E402
import bpy  # noqa: E402
import numpy as np  # noqa: E402

import harness  # noqa: E402
import variants  # noqa: E402


def subdivide(mesh, cuts):
    """Cuts every face of `mesh` into (cuts + 1)^2; returns the number of vertices it had."""
    before = len(mesh.vertices)
    if cuts > 0:
        cut = bmesh.new()
        cut.from_mesh(mesh)
        bmesh.ops.subdivide_edges(cut, edges=cut.edges[:], cuts=cuts, use_grid_fill=True)
        cut.to_mesh(mesh)
        cut.free()
    return before


def main():
    parser = variants.level_arguments()
    parser.add_argument("--cuts", type=int, default=17)
    args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:])
    addon = harness.install_addon(args.addon_zip)
    bpy.ops.wm.open_mainfile(filepath=args.blend)
    obj = bpy.data.objects[args.object]
    original = subdivide(obj.data, args.cuts)
    obj.data.calc_loop_triangles()
    triangles = len(obj.data.loop_triangles)
    cached = np.load(args.truth)
    lamps = variants.lamp_positions()
    wall = time.time()
    with harness.Stopwatch() as seconds:
        summary = addon.bake(bpy.context.scene, quality="MEDIUM")
    wall = time.time() - wall
    peak_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    print("cuts %d: %d triangles, %d vertices, %s, %d elements (%d solved), %.1f CPU s, %.1f wall s, peak %.0f MB"
          % (args.cuts, triangles, len(obj.data.vertices), summary["method"], summary["elements"],
             summary["solve_elements"], seconds.cpu, wall, peak_mb), flush=True)
    print(sys.modules[harness.MODULE + ".engine.summary"].cost_line(summary), flush=True)
    baked = variants.luminance_per_vertex(obj.data, harness.corner_colors(obj.data, "Radiosity"))[:original]
    variants.report("the level's own vertices", baked, cached["runs"], cached["positions"].reshape(-1, 3), lamps,
                    seconds.cpu)


if __name__ == "__main__":
    main()
