"""The bake pipeline: export (needs bpy) -> solve (no bpy, may run in a worker thread) ->
write back (needs bpy). `bake(scene, **overrides)` runs all three; the operator splits them."""

import math
import os
import time

import bpy
import numpy as np

from . import export, native, writeback

SETTING_NAMES = ("method", "hemicube_resolution", "element_size", "tolerance", "max_iterations",
                 "hard_edge_angle", "attribute_name", "target")
CORE_METHODS = {"GAUSS_SEIDEL": "gauss_seidel", "JACOBI": "jacobi", "PROGRESSIVE": "progressive"}
METHOD_LABELS = {"gauss_seidel": "Gauss-Seidel", "jacobi": "Jacobi", "progressive": "progressive refinement"}
TARGETS = ("ORIGINAL", "COPIES")

# AUTO's memory model for the stored matrix: a closed room sees about half of itself from each
# element, and each stored factor costs a float32 value plus an int32 column index.
NONZERO_FRACTION = 0.5
BYTES_PER_NONZERO = 8
MAX_MATRIX_BUDGET = 4 << 30


class BakeError(RuntimeError):
    """A bake that cannot run; the message says why in words an artist can act on."""


def settings_of(scene, overrides=None):
    """The scene's bake settings as a plain dict, with `overrides` (scene.radiosity names) applied."""
    overrides = dict(overrides or {})
    unknown = sorted(set(overrides) - set(SETTING_NAMES))
    if unknown:
        raise TypeError("unknown bake setting(s) %s; known: %s" % (", ".join(unknown), ", ".join(SETTING_NAMES)))
    settings = {name: getattr(scene.radiosity, name) for name in SETTING_NAMES}
    settings.update(overrides)
    if settings["method"] not in ("AUTO",) + tuple(CORE_METHODS):
        raise TypeError("method must be AUTO, GAUSS_SEIDEL, PROGRESSIVE or JACOBI, got %r" % settings["method"])
    if settings["target"] not in TARGETS:
        raise TypeError("target must be ORIGINAL or COPIES, got %r" % settings["target"])
    return settings


def matrix_budget_bytes():
    """A quarter of physical memory, at most 4 GiB: room for Blender and the rest of the bake."""
    try:
        physical = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (ValueError, OSError, AttributeError):
        physical = 8 << 30
    return min(MAX_MATRIX_BUDGET, physical // 4)


def estimated_elements(exported, element_size):
    _, areas = export.polygon_normals_areas(exported.positions, exported.face_offsets, exported.corner_vertices)
    if element_size <= 0.0:
        return len(areas)
    return int(np.maximum(1.0, np.ceil(areas / element_size ** 2)).sum())


def core_method(settings, exported):
    if settings["method"] != "AUTO":
        return CORE_METHODS[settings["method"]]
    elements = estimated_elements(exported, settings["element_size"])
    matrix_bytes = float(elements) ** 2 * NONZERO_FRACTION * BYTES_PER_NONZERO
    return "gauss_seidel" if matrix_bytes <= matrix_budget_bytes() else "progressive"


class BakeJob:
    """One bake: exported arrays, settings, and after `solve` the core's result."""

    def __init__(self, scene, depsgraph, view_layer, overrides=None):
        self.settings = settings_of(scene, overrides)
        start = time.perf_counter()
        self.exported = export.export_scene(depsgraph, view_layer)
        self.seconds_export = time.perf_counter() - start
        if self.exported.polygon_count == 0:
            raise BakeError("Nothing to bake: no visible mesh in view layer '%s'" % view_layer.name)
        self.warnings = list(self.exported.warnings)
        if not self.exported.lights and not self.exported.emission.any():
            self.warnings.append("The scene has no emitting material and no lamp: the bake will be black")
        self.method = core_method(self.settings, self.exported)
        self.result = None

    def solve(self, progress=None):
        """Runs the core. Touches no bpy data, so it may run in a worker thread."""
        self.result = self._run_core(self.method, int(self.settings["max_iterations"]), progress)
        self.warnings += self._skipped_warnings()
        return self.result

    def element_layout(self):
        """(element_vertices, element_corners) in the order progress reports radiance."""
        e = self.exported
        layout = native.core().elements(e.positions, e.face_offsets, e.corner_vertices, e.reflectance,
                                        e.emission, e.material, element_size=float(self.settings["element_size"]))
        return layout["element_vertices"], layout["element_corners"]

    def _run_core(self, method, max_iterations, progress):
        e, s = self.exported, self.settings
        resolution = int(s["hemicube_resolution"])
        return native.core().bake(
            e.positions, e.face_offsets, e.corner_vertices, e.reflectance, e.emission, e.material,
            element_size=float(s["element_size"]), resolution=resolution + resolution % 2,
            method=method, tolerance=float(s["tolerance"]), max_iterations=max_iterations,
            hard_edge_angle=float(s["hard_edge_angle"]), lights=e.lights, progress=progress)

    def write(self, scene):
        """Writes the solved light into the file and returns the bake's summary."""
        start = time.perf_counter()
        self.warnings += writeback.write(scene, self.exported, self.result, self.settings)
        seconds_writeback = time.perf_counter() - start
        r = self.result
        summary = {
            "elements": r["elements"], "iterations": r["iterations"], "shots": r["shots"],
            "residual": r["residual"], "converged": r["converged"], "method": self.method,
            "matrix_bytes": r["matrix_bytes"], "warnings": list(self.warnings),
            "seconds": {"export": self.seconds_export, "form_factors": r["seconds"]["form_factors"],
                        "solve": r["seconds"]["solve"], "writeback": seconds_writeback},
        }
        scene.radiosity.last_report = report_line(summary)
        return summary

    def _skipped_warnings(self):
        skipped = self.result["skipped"]
        if not skipped:
            return []
        names = []
        for polygon, reason in skipped[:5]:
            part = next((p for p in self.exported.parts if p.polygon_start <= polygon < p.polygon_stop), None)
            where = "%s face %d" % (part.object_name, polygon - part.polygon_start) if part else "lamp"
            names.append("%s (%s)" % (where, reason))
        return ["%d face(s) skipped: %s%s" % (len(skipped), ", ".join(names), ", ..." if len(skipped) > 5 else "")]


def report_line(summary):
    seconds = sum(summary["seconds"].values())
    state = "converged" if summary["converged"] else "NOT converged"
    return "%d elements, %s, %d iterations, residual %.2g (%s), %.1f s" % (
        summary["elements"], METHOD_LABELS[summary["method"]], summary["iterations"],
        summary["residual"], state, seconds)


def view_layer_and_depsgraph(scene):
    context = bpy.context
    if context.scene == scene:
        return context.view_layer, context.evaluated_depsgraph_get()
    view_layer = scene.view_layers[0]
    depsgraph = scene.view_layers[0].depsgraph
    depsgraph.update()
    return view_layer, depsgraph


class ProgressPrinter:
    """Prints a progress line at most every `interval` seconds (for -b and the command line)."""

    def __init__(self, interval=1.0):
        self.interval = interval
        self.last = -math.inf

    def __call__(self, info):
        now = time.perf_counter()
        if now - self.last >= self.interval or info["done"] == info["total"]:
            self.last = now
            print(progress_text(info), flush=True)
        return True


def progress_text(info):
    phase = {"form_factors": "form factors", "solve": "solving"}.get(info["phase"], info["phase"])
    text = "Bake Radiosity: %s %d/%d" % (phase, info["done"], info["total"])
    if info["phase"] == "solve":
        text += ", residual %.2e" % info["residual"]
    return text


def bake(scene, **overrides):
    """Bakes `scene` now and returns a summary dict: elements, iterations, residual, converged,
    method, warnings, and seconds per phase (export, form_factors, solve, writeback).

    `overrides` take any scene.radiosity setting by name for this bake only, e.g.
    bake(scene, hemicube_resolution=256, element_size=0.05, method="PROGRESSIVE").
    """
    view_layer, depsgraph = view_layer_and_depsgraph(scene)
    job = BakeJob(scene, depsgraph, view_layer, overrides)
    job.solve(progress=ProgressPrinter() if bpy.app.background else None)
    return job.write(scene)
