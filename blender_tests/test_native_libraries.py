"""Where the native core and its libraries come from inside this Blender, after a hierarchical bake
(which opens Embree). Installed from an extension package (tools/build_packages.sh): _core is the
bake_radiosity_core wheel's, every library it bundles is loaded from beside it (none replaced by
a library of the same soname Blender had loaded), and none of them defines a dynamic symbol that
a library Blender loaded defines too (checked with nm; Embree's rtc* API, which the core opens
privately, aside), so no call of ours can land in Blender's TBB, OpenVDB, Embree or Boost,
whatever their versions. Installed from the add-on zip: _core is the one inside the add-on."""

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
native = sys.modules[harness.MODULE + ".engine.native"]

# The C and C++ runtimes are one per process by design: their names are shared, not clashes.
RUNTIMES = ("libc.so", "libm.so", "libstdc++.so", "libgcc_s.so", "ld-linux")


def mapped_libraries():
    """The shared objects mapped into this process."""
    with open("/proc/self/maps") as maps:
        paths = {line.split(None, 5)[5].strip() for line in maps if len(line.split(None, 5)) == 6}
    return sorted(path for path in paths if path.startswith("/") and ".so" in os.path.basename(path)
                  and os.path.isfile(path))


def defined_symbols(path):
    output = subprocess.run(["nm", "-D", "--defined-only", "--without-symbol-versions", path],
                            capture_output=True, text=True).stdout
    return {line.split()[-1] for line in output.splitlines() if line.strip()}


def test_hierarchical_furnace_opens_embree():
    rho, emitted = 0.5, 1.0
    scenes.clear_scene()
    box = scenes.furnace_box(rho, emitted, cells=4)
    addon.bake(bpy.context.scene, element_size=0.125, method="HIERARCHICAL", refine_tolerance=0.02)
    colors = harness.corner_colors(box.data, "Radiosity")
    error = np.abs(colors / (emitted / (1 - rho)) - 1).max()
    print("hierarchical furnace: worst error %.3f%%" % (100 * error))
    assert error < 0.01, error


def test_core_and_libraries_are_the_packages_own():
    folder = os.path.dirname(os.path.realpath(native.core().__file__))
    mapped = mapped_libraries()
    ours = [path for path in mapped if os.path.dirname(os.path.realpath(path)) == folder]
    print("_core from %s; %d of the %d libraries mapped are from there" % (folder, len(ours), len(mapped)))
    if not harness.MODULE.startswith("bl_ext."):
        assert folder == os.path.dirname(os.path.realpath(addon.__file__)), folder
        return
    assert os.path.basename(folder) == "bake_radiosity_core" and "site-packages" in folder, folder
    bundled = sorted(name for name in os.listdir(folder) if ".so" in name and not name.startswith("_core"))
    assert sorted(os.path.basename(path) for path in ours if not os.path.basename(path).startswith("_core")) \
        == bundled, (ours, bundled)
    assert any(os.path.basename(path).startswith("libembree") for path in ours), "Embree is not the bundled one"

    theirs = [path for path in mapped if path not in ours and not os.path.basename(path).startswith(RUNTIMES)]
    runtime = set().union(*(defined_symbols(path) for path in mapped if os.path.basename(path).startswith(RUNTIMES)))
    their_symbols = set().union(*(defined_symbols(path) for path in theirs))
    clashes = {}
    for path in ours:
        shared = (defined_symbols(path) & their_symbols) - runtime
        if os.path.basename(path).startswith("libembree"):
            # Embree's API keeps its names: the core opens it with RTLD_LOCAL and takes the functions'
            # addresses with dlsym on that handle, so nothing binds to them by name.
            shared = {name for name in shared if not name.startswith("rtc")}
        if shared:
            clashes[os.path.basename(path)] = sorted(shared)[:3] + ["(%d in all)" % len(shared)]
    print("%d libraries of Blender's define %d symbols; ours define none of them: %s"
          % (len(theirs), len(their_symbols), not clashes))
    assert not clashes, clashes


harness.run(test_hierarchical_furnace_opens_embree, test_core_and_libraries_are_the_packages_own)
