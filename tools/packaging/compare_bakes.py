"""Compares the baked copies ('Radiosity Bake' collection, attribute 'Radiosity') of .blend files
with the first one's, corner by corner; e.g. the demo baked in three Blenders:

    blender -b --factory-startup --python tools/packaging/compare_bakes.py -- \\
        build/packages/demo-host/cornell_baked.blend build/packages/demo-trixie/cornell_baked.blend ...

Prints the largest difference of each file's corner colours from the first's, relative to the
brightest corner of the first.
"""

import os
import sys

import bpy
import numpy as np


def colours(path):
    bpy.ops.wm.open_mainfile(filepath=path)
    result = {}
    for obj in bpy.data.collections["Radiosity Bake"].objects:
        attribute = obj.data.color_attributes["Radiosity"]
        values = np.empty(len(attribute.data) * 4, dtype=np.float32)
        attribute.data.foreach_get("color", values)
        result[obj.name] = values.reshape(-1, 4)[:, :3]
    return result


files = sys.argv[sys.argv.index("--") + 1:]
reference = colours(files[0])
for path in files[1:]:
    other = colours(path)
    assert other.keys() == reference.keys(), (other.keys(), reference.keys())
    worst = max(np.abs(other[k] - reference[k]).max() / reference[k].max() for k in reference)
    corners = sum(len(v) for v in reference.values())
    print("%s against %s: %d corners, largest difference %.2e of the brightest corner"
          % (os.path.relpath(path), os.path.relpath(files[0]), corners, worst))
