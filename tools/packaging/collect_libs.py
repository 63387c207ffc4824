"""Copies the native module and every shared library it needs into one folder, in the environment
it was built in (where `ldd` finds the same libraries the build linked):

    python3 collect_libs.py MODULE.so OUT_DIR

OUT_DIR/bake_radiosity_core/ gets the module and its libraries under their sonames (Embree too,
which the module opens with dlopen and `ldd` does not list); OUT_DIR gets bundle.json naming
them, and system_symbols.txt: the
symbols the libraries every Linux has (the C and C++ runtimes, left out of the bundle) define,
which privatize_libs.py must not rename.
"""

import json
import os
import re
import shutil
import subprocess
import sys

# Present on every Linux a Blender runs on; Blender itself loads them (the manylinux policy's core).
SYSTEM_LIBRARIES = {
    "linux-vdso.so.1", "ld-linux-x86-64.so.2", "libc.so.6", "libm.so.6", "libdl.so.2", "librt.so.1",
    "libpthread.so.0", "libstdc++.so.6", "libgcc_s.so.1",
}


def needed_libraries(binary):
    """{soname: path} of everything `binary` loads, directly or not (ldd's list)."""
    output = subprocess.run(["ldd", binary], check=True, capture_output=True, text=True).stdout
    found = {}
    for line in output.splitlines():  # "libtbb.so.12 => /lib/.../libtbb.so.12 (0x...)" or "/lib64/ld-... (0x...)"
        parts = line.split()
        if "=>" in parts:
            name, path = parts[0], parts[2]
            if path == "not":
                raise SystemExit("%s needs %s, which is not installed" % (binary, name))
        elif parts and parts[0].startswith("/"):
            name, path = os.path.basename(parts[0]), parts[0]
        else:
            continue
        found[name] = path
    return found


def embree_soname(module):
    """The Embree soname the module dlopens (compiled in as a string)."""
    with open(module, "rb") as stream:
        match = re.search(rb"libembree[0-9]\.so\.[0-9]+", stream.read())
    if not match:
        raise SystemExit("%s names no libembree*.so.*" % module)
    return match.group().decode()


def library_path(soname):
    """Where the dynamic loader finds `soname` (ldconfig's cache)."""
    output = subprocess.run(["ldconfig", "-p"], check=True, capture_output=True, text=True).stdout
    for line in output.splitlines():
        parts = line.split()
        if parts and parts[0] == soname and "x86-64" in line:
            return parts[-1]
    raise SystemExit("%s is not installed" % soname)


def defined_symbols(path):
    output = subprocess.run(["nm", "-D", "--defined-only", "--without-symbol-versions", path],
                            check=True, capture_output=True, text=True).stdout
    return {line.split()[-1] for line in output.splitlines() if line.strip()}


PACKAGE = "bake_radiosity_core"


def main(module, out_dir):
    package = os.path.join(out_dir, PACKAGE)
    shutil.rmtree(package, ignore_errors=True)
    os.makedirs(package)
    embree = embree_soname(module)
    embree_file = library_path(embree)
    everything = {**needed_libraries(module), **needed_libraries(embree_file), embree: embree_file}
    bundled = sorted(name for name in everything if name not in SYSTEM_LIBRARIES)
    for name in bundled:
        shutil.copyfile(everything[name], os.path.join(package, name))
    shutil.copyfile(module, os.path.join(package, os.path.basename(module)))

    system = set()
    for name in SYSTEM_LIBRARIES & everything.keys():
        if name != "linux-vdso.so.1":
            system |= defined_symbols(everything[name])
    with open(os.path.join(out_dir, "system_symbols.txt"), "w") as stream:
        stream.write("\n".join(sorted(system)) + "\n")
    with open(os.path.join(out_dir, "bundle.json"), "w") as stream:
        json.dump({"package": PACKAGE, "module": os.path.basename(module), "libraries": bundled,
                   "embree": embree}, stream, indent=1)
    print("%s: %d libraries (%s)" % (package, len(bundled), ", ".join(bundled)))


if __name__ == "__main__":
    if len(sys.argv) != 3:
        raise SystemExit(__doc__)
    main(*sys.argv[1:])
