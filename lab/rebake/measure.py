"""What a re-bake after a lighting edit costs against the first bake, and what light group layers cost
over the ordinary bake, on the Cornell box of blender_tests/scenes.py (its ceiling opening and 8 point
lamps of 2 W, as lab/light_groups/measure.py lights it), the interior of lab/interior/level.py and a
game level (--blend, e.g. /tmp/oa/q3dm6ish.blend as lab/levels/README.md makes it), at a preset.

For each scene: the first bake in the session (it keeps its geometry), the re-bake after an edit
(it reuses it; `--edit`: one point lamp moved by 0.3 m, the first baked material's diffuse colour
20% darker, or the first emitting material's strength doubled), and a bake from scratch after the
edit (reuse=False), whose colours the re-bake's must equal; then, from scratch, the ordinary bake
and the bake with 1, 2 and 8 light groups (lamp i in group i mod G, the emitting faces in group 0).
Prints CPU and wall seconds (CPU: every thread of this process), the phases, the cache's memory and
the largest difference of the re-bake's colours from the bake from scratch. Run inside Blender:

    BLENDER_USER_SCRIPTS=$(mktemp -d) BLENDER_USER_CONFIG=$(mktemp -d) \\
      blender -b --factory-startup --python-exit-code 1 --python lab/rebake/measure.py -- \\
        --addon-zip build/bake_radiosity.zip [--scenes cornell,interior,level] [--blend /tmp/oa/q3dm6ish.blend] \\
        [--groups 0,1,2,8] [--quality MEDIUM] [--edit lamp|colour|emission]
"""

import argparse
import os
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [os.path.join(here, "..", "interior"), os.path.join(here, "..", "..", "blender_tests")]

import bpy  # noqa: E402
import numpy as np  # noqa: E402

import harness  # noqa: E402
import level  # noqa: E402
import scenes  # noqa: E402

CORNELL_LAMPS = 8
MOVE = (0.3, 0.0, 0.0)


def interior():
    scenes.clear_scene()
    level.build()


def point_lamps():
    """The scene's point and spot lamps, by name."""
    return sorted((o for o in bpy.context.scene.objects if o.type == "LIGHT" and o.data.type in ("POINT", "SPOT")),
                  key=lambda o: o.name)


def baked_meshes():
    return [o for o in bpy.context.scene.objects if o.type == "MESH"]


def colours(attribute):
    """Every mesh's corner colours of `attribute`, in one array."""
    return np.concatenate([harness.corner_colors(o.data, attribute) for o in baked_meshes()
                           if attribute in o.data.color_attributes])


def bake(addon, attribute, **keywords):
    """A bake into `attribute`: its summary, CPU and wall seconds."""
    bpy.context.scene.radiosity.attribute_name = attribute
    with harness.Stopwatch() as seconds:
        summary = addon.bake(bpy.context.scene, **keywords)
    return summary, seconds.cpu, seconds.wall


def report(label, summary, cpu, wall, reference_cpu=None):
    phases = {k: round(v, 2) for k, v in summary["seconds"].items() if v >= 0.05}
    share = " (%.1f%% of the first bake's CPU)" % (100.0 * cpu / reference_cpu) if reference_cpu else ""
    cache = summary.get("cache") or {}
    print("  %-22s %7d elements, %s: %6.2f CPU s, %6.2f wall s%s; cache reused %s, %.0f MB (direct light %.0f MB); %s"
          % (label, summary["elements"], summary["method"], cpu, wall, share, cache.get("reused"),
             cache.get("bytes", 0) / 2 ** 20, cache.get("direct_bytes", 0) / 2 ** 20, phases), flush=True)


def move_lamp():
    lamp = point_lamps()[0]
    lamp.location = tuple(a + b for a, b in zip(lamp.location, MOVE))


def baked_materials():
    return sorted({s.material for o in baked_meshes() for s in o.material_slots if s.material}, key=lambda m: m.name)


def darken_colour():
    """The first baked material's diffuse colour (Diffuse BSDF or Principled Base Color), 20% darker."""
    for material in baked_materials():
        for node in material.node_tree.nodes:
            socket = node.inputs.get("Base Color") if node.type == "BSDF_PRINCIPLED" else (
                node.inputs.get("Color") if node.type == "BSDF_DIFFUSE" else None)
            if socket is not None and not socket.is_linked:
                socket.default_value = tuple(0.8 * c for c in socket.default_value[:3]) + (1.0,)
                return
    raise RuntimeError("no diffuse colour to edit")


def brighten_emission():
    """The first emitting material's strength (Emission or Principled Emission Strength) doubled."""
    for material in baked_materials():
        for node in material.node_tree.nodes:
            socket = node.inputs.get("Strength") if node.type == "EMISSION" else (
                node.inputs.get("Emission Strength") if node.type == "BSDF_PRINCIPLED" else None)
            if socket is not None and not socket.is_linked and socket.default_value > 0.0:
                socket.default_value *= 2.0
                return
    raise RuntimeError("no emission to edit")


EDITS = {"lamp": (move_lamp, "lamp moved"), "colour": (darken_colour, "colour darker"),
         "emission": (brighten_emission, "emission doubled")}


def measure_rebake(addon, quality, edit):
    apply, what = EDITS[edit]
    first = bake(addon, "First", quality=quality, reuse=False)  # nothing kept before it
    first = bake(addon, "First", quality=quality)
    report("first bake", *first)
    apply()
    again = bake(addon, "Rebake", quality=quality)
    report("re-bake, " + what, *again, reference_cpu=first[1])
    fresh = bake(addon, "Fresh", quality=quality, reuse=False)
    report("from scratch, " + what, *fresh)
    difference = float(np.abs(colours("Rebake") - colours("Fresh")).max())
    print("  re-bake against the bake from scratch: largest corner difference %.3g" % difference, flush=True)


def group_sources(groups):
    """Lamp i in group i mod `groups`, the meshes (their emitting faces) in group 0; no groups for 0."""
    view_layer = bpy.context.view_layer
    names = ["G%d" % g for g in range(groups)]
    for name in names:
        if name not in [g.name for g in view_layer.lightgroups]:
            view_layer.lightgroups.add(name=name)
    for mesh in baked_meshes():
        mesh.lightgroup = names[0] if names else ""
    lamps = sorted((o for o in bpy.context.scene.objects if o.type == "LIGHT"), key=lambda o: o.name)
    for i, lamp in enumerate(lamps):
        lamp.lightgroup = names[i % groups] if names else ""


def measure_layers(addon, quality, group_counts):
    reference = None
    for groups in group_counts:
        group_sources(groups)
        summary, cpu, wall = bake(addon, "Layers", quality=quality, light_group_layers=groups > 0, reuse=False)
        reference = reference or cpu
        layers = summary["light_layers"]
        memory = ", layers' memory %.1f MB" % (layers["bytes"] / 2 ** 20) if layers else ""
        print("  %d light groups: %6.2f CPU s (%.2fx the ordinary bake's), %6.2f wall s%s; %s"
              % (groups, cpu, cpu / reference, wall, memory,
                 {k: round(v, 2) for k, v in summary["seconds"].items() if v >= 0.05}), flush=True)
    group_sources(0)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--addon-zip", required=True)
    parser.add_argument("--scenes", default="cornell,interior,level")
    parser.add_argument("--blend", default="/tmp/oa/q3dm6ish.blend", help="the game level")
    parser.add_argument("--groups", default="0,1,2,8", help="light groups (0: the ordinary bake, first)")
    parser.add_argument("--quality", default="MEDIUM")
    parser.add_argument("--edit", default="lamp", choices=sorted(EDITS))
    args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:])
    addon = harness.install_addon(args.addon_zip)
    build = {"cornell": lambda: scenes.cornell_box_under_lamps(CORNELL_LAMPS), "interior": interior,
             "level": lambda: bpy.ops.wm.open_mainfile(filepath=args.blend)}
    for name in args.scenes.split(","):
        build[name]()
        print("%s at %s: %d faces, %d point lamps; load %.1f" % (
            name, args.quality, sum(len(o.data.polygons) for o in baked_meshes()), len(point_lamps()),
            os.getloadavg()[0]), flush=True)
        measure_rebake(addon, args.quality, args.edit)
        measure_layers(addon, args.quality, [int(g) for g in args.groups.split(",")])


main()
