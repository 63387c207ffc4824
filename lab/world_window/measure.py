"""Where the World's error through a window comes from: blender_tests/world_scenes.py's 2 m room,
lit through its 0.8 m window by a uniform World, baked by the add-on at the default preset with the
World's rays per element and per output point set here (the core's world_samples and
world_point_samples keywords, patched into the add-on's call); each bake against Cycles' bake of
the same room lit by a square area lamp filling the window (the same light seen from inside, and
far less noisy in Cycles than the World), and against the add-on's own bake of that lamp's room.

    BLENDER_USER_SCRIPTS=/tmp/world_window/scripts BLENDER_USER_CONFIG=/tmp/world_window/config \\
      blender -b --factory-startup --python-exit-code 1 --python lab/world_window/measure.py -- \\
        --addon-zip build/bake_radiosity.zip --reference /tmp/world_window/lamp.npz \\
        --samples preset,4096x8192

--samples: ELEMENTxPOINT rays per bake ('preset': the core's own). The reference (two Cycles bakes
of the lamp's room with seeds 1 and 2, --cycles-samples each) is made and saved when the file is
missing. Errors are relative RMS over all corners, the reference's noise (its halves' difference /
2) taken out in quadrature, as world_scenes.errors gives them; "window wall" is the wall with the
window, which sees no World directly: its error is the indirect light's alone."""

import argparse
import math
import os
import sys

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "blender_tests"))
import harness  # noqa: E402
import scenes  # noqa: E402
import world_scenes  # noqa: E402

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
parser = argparse.ArgumentParser()
parser.add_argument("--addon-zip", required=True)
parser.add_argument("--reference", required=True)
parser.add_argument("--cycles-samples", type=int, default=world_scenes.SAMPLES_PER_HALF)
parser.add_argument("--samples", default="preset")
parser.add_argument("--save", help="folder for each bake's corner colours (.npy) and the corners' positions")
args = parser.parse_args(argv)

addon = harness.install_addon(args.addon_zip)
solve = sys.modules[harness.MODULE + ".engine.solve"]

scenes.clear_scene()
room = world_scenes.room()
lamp = world_scenes.window_lamp(world_scenes.SKY_RADIANCE)
window_wall = np.isclose(harness.corner_positions(room.data)[:, 0], world_scenes.ROOM)

if not os.path.exists(args.reference):
    halves = [harness.cycles_corner_bake(room, args.cycles_samples, seed) for seed in (1, 2)]
    os.makedirs(os.path.dirname(os.path.abspath(args.reference)), exist_ok=True)
    np.savez(args.reference, first=halves[0], second=halves[1])
saved = np.load(args.reference)
reference = 0.5 * (saved["first"] + saved["second"])
noise_rms = np.sqrt(np.mean((saved["first"] - saved["second"]) ** 2, axis=1)) / 2  # per corner


def relative_rms(baked, truth, where, noise=None):
    scale2 = np.mean(truth[where] ** 2)
    noise2 = np.mean(noise[where] ** 2) if noise is not None else 0.0
    return math.sqrt(max((np.mean((baked[where] - truth[where]) ** 2) - noise2) / scale2, 0.0))


def report(name, baked, seconds):
    if args.save:
        os.makedirs(args.save, exist_ok=True)
        np.save(os.path.join(args.save, name.replace(" ", "_") + ".npy"), baked)
    everywhere = np.ones(len(baked), bool)
    print("%-18s world %5.1f s, gather %5.1f s | Cycles' lamp: all %.2f%%, window wall %.2f%%, others %.2f%%, "
          "mean %+.2f%% | add-on's lamp: all %.2f%%, window wall %.2f%%, others %.2f%%" % (
              name, seconds["world"], seconds["gather"],
              100 * relative_rms(baked, reference, everywhere, noise_rms),
              100 * relative_rms(baked, reference, window_wall, noise_rms),
              100 * relative_rms(baked, reference, ~window_wall, noise_rms),
              100 * (baked.mean() / reference.mean() - 1),
              100 * relative_rms(baked, lamp_bake, everywhere), 100 * relative_rms(baked, lamp_bake, window_wall),
              100 * relative_rms(baked, lamp_bake, ~window_wall)), flush=True)


def bake(extra):
    original = solve.core_settings

    def patched(*a, **k):
        keywords = original(*a, **k)
        keywords.update(extra)
        return keywords

    solve.core_settings = patched
    try:
        seconds = addon.bake(bpy.context.scene)["seconds"]
        return harness.corner_colors(room.data, "Radiosity"), seconds
    finally:
        solve.core_settings = original


print("Cycles reference: %d samples a half, noise %.2f%% RMS" % (
    args.cycles_samples, 100 * math.sqrt(np.mean(noise_rms ** 2) / np.mean(reference ** 2))), flush=True)
if args.save:
    os.makedirs(args.save, exist_ok=True)
    np.save(os.path.join(args.save, "positions.npy"), harness.corner_positions(room.data))
lamp_bake, seconds = bake({})
report("area lamp", lamp_bake, seconds)
bpy.data.objects.remove(lamp)
world_scenes.uniform_world(world_scenes.SKY_RADIANCE)
for choice in args.samples.split(","):
    extra = {}
    if choice != "preset":
        element, point = (int(n) for n in choice.split("x"))
        extra = {"world_samples": element, "world_point_samples": point}
    baked, seconds = bake(extra)
    report("World %s" % choice, baked, seconds)
