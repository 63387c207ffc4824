"""Makes the libraries collect_libs.py gathered private to the module, so that it loads beside
whatever the host Blender has loaded (its own TBB, OpenVDB, Embree, Boost, Imath, ...):

    python3 privatize_libs.py OUT_DIR        (needs patchelf 0.18 or later, and nm)

- Each library gets a soname of its own, libX-<hash>.so.N (as auditwheel names them), and the
  module and the libraries ask for those: the dynamic loader reuses an already loaded library of
  the same soname, so Blender's libtbb.so.12 would otherwise stand in for ours.
- Every symbol the libraries define is renamed NAME.bake_radiosity, in the libraries and in the
  module that calls them: the loader binds a name to the first definition in the process, and
  Blender's libraries come first, so another version of the same function (Embree 3's rtcOccluded1
  bound to Embree 4's misses every ray) would be called. Left alone: the names the C and C++
  runtimes define (they must stay one per process: operator new, typeinfo of std types, ...) and
  Embree's rtc* API, which the module finds with dlsym on its own handle.
- RUNPATH $ORIGIN: they are found beside the module, wherever the package is installed.

Embree keeps its soname as its file name: the module dlopens it by path from its own folder.
Checks the result with nm and readelf and fails if any bundled library still defines a name
the host could own, or still needs an unbundled, non-system library.
"""

import hashlib
import json
import os
import subprocess
import sys

SUFFIX = ".bake_radiosity"


def run(*command):
    return subprocess.run(command, check=True, capture_output=True, text=True).stdout


def defined_symbols(path):
    output = run("nm", "-D", "--defined-only", "--without-symbol-versions", path)
    return {line.split()[-1] for line in output.splitlines() if line.strip()}


def needed(path):
    output = run("readelf", "-d", "-W", path)
    return [line.split("[", 1)[1].rstrip("]") for line in output.splitlines() if "(NEEDED)" in line]


def private_name(folder, soname):
    """libtbb.so.12 -> libtbb-1a2b3c4d.so.12 (the hash of the file's contents)."""
    with open(os.path.join(folder, soname), "rb") as stream:
        digest = hashlib.sha256(stream.read()).hexdigest()[:8]
    stem, _, version = soname.partition(".so")
    return "%s-%s.so%s" % (stem, digest, version)


def main(out_dir):
    with open(os.path.join(out_dir, "bundle.json")) as stream:
        bundle = json.load(stream)
    with open(os.path.join(out_dir, "system_symbols.txt")) as stream:
        system = set(stream.read().split())
    folder = os.path.join(out_dir, bundle["package"])
    libraries, embree = bundle["libraries"], bundle["embree"]

    renamed = {soname: private_name(folder, soname) for soname in libraries}
    symbols = set()
    for soname in libraries:
        defined = defined_symbols(os.path.join(folder, soname))
        if soname == embree:
            defined = {name for name in defined if not name.startswith("rtc")}
        symbols |= defined
    symbols -= system
    symbol_map = os.path.join(out_dir, "symbol_map.txt")
    with open(symbol_map, "w") as stream:
        stream.writelines("%s %s%s\n" % (name, name, SUFFIX) for name in sorted(symbols))

    for file_name in libraries + [bundle["module"]]:
        path = os.path.join(folder, file_name)
        command = ["patchelf", "--rename-dynamic-symbols", symbol_map, "--set-rpath", "$ORIGIN"]
        if file_name in renamed:
            command += ["--set-soname", renamed[file_name]]
        for dependency in needed(path):
            if dependency in renamed:
                command += ["--replace-needed", dependency, renamed[dependency]]
        run(*command, path)
        if file_name in renamed and file_name != embree:
            os.rename(path, os.path.join(folder, renamed[file_name]))

    check(folder, bundle, renamed, symbols)
    print("%s: %d libraries private, %d symbols renamed" % (folder, len(libraries), len(symbols)))


def check(folder, bundle, renamed, symbols):
    files = [bundle["embree"] if soname == bundle["embree"] else renamed[soname] for soname in bundle["libraries"]]
    private = set(renamed.values())
    problems = []
    for file_name in files + [bundle["module"]]:
        path = os.path.join(folder, file_name)
        left = defined_symbols(path) & symbols
        if left:
            problems.append("%s still defines %d public names, e.g. %s" % (file_name, len(left), sorted(left)[0]))
        for dependency in needed(path):
            if dependency not in private and dependency in renamed:
                problems.append("%s still needs %s" % (file_name, dependency))
        if "$ORIGIN" not in run("readelf", "-d", "-W", path):
            problems.append("%s has no RUNPATH $ORIGIN" % file_name)
    if problems:
        raise SystemExit("privatize_libs.py: " + "; ".join(problems))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        raise SystemExit(__doc__)
    main(sys.argv[1])
