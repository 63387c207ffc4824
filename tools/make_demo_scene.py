"""Writes the bundled demo scene: the Cornell box (emitting ceiling opening) with a camera.

    blender -b --factory-startup --python tools/make_demo_scene.py -- out.blend
"""

import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "blender_tests"))

import bpy  # noqa: E402

import scenes  # noqa: E402

output = os.path.abspath(sys.argv[sys.argv.index("--") + 1])
scenes.clear_scene()
scenes.cornell_box("MESH")
scenes.camera_for_cornell_box()
render = bpy.context.scene.render
render.resolution_x = render.resolution_y = 512
bpy.ops.wm.save_as_mainfile(filepath=output)
print("wrote", output)
