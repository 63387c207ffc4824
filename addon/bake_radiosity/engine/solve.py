"""The core's part of a bake: the settings `_core.plan` and `_core.bake` take for a Choice, and
the two calls, with the core's errors as BakeError."""

import contextlib

from . import auto_settings, faces, native
from .errors import BakeError


@contextlib.contextmanager
def core_errors_as_bake_errors(scene=None):
    """The core's errors (bad input, budget, divergence, files: `_core.Error`) as BakeError; with
    `scene` (scene.ExportedScene), the faces they name by index named by object."""
    try:
        yield
    except native.core().Error as error:
        raise BakeError(faces.name_faces(str(error), scene) if scene else str(error)) from error


@contextlib.contextmanager
def numerical_errors_named(scene):
    """Light that is not a number (`_core.NumericalError`) is the bake's fault, never a result to
    write: a BakeError saying in which phase and on which object's face."""
    try:
        yield
    except native.core().NumericalError as error:
        where = scene.polygon_name(error.polygon)
        raise BakeError("The bake failed: light stopped being a number in its '%s' phase at %s. Nothing was "
                        "written; please report this scene" % (error.phase, where)) from error


def core_settings(choice, settings, lights, world=None, media=()):
    """The keyword settings of `_core.plan` and `_core.bake` for `choice` (auto_settings.choose),
    the artist's `settings` (max_iterations, hard_edge_angle), the exported lamps, the World's map
    (None: no World light) and the media's grids (none: a surface bake)."""
    c = choice
    keywords = {"element_size": c.element_size, "resolution": c.resolution, "method": c.method,
                "tolerance": c.tolerance, "max_iterations": int(settings["max_iterations"]),
                "hard_edge_angle": float(settings["hard_edge_angle"]), "lights": lights,
                "matrix_budget_bytes": c.budget_bytes,
                "ambient": c.method == "progressive"}  # brightens only the preview, never the result
    if world is not None:
        keywords["world"] = world
    if c.method == "hierarchical":
        keywords.update(refine_tolerance=c.refine_tolerance, max_bytes=c.budget_bytes)
        keywords.update(c.gather_keywords())
    elif media:  # the zonal bake: surfaces and media in one system
        keywords["media"] = list(media)
        if c.method == "gauss_seidel":
            keywords["over_relaxation"] = auto_settings.AUTOMATIC_OVER_RELAXATION
    else:
        keywords.update(c.stability_keywords())
    return keywords


def plan(scene, keywords):
    """What `_core.bake` will solve for `scene` (scene.ExportedScene) with `keywords`: its elements."""
    with core_errors_as_bake_errors(scene):
        return native.core().plan(*scene.scene_arrays(), front_only=scene.front_only,
                                  textures=scene.textures, **keywords)


def bake(scene, keywords, progress=None):
    """`_core.bake` of `scene` with `keywords`; `progress`: a callback or a `_core.ProgressMonitor`."""
    with core_errors_as_bake_errors(scene), numerical_errors_named(scene):
        return native.core().bake(*scene.scene_arrays(), front_only=scene.front_only,
                                  textures=scene.textures, progress=progress, **keywords)
