"""Zips a folder made by collect_libs.py and privatize_libs.py into a wheel Blender's extension
system installs (PEP 427):

    python3 make_wheel.py OUT_DIR VERSION WHEEL_DIR [PLATFORM_TAG]

The wheel holds one package, bake_radiosity_core: its __init__.py (native/python), the module
_core and the private libraries beside it. Its Python tags come from the module's file name
(_core.cpython-313-x86_64-linux-gnu.so: cp313-cp313). The platform tag is linux_x86_64 unless
given: a wheel built on a Debian release needs that release's glibc or newer, which is not a
manylinux promise (the release workflow, built in a manylinux_2_28 image, gives that tag).
Prints the wheel's path.
"""

import base64
import hashlib
import json
import os
import re
import sys
import zipfile

DISTRIBUTION = "bake_radiosity_core"


INIT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "native", "python",
                    "bake_radiosity_core", "__init__.py")


def python_tag(module):
    match = re.fullmatch(r"_core\.cpython-(\d+)-x86_64-linux-gnu\.so", module)
    if not match:
        raise SystemExit("cannot tell the Python of %s" % module)
    return "cp" + match.group(1)


def record_line(name, data):
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return "%s,sha256=%s,%d" % (name, digest, len(data))


def main(out_dir, version, wheel_dir, platform="linux_x86_64"):
    with open(os.path.join(out_dir, "bundle.json")) as stream:
        bundle = json.load(stream)
    python = abi = python_tag(bundle["module"])
    folder = os.path.join(out_dir, bundle["package"])
    info = "%s-%s.dist-info" % (DISTRIBUTION, version)
    with open(INIT, "rb") as stream:
        files = {bundle["package"] + "/__init__.py": stream.read()}
    for name in sorted(os.listdir(folder)):
        with open(os.path.join(folder, name), "rb") as stream:
            files[bundle["package"] + "/" + name] = stream.read()
    files[info + "/METADATA"] = ("Metadata-Version: 2.1\nName: %s\nVersion: %s\n"
                                 "Summary: Bake Radiosity's native core with its libraries\n"
                                 % (DISTRIBUTION, version)).encode()
    files[info + "/WHEEL"] = ("Wheel-Version: 1.0\nGenerator: bake_radiosity make_wheel.py\n"
                              "Root-Is-Purelib: false\nTag: %s-%s-%s\n" % (python, abi, platform)).encode()
    record = [record_line(name, data) for name, data in files.items()] + [info + "/RECORD,,"]
    files[info + "/RECORD"] = ("\n".join(record) + "\n").encode()

    os.makedirs(wheel_dir, exist_ok=True)
    path = os.path.join(wheel_dir, "%s-%s-%s-%s-%s.whl" % (DISTRIBUTION, version, python, abi, platform))
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED, compresslevel=9) as wheel:
        for name, data in files.items():
            entry = zipfile.ZipInfo(name, date_time=(2024, 1, 1, 0, 0, 0))  # the same bytes on every build
            entry.external_attr = 0o755 << 16 if name.endswith(".so") or ".so." in name else 0o644 << 16
            wheel.writestr(entry, data, zipfile.ZIP_DEFLATED)
    print(path)


if __name__ == "__main__":
    if len(sys.argv) not in (4, 5):
        raise SystemExit(__doc__)
    main(*sys.argv[1:])
