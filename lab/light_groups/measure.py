"""What light group layers cost over the ordinary bake: the Cornell box of blender_tests/scenes.py lit
by its ceiling opening and 8 point lamps under the ceiling, baked at a preset without layers and with
1, 2 and 8 light groups (lamp i in group i mod G, the opening in group 0). Prints wall and CPU
seconds, the phases, the layers' memory (the add-on's bound, which the summary names) and the
process's peak resident memory (run one group count a process to compare those). Run inside Blender:

    BLENDER_USER_SCRIPTS=$(mktemp -d) BLENDER_USER_CONFIG=$(mktemp -d) \\
      blender -b --factory-startup --python-exit-code 1 --python lab/light_groups/measure.py -- \\
        --addon-zip build/bake_radiosity.zip [--groups 0,1,2,8] [--quality MEDIUM] [--method HIERARCHICAL]
"""

import argparse
import os
import resource
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "blender_tests"))

import bpy  # noqa: E402

import harness  # noqa: E402
import scenes  # noqa: E402

LAMPS = 8


def group_sources(box, groups):
    """Lamp i in group i mod `groups`, the box (its opening emits) in group 0; no groups for 0 (groups that
    light nothing have no layer)."""
    view_layer = bpy.context.view_layer
    names = ["G%d" % g for g in range(groups)]
    for name in names:
        if name not in [g.name for g in view_layer.lightgroups]:
            view_layer.lightgroups.add(name=name)
    box.lightgroup = names[0] if names else ""
    for i in range(LAMPS):
        bpy.data.objects["Lamp %d" % i].lightgroup = names[i % groups] if names else ""


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--addon-zip", required=True)
    parser.add_argument("--groups", default="0,1,2,8", help="light groups (0: the ordinary bake, no layers)")
    parser.add_argument("--quality", default="MEDIUM")
    parser.add_argument("--method", help="a method instead of the preset's (Custom quality, its defaults)")
    args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:])
    addon = harness.install_addon(args.addon_zip)
    box = scenes.cornell_box_under_lamps(LAMPS)
    for groups in [int(g) for g in args.groups.split(",")]:
        group_sources(box, groups)
        wall, cpu = time.perf_counter(), time.process_time()
        chosen = {"method": args.method} if args.method else {"quality": args.quality}
        summary = addon.bake(bpy.context.scene, light_group_layers=groups > 0, **chosen)
        phases = {k: round(v, 1) for k, v in summary["seconds"].items() if v >= 0.05}
        layers = summary["light_layers"]
        memory = "%.1f MB" % (layers["bytes"] / 2 ** 20) if layers else "none"
        peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
        print("%d groups, %s: %d elements, %.1f wall s, %.1f CPU s, load %.1f, layers' memory %s, peak resident "
              "%.0f MB; %s" % (groups, summary["method"], summary["elements"], time.perf_counter() - wall,
                               time.process_time() - cpu, os.getloadavg()[0], memory, peak, phases), flush=True)


main()
