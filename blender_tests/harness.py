"""Shared set-up for the tests that run inside Blender:

    blender -b --factory-startup --python-exit-code 1 --python test_x.py -- --addon-zip <zip> --work <dir>

parses those arguments, installs and enables the add-on from the zip, and runs test functions,
failing the process (exit code 1 through --python-exit-code) if any fails."""

import argparse
import contextlib
import os
import sys
import time
import traceback

import addon_utils
import bpy

MODULE = "bake_radiosity"


def arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    parser = argparse.ArgumentParser()
    parser.add_argument("--addon-zip", required=True)
    parser.add_argument("--work", required=True)
    parsed = parser.parse_args(argv)
    os.makedirs(parsed.work, exist_ok=True)
    return parsed


def install_addon(zip_path):
    """Installs the zip into this test's own user folders and enables it: an extension package
    (tools/build_packages.sh; its manifest at the top) as an extension in the user_default
    repository, which makes the module bl_ext.user_default.bake_radiosity (harness.MODULE says
    which), the add-on zip as a legacy add-on. The preferences are saved, so that the batch
    command (batch_command) finds the add-on enabled."""
    global MODULE
    import zipfile
    with zipfile.ZipFile(zip_path) as package:
        extension = "blender_manifest.toml" in package.namelist()
    if extension:
        MODULE = "bl_ext.user_default.bake_radiosity"
        result = bpy.ops.extensions.package_install_files(
            repo="user_default", filepath=os.path.abspath(zip_path), enable_on_install=True)
        assert result == {"FINISHED"}, "package_install_files failed: %s" % result
    else:
        result = bpy.ops.preferences.addon_install(filepath=os.path.abspath(zip_path), overwrite=True)
        assert result == {"FINISHED"}, "addon_install failed: %s" % result
        result = bpy.ops.preferences.addon_enable(module=MODULE)
        assert result == {"FINISHED"}, "addon_enable failed: %s" % result
    assert addon_utils.check(MODULE)[1], "add-on not loaded after enabling"
    bpy.ops.wm.save_userpref()
    return sys.modules[MODULE]


def batch_command(blend_file, *options):
    """The command line of a headless bake of `blend_file` with the batch command's `options`, as
    an artist types it in this Blender: `--command bake_radiosity` from 4.2 on, the
    `--python-expr` form (which imports the add-on by its legacy name) before."""
    if bpy.app.version >= (4, 2, 0):
        return [bpy.app.binary_path, "-b", blend_file, "--command", "bake_radiosity", *options]
    return [bpy.app.binary_path, "-b", "--factory-startup", blend_file, "--python-exit-code", "1",
            "--python-expr", "import bake_radiosity.cli as c; c.main()", "--", *options]


class Stopwatch:
    """CPU seconds of this process (every thread) and wall seconds of a with-block."""

    def __enter__(self):
        self.cpu, self.wall = time.process_time(), time.perf_counter()
        return self

    def __exit__(self, *_):
        self.cpu, self.wall = time.process_time() - self.cpu, time.perf_counter() - self.wall


def use_unbiased_cycles(samples, seed, bounces=128, volume_bounces=0, transparent_bounces=0):
    """Cycles as a reference: CPU, a fixed sample count and seed, no adaptive sampling, no
    denoising, no clamping, diffuse (and volume) bounces raised, glossy and transmission off.
    Blender's default light paths stop early and bias a white furnace about 1.6% dark."""
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    cycles = scene.cycles
    cycles.device = "CPU"
    cycles.samples = samples
    cycles.seed = seed
    cycles.use_adaptive_sampling = False
    cycles.use_denoising = False
    cycles.max_bounces = cycles.diffuse_bounces = bounces
    cycles.volume_bounces = volume_bounces
    cycles.transparent_max_bounces = transparent_bounces
    cycles.glossy_bounces = cycles.transmission_bounces = 0
    cycles.sample_clamp_direct = cycles.sample_clamp_indirect = 0.0


def cycles_corner_bake(obj, samples, seed, diffuse_only=False, transparent_bounces=0):
    """(corners, 3) colours of Cycles' Combined bake of `obj` into a new colour attribute 'Cycles
    <seed>', with use_unbiased_cycles(samples, seed, transparent_bounces=transparent_bounces).
    `diffuse_only`: its Diffuse bake (direct, indirect and colour) instead, the light a surface
    reflects diffusely, without the glossy highlights a Combined bake adds for a Principled BSDF.
    Cycles counts a ray that hits a lamp's disk as a transparent bounce: with none allowed it ends
    there, the lamp absorbs it."""
    use_unbiased_cycles(samples, seed, transparent_bounces=transparent_bounces)
    bpy.context.scene.render.bake.target = "VERTEX_COLORS"
    name = "Cycles %d" % seed
    attributes = obj.data.color_attributes
    attributes.active_color = attributes.new(name, "FLOAT_COLOR", "CORNER")
    bpy.context.view_layer.update()
    for other in bpy.context.view_layer.objects:
        if other is not None:  # Blender 5.2 lists objects just removed as None until it redraws
            other.select_set(False)
    obj.select_set(True)
    bpy.context.view_layer.objects.active = obj
    if diffuse_only:
        result = bpy.ops.object.bake(type="DIFFUSE", pass_filter={"DIRECT", "INDIRECT", "COLOR"},
                                     target="VERTEX_COLORS")
    else:
        result = bpy.ops.object.bake(type="COMBINED", target="VERTEX_COLORS")
    assert result == {"FINISHED"}
    return corner_colors(obj.data, name)


def cached_cycles_bakes(obj, path, samples, seeds=(1, 2)):
    """Cycles' corner colours of `obj` for each of `seeds` (cycles_corner_bake), cached in the .npz
    `path`: `colors` (seeds, corners, 3), `samples` and the bakes' wall `seconds`. A file without
    `colors` (an older cache) is made again."""
    import numpy as np
    if not os.path.exists(path) or "colors" not in np.load(path).files:
        start = time.perf_counter()
        colors = np.array([cycles_corner_bake(obj, samples, seed) for seed in seeds])
        os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
        np.savez(path, colors=colors, samples=samples, seconds=time.perf_counter() - start)
    return np.load(path)


def run(*tests):
    """Runs each test function, reports, and raises if any failed."""
    failures = []
    for test in tests:
        start = time.perf_counter()
        try:
            test()
        except Exception:
            failures.append(test.__name__)
            print("FAIL %s\n%s" % (test.__name__, traceback.format_exc()), flush=True)
        else:
            print("PASS %s (%.1f s)" % (test.__name__, time.perf_counter() - start), flush=True)
    if failures:
        raise RuntimeError("failed: " + ", ".join(failures))


def drive_steps(steps, time_limit=None):
    """Registers a timer that advances the generator `steps` every 0.2 s (it yields while Blender
    runs its window) and ends the process with the verdict: 0 when it finishes, 1 after printing the
    traceback of what it raised, or of running past `time_limit` seconds. Windowed Blender has no
    --python-exit-code for timers."""
    started = time.monotonic()

    def drive():
        try:
            if time_limit is not None and time.monotonic() - started > time_limit:
                raise TimeoutError("took longer than %d s" % time_limit)
            next(steps)
            return 0.2
        except StopIteration:
            code = 0
        except Exception:
            traceback.print_exc()
            code = 1
        sys.stdout.flush()
        os._exit(code)

    bpy.app.timers.register(drive, first_interval=1.0)


def operator_error():
    """The operator's ERROR report (bpy.ops raises it in the background), or None if it finished."""
    try:
        result = bpy.ops.radiosity.bake()
    except RuntimeError as error:
        return str(error)
    assert result == {"FINISHED"}, result
    return None


def corner_positions(mesh):
    """(loops, 3) float array: the position of each face corner's vertex."""
    import numpy as np
    positions = np.empty(len(mesh.vertices) * 3)
    mesh.vertices.foreach_get("co", positions)
    loops = np.empty(len(mesh.loops), dtype=np.int64)
    mesh.loops.foreach_get("vertex_index", loops)
    return positions.reshape(-1, 3)[loops]


def corner_normals(mesh):
    """(loops, 3) float array: the normal of each face corner's polygon."""
    import numpy as np
    normals = np.empty(len(mesh.polygons) * 3)
    mesh.polygons.foreach_get("normal", normals)
    totals = np.empty(len(mesh.polygons), dtype=np.int64)
    mesh.polygons.foreach_get("loop_total", totals)
    return np.repeat(normals.reshape(-1, 3), totals, axis=0)


@contextlib.contextmanager
def patched_setting(name, value):
    """The add-on's auto_settings.<name> set to `value` inside the block."""
    auto_settings = sys.modules[MODULE + ".engine.auto_settings"]
    kept = getattr(auto_settings, name)
    setattr(auto_settings, name, value)
    try:
        yield
    finally:
        setattr(auto_settings, name, kept)


def corner_colors(mesh, name):
    """(loops, 3) float array of a FLOAT_COLOR corner attribute."""
    import numpy as np
    attribute = mesh.color_attributes[name]
    assert attribute.domain == "CORNER" and attribute.data_type == "FLOAT_COLOR", \
        (attribute.domain, attribute.data_type)
    values = np.empty(len(mesh.loops) * 4, dtype=np.float32)
    attribute.data.foreach_get("color", values)
    return values.reshape(-1, 4)[:, :3].astype(np.float64)


def file_state():
    """Everything a bake may touch, as comparable plain data (a cancelled or failed bake must
    leave it equal)."""
    import numpy as np
    meshes = {}
    for mesh in bpy.data.meshes:
        colors = {}
        for attribute in mesh.color_attributes:
            values = np.empty(len(attribute.data) * 4, dtype=np.float32)
            attribute.data.foreach_get("color", values)
            colors[attribute.name] = (attribute.domain, attribute.data_type, values.tobytes())
        meshes[mesh.name] = (colors, mesh.color_attributes.active_color_name, len(mesh.materials))
    return {
        "objects": sorted(o.name for o in bpy.data.objects),
        "collections": sorted(c.name for c in bpy.data.collections),
        "materials": sorted(m.name for m in bpy.data.materials),
        "meshes": meshes,
        "report": bpy.context.scene.radiosity.last_report,
        "keys": sorted(bpy.context.scene.keys()),
    }
