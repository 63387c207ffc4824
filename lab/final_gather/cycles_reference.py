"""Cycles' Combined bake of the Cornell box (emitting opening) to corners, saved as .npy, for
lab/final_gather/measure.py. Two halves with seeds 1 and 2; saves their mean and difference.

    blender -b --factory-startup --python-exit-code 1 --python lab/final_gather/cycles_reference.py -- \\
        --out /tmp/fg/cycles.npz --samples 2048
"""
import argparse
import os
import sys

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
halves = [harness.cycles_corner_bake(box, args.samples, seed) for seed in (1, 2)]
np.savez(args.out, half1=halves[0], half2=halves[1], positions=harness.corner_positions(box.data))
print("saved", args.out, halves[0].shape)
