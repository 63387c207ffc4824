"""Puts a library into a wheel's bake_radiosity_core/ folder, beside _core, and rewrites RECORD
(the release workflow, before delocate or delvewheel, which copy only the libraries that are
linked: the core opens Embree itself, from its own folder first):

    python add_to_wheel.py WHEEL LIBRARY
"""

import os
import sys
import zipfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

from make_wheel import record_line  # noqa: E402

PACKAGE = "bake_radiosity_core"


def main(wheel, library):
    with zipfile.ZipFile(wheel) as archive:
        files = {entry.filename: archive.read(entry) for entry in archive.infolist()}
    with open(library, "rb") as stream:
        files[PACKAGE + "/" + os.path.basename(library)] = stream.read()
    record = next(name for name in files if name.endswith(".dist-info/RECORD"))
    files[record] = ("\n".join([record_line(name, data) for name, data in files.items() if name != record]
                               + [record + ",,"]) + "\n").encode()
    with zipfile.ZipFile(wheel, "w", zipfile.ZIP_DEFLATED) as archive:
        for name, data in files.items():
            archive.writestr(name, data)
    print("%s: added %s" % (wheel, os.path.basename(library)))


if __name__ == "__main__":
    if len(sys.argv) != 3:
        raise SystemExit(__doc__)
    main(*sys.argv[1:])
