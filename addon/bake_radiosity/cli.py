"""Headless baking from the command line. Blender 4.2 and later (the add-on installed and enabled,
as an extension or not):

    blender -b scene.blend --command bake_radiosity --output baked.blend [--quality HIGH] ...

Blender 3.x (the add-on installed from the zip; enabling it is not needed):

    blender -b scene.blend --python-exit-code 1 --python-expr "import bake_radiosity.cli as c; c.main()" -- \\
        --output baked.blend [--quality HIGH] [--resolution 256] [--element-size 0.05] ...

or, with the path of this file:  blender -b scene.blend --python .../bake_radiosity/cli.py -- ...

Bakes the file's active scene, or each --scene in turn, saves it to --output (default: over the
input file) and exits 0. Scenes that show the same objects under other lamps, World or emission
strengths (lighting variants, each writing its own Attribute Name) reuse the first one's geometry
(elements, form factors, the final gather's rays) unless --no-reuse is given. On any failure prints
"Bake Radiosity failed: <reason>" to stderr and exits 1 (2 for arguments it cannot parse, with the
usage).
"""

import argparse
import os
import sys


def parse(argv):
    parser = argparse.ArgumentParser(prog="blender -b scene.blend --command bake_radiosity",
                                     description="Bake radiosity into colour attributes and save.")
    parser.add_argument("--output", help="where to save the baked file (default: overwrite the input)")
    parser.add_argument("--scene", action="append",
                        help="scene to bake (default: the file's active scene); repeat it to bake several in turn")
    parser.add_argument("--no-reuse", dest="reuse", action="store_false",
                        help="bake every scene from scratch instead of reusing the previous bake's geometry")
    parser.add_argument("--quality", choices=("DRAFT", "MEDIUM", "HIGH", "CUSTOM"),
                        help="preset; naming --method, --resolution, --element-size or --tolerance alone means CUSTOM")
    parser.add_argument("--method", choices=("AUTO", "GAUSS_SEIDEL", "PROGRESSIVE", "JACOBI", "HIERARCHICAL"))
    parser.add_argument("--resolution", type=int, dest="hemicube_resolution", help="hemi-cube resolution")
    parser.add_argument("--element-size", type=float, help="largest element edge in metres (0 = faces)")
    parser.add_argument("--tolerance", type=float, help="relative residual to stop at")
    parser.add_argument("--refine-tolerance", type=float, help="hierarchical: error per link, share of the mean")
    parser.add_argument("--max-iterations", type=int)
    parser.add_argument("--memory-budget", type=int, help="megabytes the stored form factors may take")
    parser.add_argument("--hard-edge-angle", type=float, help="degrees")
    parser.add_argument("--attribute-name")
    parser.add_argument("--target", choices=("ORIGINAL", "COPIES"))
    parser.add_argument("--write-light-only", action="store_true", default=None,
                        help="also write the light without the surface colour into '<attribute> Light'")
    parser.add_argument("--light-group-layers", action="store_true", default=None,
                        help="also write one attribute per light group, '<attribute> <group>', that sum to it")
    parser.add_argument("--no-final-gather", dest="final_gather", action="store_false", default=None,
                        help="corners take the interpolated solution instead of gathering their light")
    parser.add_argument("--separate-linked-duplicates", action="store_true", default=None,
                        help="give objects that share a mesh (Alt+D) a mesh each, so each keeps its own light")
    parser.add_argument("--make-linked-local", action="store_true", default=None,
                        help="give objects whose meshes are linked from another file local meshes to hold the light "
                             "(without it such a bake is refused: linked data is not saved with the file)")
    return parser.parse_args(argv)


def overrides_of(arguments):
    import math
    overrides = {k: v for k, v in vars(arguments).items()
                 if v is not None and k not in ("output", "scene", "reuse")}
    if "hard_edge_angle" in overrides:
        overrides["hard_edge_angle"] = math.radians(overrides["hard_edge_angle"])
    return overrides


def run(argv):
    """Bakes and saves as `argv` says; returns the exit code: 0, 1 after a failure (the reason on
    stderr), 2 for arguments argparse rejected (its usage on stderr). The `--command` entry."""
    try:
        arguments = parse(argv)
    except SystemExit as stop:  # --help (0) or arguments it rejected (2)
        return stop.code or 0
    try:
        _bake_and_save(arguments)
    except Exception as error:
        print("Bake Radiosity failed: %s" % error, file=sys.stderr, flush=True)
        return 1
    return 0


def main(argv=None):
    """The `--python-expr` entry: the arguments after `--`; exits the process on failure."""
    if argv is None:
        argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    code = run(argv)
    if code:
        sys.exit(code)


_command = None


def register():
    """`blender --command bake_radiosity ...` (Blender 4.2 and later)."""
    global _command
    import bpy
    if hasattr(bpy.utils, "register_cli_command"):
        _command = bpy.utils.register_cli_command("bake_radiosity", run)


def unregister():
    global _command
    import bpy
    if _command is not None:
        bpy.utils.unregister_cli_command(_command)
        _command = None


def _bake_and_save(arguments):
    import importlib

    import addon_utils
    import bpy

    if not hasattr(bpy.types.Scene, "radiosity"):
        addon_utils.enable(__package__, default_set=False, handle_error=_raise)
    pipeline = importlib.import_module(__package__ + ".pipeline")

    scenes = [bpy.data.scenes[name] for name in arguments.scene] if arguments.scene else [bpy.context.scene]
    for scene in scenes:
        summary = pipeline.bake(scene, reuse=arguments.reuse, **overrides_of(arguments))
        for warning in summary["warnings"]:
            print("Bake Radiosity warning: %s" % warning, flush=True)
        print("Bake Radiosity: %s: %s" % (scene.name, scene.radiosity.last_report), flush=True)
        print("Bake Radiosity: %s" % scene.radiosity.last_accuracy, flush=True)
        print("Bake Radiosity: %s" % scene.radiosity.last_cost, flush=True)
    output = arguments.output or bpy.data.filepath
    if not output:
        raise RuntimeError("no --output given and the scene was never saved")
    bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(output))
    print("Bake Radiosity: saved %s" % os.path.abspath(output), flush=True)


def _raise(error):
    raise error


if __name__ == "__main__":
    # Run as a script (--python path/to/cli.py): make the package importable, then bake.
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    from bake_radiosity import cli

    cli.main()
