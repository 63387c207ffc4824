"""Whether this Blender's Cycles renders Volume objects: a cube turned into a Volume by Blender's
own Mesh to Volume modifier, emitting light, in front of the camera. Exits 0 if it shows in the
render, 1 if the render is black (Debian sid's Blender 5.2 renders no Volume object at all; see
docs/blender-versions.md).

    blender -b --factory-startup --python tools/ci/cycles_renders_volumes.py
"""

import sys

import bpy
import numpy as np

SIZE = 16

for collection in (bpy.data.objects, bpy.data.meshes, bpy.data.materials, bpy.data.lights):
    for item in list(collection):
        collection.remove(item)
bpy.ops.mesh.primitive_cube_add(size=1.0)
cube = bpy.context.active_object
cube.hide_render = True
material = bpy.data.materials.new("Glow")
if bpy.app.version < (5, 0, 0):
    material.use_nodes = True
nodes = material.node_tree.nodes
nodes.clear()
glow = nodes.new("ShaderNodeVolumePrincipled")
glow.inputs["Emission Strength"].default_value = 1.0
material.node_tree.links.new(glow.outputs[0], nodes.new("ShaderNodeOutputMaterial").inputs["Volume"])
volume = bpy.data.volumes.new("Glow")
volume.materials.append(material)
obj = bpy.data.objects.new("Glow", volume)
bpy.context.scene.collection.objects.link(obj)
modifier = obj.modifiers.new("Mesh to Volume", "MESH_TO_VOLUME")
modifier.object = cube
camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
camera.location = (0.0, -4.0, 0.0)
camera.rotation_euler = (np.pi / 2, 0.0, 0.0)
bpy.context.scene.collection.objects.link(camera)

scene = bpy.context.scene
scene.camera = camera
scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = 4
scene.cycles.use_denoising = False
scene.world = None  # black: only the volume can light a pixel
scene.render.resolution_x = scene.render.resolution_y = SIZE
scene.render.resolution_percentage = 100
bpy.ops.render.render()
result = bpy.data.images["Render Result"]
scene.render.filepath = bpy.app.tempdir + "volume.exr"
scene.render.image_settings.file_format = "OPEN_EXR"
result.save_render(scene.render.filepath)
image = bpy.data.images.load(scene.render.filepath)
pixels = np.empty(SIZE * SIZE * 4, dtype=np.float32)
image.pixels.foreach_get(pixels)
brightness = float(pixels.reshape(-1, 4)[:, :3].mean())
renders = brightness > 0.0
print("Cycles in Blender %s %s Volume objects (mean of a glowing cube's render: %.4f)"
      % (bpy.app.version_string, "renders" if renders else "does not render", brightness), flush=True)
sys.exit(0 if renders else 1)
