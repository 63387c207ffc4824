"""Renders the demo scene to a PNG.

    blender -b baked.blend --python tools/render_demo.py -- out.png baked   # Workbench, flat, baked colours
    blender -b scene.blend --python tools/render_demo.py -- out.png cycles  # Cycles path tracing, for comparison

"baked" shows the colour attribute unshaded (Workbench needs an OpenGL context: run under Xvfb
when there is no display); when a COPIES bake exists, its copies replace the originals.
"""

import sys

import bpy

output, mode = sys.argv[sys.argv.index("--") + 1:][:2]
scene = bpy.context.scene
# Both pictures go through the same plain sRGB transform, so they compare pixel for pixel.
scene.view_settings.view_transform = "Standard"
scene.view_settings.look = "None"

if mode == "baked":
    copies = bpy.data.collections.get("Radiosity Bake")
    if copies is not None and len(copies.objects):
        for obj in scene.objects:
            obj.hide_render = obj.name not in copies.objects and obj.type == "MESH"
    scene.render.engine = "BLENDER_WORKBENCH"
    shading = scene.display.shading
    shading.light = "FLAT"
    shading.color_type = "VERTEX"
    scene.display.render_aa = "16"
elif mode == "cycles":
    scene.render.engine = "CYCLES"
    cycles = scene.cycles
    cycles.samples = 1024
    cycles.use_denoising = False  # Debian's Blender has no OpenImageDenoise
    cycles.max_bounces = cycles.diffuse_bounces = 64
    cycles.sample_clamp_direct = cycles.sample_clamp_indirect = 0.0
else:
    raise SystemExit("mode must be 'baked' or 'cycles'")

scene.render.filepath = output
scene.render.image_settings.file_format = "PNG"
bpy.ops.render.render(write_still=True)
print("wrote", output)
