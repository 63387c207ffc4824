"""Whether a level's error is in its direct or its indirect light: Cycles and the add-on at Medium bake
the level's corners twice, as it is and with every Diffuse colour scaled by --albedo-scale (0.02: the
light reflected twice or more falls to 2% of what is reflected once, so that bake is the direct light
times the scale). The direct light is the second bake over the scale, the indirect the first less it;
each is compared with Cycles' over the corners the truth lights at 1% of the mean or more, in all and by
distance from the nearest lamp. Cycles' corners (--seeds of 1024 samples each) are cached in --cache.
Run inside Blender:

    BLENDER_USER_SCRIPTS=$(mktemp -d) BLENDER_USER_CONFIG=$(mktemp -d) \\
      blender -b --factory-startup --python-exit-code 1 --python lab/levels/direct_and_indirect.py -- \\
        --addon-zip build/bake_radiosity.zip --blend /tmp/oa/kaos.blend \\
        --cache /var/cache/bake-radiosity/levels/kaos_corners.npz [--seeds 4] [--albedo-scale 0.02]
"""

import os
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [here, os.path.join(here, "..", "..", "blender_tests")]

import bpy  # noqa: E402
import numpy as np  # noqa: E402

import harness  # noqa: E402
import variants  # noqa: E402

LUMINANCE = np.array([0.2126, 0.7152, 0.0722])


def scale_albedo(scale):
    """Every Diffuse BSDF's colour in the open file times `scale`."""
    for material in bpy.data.materials:
        for node in material.node_tree.nodes if material.node_tree else ():
            if node.type == "BSDF_DIFFUSE":
                color = node.inputs["Color"].default_value
                node.inputs["Color"].default_value = (*(scale * c for c in color[:3]), color[3])


def corners(args, scale, cached):
    """(Cycles' mean corner luminance, the add-on's) of the level with its albedo times `scale`; Cycles'
    from `cached` (a dict) under the scale's name when there, else baked and put there."""
    bpy.ops.wm.open_mainfile(filepath=args.blend)
    obj = bpy.data.objects[args.object]
    scale_albedo(scale)
    name = "scale %g" % scale
    if name not in cached:
        cached[name] = np.array([harness.cycles_corner_bake(obj, 1024, 1 + seed) @ LUMINANCE
                                 for seed in range(args.seeds)])
    settings = bpy.context.scene.radiosity
    settings.quality = "MEDIUM"
    assert bpy.ops.radiosity.bake() == {"FINISHED"}, settings.last_report
    return cached[name].mean(axis=0), harness.corner_colors(obj.data, "Radiosity") @ LUMINANCE


def main():
    parser = variants.level_arguments(truth=False)
    parser.add_argument("--cache", required=True, help="a .npz for Cycles' corners at both albedos")
    parser.add_argument("--seeds", type=int, default=4)
    parser.add_argument("--albedo-scale", type=float, default=0.02)
    args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:])
    harness.install_addon(args.addon_zip)
    cached = dict(np.load(args.cache)) if os.path.exists(args.cache) else {}
    cycles, baked = corners(args, 1.0, cached)
    cycles_low, baked_low = corners(args, args.albedo_scale, cached)
    os.makedirs(os.path.dirname(os.path.abspath(args.cache)), exist_ok=True)
    np.savez(args.cache, **cached)
    direct, baked_direct = cycles_low / args.albedo_scale, baked_low / args.albedo_scale
    indirect, baked_indirect = cycles - direct, baked - baked_direct
    lit = cycles > 0.01 * cycles.mean()
    distance = np.min(np.linalg.norm(harness.corner_positions(bpy.data.objects[args.object].data)[:, None, :] -
                                     variants.lamp_positions()[None, :, :], axis=2), axis=1)
    print("%s, %d lit corners, Cycles %d seeds: all light %.4f of Cycles'; direct (%.1f%% of it) %.4f, indirect %.4f"
          % (os.path.basename(args.blend), lit.sum(), args.seeds, baked[lit].sum() / cycles[lit].sum(),
             100 * direct[lit].sum() / cycles[lit].sum(), baked_direct[lit].sum() / direct[lit].sum(),
             baked_indirect[lit].sum() / indirect[lit].sum()), flush=True)
    for low, high in variants.BANDS:
        band = lit & (distance >= low) & (distance < high)
        if band.any():
            print("  %4.1f to %4.1f m from a lamp: %5d corners, all %.4f, direct %.4f, indirect %.4f"
                  % (low, high, band.sum(), baked[band].sum() / cycles[band].sum(),
                     baked_direct[band].sum() / direct[band].sum(), baked_indirect[band].sum() / indirect[band].sum()),
                  flush=True)


main()
