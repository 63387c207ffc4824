"""Cycles' Combined bake of the Cornell box (emitting opening) to corners, saved as .npy, for
lab/final_gather/measure.py. Two halves with seeds 1 and 2; saves their mean and difference.

    blender -b --factory-startup --python-exit-code 1 --python lab/final_gather/cycles_reference.py -- \\
        --out /tmp/fg/cycles.npz --samples 2048
"""
import argparse
import os
import sys

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "blender_tests"))
import harness  # noqa: E402
import scenes  # noqa: E402

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
parser = argparse.ArgumentParser()
parser.add_argument("--out", required=True)
parser.add_argument("--samples", type=int, default=2048)
parser.add_argument("--light", default="MESH", help="scenes.cornell_box's light: MESH, AREA or POINT")
args = parser.parse_args(argv)

scenes.clear_scene()
box = scenes.cornell_box(args.light)
halves = []
for seed in (1, 2):
    harness.use_unbiased_cycles(args.samples, seed)
    name = "Cycles %d" % seed
    attributes = box.data.color_attributes
    attributes.active_color = attributes.new(name, "FLOAT_COLOR", "CORNER")
    for other in bpy.context.view_layer.objects:
        other.select_set(False)
    box.select_set(True)
    bpy.context.view_layer.objects.active = box
    assert bpy.ops.object.bake(type="COMBINED", target="VERTEX_COLORS") == {"FINISHED"}
    halves.append(harness.corner_colors(box.data, name))
np.savez(args.out, half1=halves[0], half2=halves[1], positions=harness.corner_positions(box.data))
print("saved", args.out, halves[0].shape)
