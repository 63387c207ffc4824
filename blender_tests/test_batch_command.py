"""The batch command as a farm runs it, in a Blender of its own: `blender -b file --command
bake_radiosity ...` from Blender 4.2 on, the `--python-expr` form with `--python-exit-code 1`
before (harness.batch_command). It bakes a closed furnace to its exact radiance and saves;
every failure exits non-zero with the reason on stderr and writes nothing. From 4.2 on, also
with the add-on installed as an extension from the command line (`extension install-file`),
where it is the module bl_ext.user_default.bake_radiosity and `import bake_radiosity` fails."""

import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402
import numpy as np  # noqa: E402

import harness  # noqa: E402
import scenes  # noqa: E402

args = harness.arguments()
addon = harness.install_addon(args.addon_zip)

RHO, EMITTED = 0.5, 1.0
FURNACE_OPTIONS = ("--method", "GAUSS_SEIDEL", "--element-size", "0.125", "--tolerance", "1e-6")


def saved_furnace():
    scenes.clear_scene()
    scenes.furnace_box(RHO, EMITTED, cells=4)
    path = os.path.join(args.work, "furnace.blend")
    bpy.ops.wm.save_as_mainfile(filepath=path)
    return path


def run(command, env=None):
    print(" ".join(command), flush=True)
    result = subprocess.run(command, capture_output=True, text=True, timeout=600, env=env)
    print("exit code %d; stderr ends: %s" % (result.returncode, result.stderr[-600:]), flush=True)
    return result


def assert_furnace_baked(output):
    """`output` holds the furnace baked to emitted / (1 - rho) at every corner."""
    bpy.ops.wm.open_mainfile(filepath=output)
    colors = np.concatenate([harness.corner_colors(obj.data, "Radiosity")
                             for obj in bpy.data.objects if obj.type == "MESH"])
    expected = EMITTED / (1 - RHO)
    error = np.abs(colors / expected - 1).max()
    print("furnace from the batch command: %d corners, expected %.4f, worst error %.3f%%"
          % (len(colors), expected, 100 * error))
    assert error < 0.005, error


def test_bakes_and_saves():
    source = saved_furnace()
    output = os.path.join(args.work, "furnace-baked.blend")
    result = run(harness.batch_command(source, "--output", output, *FURNACE_OPTIONS))
    assert result.returncode == 0, result.stderr
    assert "Bake Radiosity: saved %s" % os.path.abspath(output) in result.stdout, result.stdout
    assert "Bake Radiosity: Cost: " in result.stdout, result.stdout  # the summary's cost line
    assert_furnace_baked(output)


def test_a_failed_bake_exits_1_with_the_reason():
    scenes.clear_scene()
    source = os.path.join(args.work, "empty.blend")
    bpy.ops.wm.save_as_mainfile(filepath=source)
    output = os.path.join(args.work, "empty-baked.blend")
    result = run(harness.batch_command(source, "--output", output))
    assert result.returncode == 1, result.returncode
    assert "Bake Radiosity failed: Nothing to bake: no mesh renders in view layer" in result.stderr, result.stderr
    assert "Traceback" not in result.stderr, result.stderr
    assert not os.path.exists(output)


def test_arguments_it_cannot_read_exit_2_with_the_usage():
    source = saved_furnace()
    output = os.path.join(args.work, "furnace-unread.blend")
    result = run(harness.batch_command(source, "--output", output, "--quality", "BEST"))
    assert result.returncode == 2, result.returncode
    assert "usage:" in result.stderr and "invalid choice: 'BEST'" in result.stderr, result.stderr
    assert not os.path.exists(output)


def test_installed_as_an_extension_from_the_command_line():
    """Blender 4.2 and later: `blender --command extension install-file -r user_default -e` into
    folders of its own, then the batch command bakes and a failure still exits 1."""
    if bpy.app.version < (4, 2, 0):
        print("Blender %s has no extensions: the legacy form is tested above" % bpy.app.version_string)
        return
    home = os.path.join(args.work, "extension")
    env = dict(os.environ, BLENDER_USER_CONFIG=os.path.join(home, "config"),
               BLENDER_USER_SCRIPTS=os.path.join(home, "scripts"),
               BLENDER_USER_EXTENSIONS=os.path.join(home, "extensions"))
    installed = run([bpy.app.binary_path, "--command", "extension", "install-file", "-r", "user_default", "-e",
                     os.path.abspath(args.addon_zip)], env=env)
    assert installed.returncode == 0, installed.stdout + installed.stderr
    assert os.path.isdir(os.path.join(home, "extensions", "user_default", "bake_radiosity"))

    source = saved_furnace()
    output = os.path.join(args.work, "furnace-extension.blend")
    result = run(harness.batch_command(source, "--output", output, *FURNACE_OPTIONS), env=env)
    assert result.returncode == 0, result.stderr
    assert_furnace_baked(output)

    failed = run(harness.batch_command(source, "--output", output, "--resolution", "8"), env=env)
    assert failed.returncode == 1 and "Bake Radiosity failed: Resolution must be between 16" in failed.stderr, \
        failed.stderr


harness.run(test_bakes_and_saves, test_a_failed_bake_exits_1_with_the_reason,
            test_arguments_it_cannot_read_exit_2_with_the_usage, test_installed_as_an_extension_from_the_command_line)
