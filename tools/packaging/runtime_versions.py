"""The C and C++ runtime a folder of native libraries needs, and whether a manylinux tag is true
of it:

    python3 runtime_versions.py FOLDER [PLATFORM_TAG]

Prints the newest GLIBC_, GLIBCXX_, CXXABI_ and GCC_ symbol version any file in FOLDER asks for
(readelf's version-needs section: the loader refuses a library whose runtime lacks one) and which
file asks for it. With a manylinux PLATFORM_TAG, exits 1 naming the versions that tag does not
allow: repair_wheel_linux.py runs it before it tags a wheel manylinux, the check auditwheel would
have made.
"""

import os
import re
import subprocess
import sys

# The newest symbol versions a manylinux policy allows on x86_64 (auditwheel's policy file).
MANYLINUX_LIMITS = {
    "manylinux_2_28_x86_64": {"GLIBC": (2, 28), "GLIBCXX": (3, 4, 24), "CXXABI": (1, 3, 11), "GCC": (7, 0, 0)},
}
NEEDED = re.compile(r"Name: (GLIBC|GLIBCXX|CXXABI|GCC)_([0-9]+(?:\.[0-9]+)*)\s")


def needed_versions(path):
    """{runtime: newest version tuple} that the ELF file `path` asks for."""
    output = subprocess.run(["readelf", "-V", "--wide", path], check=True, capture_output=True, text=True).stdout
    newest = {}
    for runtime, text in NEEDED.findall(output):
        version = tuple(int(part) for part in text.split("."))
        newest[runtime] = max(newest.get(runtime, version), version)
    return newest


def shared_objects(folder):
    for directory, _, names in os.walk(folder):
        for name in sorted(names):
            if ".so" in name:
                yield os.path.join(directory, name)


def newest_needed(folder):
    """{runtime: (newest version, a file that asks for it)} over every shared object in `folder`."""
    newest = {}
    for path in shared_objects(folder):
        for runtime, version in needed_versions(path).items():
            if runtime not in newest or version > newest[runtime][0]:
                newest[runtime] = (version, os.path.relpath(path, folder))
    return newest


def dotted(version):
    return ".".join(str(part) for part in version)


def main(folder, platform=None):
    newest = newest_needed(folder)
    for runtime, (version, path) in sorted(newest.items()):
        print("%s_%s (%s)" % (runtime, dotted(version), path))
    if platform is None or not platform.startswith("manylinux"):
        return
    if platform not in MANYLINUX_LIMITS:
        raise SystemExit("no symbol-version limits known for %s" % platform)
    limits = MANYLINUX_LIMITS[platform]
    too_new = ["%s_%s (%s; %s allows up to %s)" % (runtime, dotted(version), path, platform, dotted(limits[runtime]))
               for runtime, (version, path) in sorted(newest.items()) if version > limits[runtime]]
    if too_new:
        raise SystemExit("%s is not %s: it needs %s" % (folder, platform, ", ".join(too_new)))


if __name__ == "__main__":
    if len(sys.argv) not in (2, 3):
        raise SystemExit(__doc__)
    main(*sys.argv[1:])
