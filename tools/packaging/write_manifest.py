"""Writes the extension's manifest into a package source folder, with `wheels` naming the wheels in
its wheels/ folder and `platforms` the platforms those wheels are for (a package claims only the
platforms it has a native core for):

    python3 write_manifest.py SOURCE_MANIFEST PACKAGE_SOURCE_DIR
"""

import os
import re
import sys

# Wheel platform tag -> Blender's platform name.
PLATFORMS = (
    (r"(many)?linux.*_x86_64", "linux-x64"),
    (r"(many)?linux.*_aarch64", "linux-arm64"),
    (r"win_amd64", "windows-x64"),
    (r"win_arm64", "windows-arm64"),
    (r"macosx_.*_(arm64|universal2)", "macos-arm64"),
    (r"macosx_.*_x86_64", "macos-x64"),
)


def platform_of(wheel):
    tag = wheel[:-len(".whl")].split("-")[-1]
    for pattern, platform in PLATFORMS:
        if re.fullmatch(pattern, tag):
            return platform
    raise SystemExit("no Blender platform for the wheel %s" % wheel)


def toml_list(values):
    return "[%s]" % ", ".join('"%s"' % value for value in values)


def main(source_manifest, package_dir):
    wheels = sorted(name for name in os.listdir(os.path.join(package_dir, "wheels")) if name.endswith(".whl"))
    if not wheels:
        raise SystemExit("%s/wheels has no wheels" % package_dir)
    platforms = sorted({platform_of(wheel) for wheel in wheels})
    with open(source_manifest) as stream:
        text = stream.read()
    text, count = re.subn(r"(?m)^platforms = .*$", "platforms = %s\nwheels = %s" % (
        toml_list(platforms), toml_list("./wheels/" + wheel for wheel in wheels)), text)
    if count != 1:
        raise SystemExit("%s: expected one `platforms = ...` line" % source_manifest)
    with open(os.path.join(package_dir, "blender_manifest.toml"), "w") as stream:
        stream.write(text)
    print("%s: %s, %d wheels" % (package_dir, ", ".join(platforms), len(wheels)))


if __name__ == "__main__":
    if len(sys.argv) != 3:
        raise SystemExit(__doc__)
    main(*sys.argv[1:])
