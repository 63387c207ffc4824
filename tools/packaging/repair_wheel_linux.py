"""cibuildwheel's repair step on Linux (.github/workflows/release.yml), in place of auditwheel, which
neither bundles Embree (the core opens it with dlopen; it is not a DT_NEEDED library) nor keeps
the bundled libraries' symbols from binding to the host Blender's:

    python repair_wheel_linux.py WHEEL DEST_DIR [PLATFORM_TAG]    (default manylinux_2_28_x86_64)

Unpacks the wheel scikit-build-core built, then does what tools/build_packages.sh does with a
Debian build: collect_libs.py, privatize_libs.py (patchelf 0.18 or later), make_wheel.py; before
the last, runtime_versions.py fails if a file of the bundle needs a newer glibc or libstdc++ than
the manylinux tag allows.
"""

import os
import sys
import tempfile
import zipfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import collect_libs  # noqa: E402
import make_wheel  # noqa: E402
import privatize_libs  # noqa: E402
import runtime_versions  # noqa: E402


def main(wheel, dest_dir, platform="manylinux_2_28_x86_64"):
    version = os.path.basename(wheel).split("-")[1]
    with tempfile.TemporaryDirectory() as work:
        with zipfile.ZipFile(wheel) as archive:
            archive.extractall(os.path.join(work, "wheel"))
        package = os.path.join(work, "wheel", collect_libs.PACKAGE)
        module = next(os.path.join(package, name) for name in os.listdir(package) if name.startswith("_core."))
        bundle = os.path.join(work, "bundle")
        collect_libs.main(module, bundle)
        privatize_libs.main(bundle)
        runtime_versions.main(bundle, platform)
        make_wheel.main(bundle, version, dest_dir, platform)


if __name__ == "__main__":
    if len(sys.argv) not in (3, 4):
        raise SystemExit(__doc__)
    main(*sys.argv[1:])
