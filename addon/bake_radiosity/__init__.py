"""Bake Radiosity: diffuse global illumination by the radiosity method, baked into colour
attributes by a native C++ core."""

bl_info = {
    "name": "Bake Radiosity",
    "author": "Bake Radiosity developers",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Properties > Render > Radiosity, and 3D View > Sidebar > Radiosity",
    "description": "Bake diffuse light by the radiosity method into colour attributes",
    "doc_url": "https://github.com/bake-radiosity/bake-radiosity/blob/main/docs/user-guide.md",
    "category": "Render",
}

import importlib  # noqa: E402  (bl_info first: Blender reads it without running the module)
import importlib.util  # noqa: E402

# Outside Blender only the Blender-free layer (bake_radiosity.engine) can be used: nothing here
# that needs bpy is imported then.
IN_BLENDER = importlib.util.find_spec("bpy") is not None
MODULE_NAMES = ("properties", "operators", "ui", "cli") if IN_BLENDER else ()
_modules = [importlib.import_module("." + name, __package__) for name in MODULE_NAMES]

# Reloading the add-on (F3 > Reload Scripts) must pick up edited modules.
if "bpy" in locals():
    _modules = [importlib.reload(module) for module in _modules]

if IN_BLENDER:
    import bpy  # noqa: E402, F401  (after the reload check above, as Blender's own add-ons do)


def bake(scene, **overrides):
    """Bake `scene` now; see bake_radiosity.pipeline.bake for the summary returned."""
    from .pipeline import bake as run
    return run(scene, **overrides)


def register():
    for module in _modules:
        module.register()


def unregister():
    for module in reversed(_modules):
        module.unregister()
