"""A level's own `_core.bake` call (the settings the add-on chooses at Medium), run again with some of
its keywords changed, each against a deep Cycles truth that lab/interior/measure.py cached: the mean
over the lit vertices, the median and RMS per vertex and the luminance-weighted ratio to the truth
by distance from the nearest lamp (lab/levels/variants.py's report), the power balance, and, with
--polygons, each variant's solved light per input polygon (area-weighted means of the elements'
radiance and of their emission, the lamps' first reflection included) in a .npz beside the truth, so
that two methods' solutions can be compared polygon by polygon whatever their meshes. Run inside Blender:

    BLENDER_USER_SCRIPTS=$(mktemp -d) BLENDER_USER_CONFIG=$(mktemp -d) \\
      blender -b --factory-startup --python-exit-code 1 --python lab/levels/core_variants.py -- \\
        --addon-zip build/bake_radiosity.zip --blend /tmp/oa/oa_bases3.blend \\
        --truth /var/cache/bake-radiosity/levels/oa_bases3_1024.npz \\
        --variants "method=hierarchical;final_gather=False,\
method=gauss_seidel;final_gather=False;matrix_budget_bytes=6291456000"

A variant is ';'-separated keyword=value pairs of `_core.bake` ("-": the call as the add-on makes it).
"""

import os
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "..", "blender_tests"))
sys.path.insert(0, here)

import bpy  # noqa: E402
import numpy as np  # noqa: E402

import harness  # noqa: E402
import variants  # noqa: E402


class Captured(Exception):
    """Stops the add-on's bake once its `_core.bake` call is known."""


def captured_call(addon):
    """(the exported scene, the keywords) of the add-on's `_core.bake` call at Medium."""
    solve = sys.modules[harness.MODULE + ".engine.solve"]
    kept, call = solve.bake, {}

    def capture(scene, keywords, progress=None):
        call.update(scene=scene, keywords=dict(keywords))
        raise Captured()
    solve.bake = capture
    try:
        addon.bake(bpy.context.scene, quality="MEDIUM")
    except Captured:
        pass
    finally:
        solve.bake = kept
    return call["scene"], call["keywords"], solve.native.core()


def value(text):
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    return {"True": True, "False": False}.get(text, text)


def per_polygon(result, key, polygons):
    """Area-weighted mean over each input polygon's elements of an element array's mean channel."""
    area = result["element_area"].astype(np.float64)
    weighted = np.bincount(result["element_polygon"], result[key].mean(axis=1) * area, polygons)
    return weighted / np.maximum(np.bincount(result["element_polygon"], area, polygons), 1e-30)


def main():
    parser = variants.level_arguments()
    parser.add_argument("--variants", default="-")
    parser.add_argument("--polygons", help="a .npz for each variant's light per input polygon")
    args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:])
    addon = harness.install_addon(args.addon_zip)
    bpy.ops.wm.open_mainfile(filepath=args.blend)
    mesh = bpy.data.objects[args.object].data
    cached = np.load(args.truth)
    positions = cached["positions"].reshape(-1, 3)
    lamps = variants.lamp_positions()
    scene, base, core = captured_call(addon)
    energy = sys.modules[harness.MODULE + ".engine.energy"]
    saved = {}
    for variant in args.variants.split(","):
        keywords = dict(base)
        for item in filter(None, variant.split(";")):
            if item != "-":
                name, text = item.split("=")
                keywords[name] = value(text)
        start = time.process_time()
        result = core.bake(*scene.scene_arrays(), front_only=scene.front_only, textures=scene.textures, **keywords)
        cpu = time.process_time() - start
        corners = np.asarray(result["corner_radiance"]).reshape(-1, 3)
        assert len(corners) == len(mesh.loops), "the scene's corners are not the mesh's loops"
        baked = variants.luminance_per_vertex(mesh, corners)
        variants.report("%s (%s, %d elements)" % (variant, keywords["method"], len(result["element_radiance"])),
                        baked, cached["runs"], positions, lamps, cpu)
        print("  absorbed %.4f of the emitted" % energy.balance(result).absorbed_fraction, flush=True)
        saved[variant + " radiance"] = per_polygon(result, "element_radiance", len(mesh.polygons))
        saved[variant + " emission"] = per_polygon(result, "element_emission", len(mesh.polygons))
    if args.polygons:
        np.savez(args.polygons, **saved)


main()
