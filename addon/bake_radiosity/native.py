"""Loads the compiled radiosity core (`_core`), which ships inside this package."""

import os
import sys

_module = None


class CoreMissingError(ImportError):
    pass


def core():
    """The `_core` extension module; raises CoreMissingError with a fix if it cannot load."""
    global _module
    if _module is None:
        try:
            from . import _core
        except ImportError as error:
            folder = os.path.dirname(os.path.abspath(__file__))
            raise CoreMissingError(
                "Bake Radiosity's native module _core could not be loaded from %s (%s). It must be "
                "built for Python %d.%d, the Python this Blender runs: build it with "
                "`cmake --build build --target addon_zip` and install build/bake_radiosity.zip."
                % (folder, error, sys.version_info.major, sys.version_info.minor)) from error
        _module = _core
    return _module
