"""Loads the compiled radiosity core (`_core`): inside this package (the legacy add-on zip, a
build tree), or from the bake_radiosity_core wheel an extension package installs for the Python
of the Blender it is installed in."""

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
            from .. import _core
        except ImportError as packaged_error:
            try:
                from bake_radiosity_core import _core
            except ImportError as wheel_error:
                folder = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
                raise CoreMissingError(
                    "Bake Radiosity's native module _core could not be loaded, neither from %s (%s) nor from "
                    "the bake_radiosity_core wheel (%s). It must be built for Python %d.%d, the Python this "
                    "Blender runs: install the extension package for this platform (Blender 4.2 and later) "
                    "or the add-on zip built for this Python (see the README)."
                    % (folder, packaged_error, wheel_error, sys.version_info.major, sys.version_info.minor)
                ) from wheel_error
        _module = _core
    return _module
