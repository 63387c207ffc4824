"""The add-on's Blender-free layer: the scene as flat arrays in (scene.ExportedScene), the bake's
settings chosen (auto_settings), the core run (solve), and the result judged (energy,
error_estimate) and put in words (summary). It imports no bpy, so it runs and is tested in plain
Python with numpy; the Blender layer around it exports, writes back and shows."""
