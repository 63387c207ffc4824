"""The artist's Quality and the Automatic method as concrete bake settings: element size from the
scene's size, resolution and tolerance from the preset, method from the core's own memory model
and the memory budget. No bpy: numbers from the exported arrays only."""

import math
from dataclasses import dataclass

from . import export, native

CORE_METHODS = {"GAUSS_SEIDEL": "gauss_seidel", "JACOBI": "jacobi", "PROGRESSIVE": "progressive",
                "HIERARCHICAL": "hierarchical"}
MEBIBYTE = 1 << 20
# Stability mitigations of docs/stability.md, on for every quality: slivers are cut until no
# element is longer than 4 times its width, and Gauss-Seidel over-relaxes with the core's
# recommended omega (over_relaxation 0 = automatic), which pays off where reflectance is near 1.
MAX_ELEMENT_ASPECT = 4.0
AUTOMATIC_OVER_RELAXATION = 0.0


@dataclass(frozen=True)
class Preset:
    divisions: int      # element size = scene size / divisions (about 6 divisions^2 elements)
    resolution: int     # 4 x divisions: an element one scene size away covers about 2 cells across
    tolerance: float
    refine_tolerance: float  # hierarchical: error per link, share of the mean reflected radiance


PRESETS = {
    "DRAFT": Preset(16, 64, 1e-3, 0.05),
    "MEDIUM": Preset(32, 128, 1e-4, 0.02),
    "HIGH": Preset(48, 192, 1e-5, 0.01),
}


@dataclass(frozen=True)
class Choice:
    """What a bake will run with, and why (the numbers the summary reports)."""
    element_size: float
    resolution: int
    tolerance: float
    refine_tolerance: float
    method: str                 # core name: gauss_seidel, jacobi, progressive, hierarchical
    elements: int
    scene_size: float
    matrix_bytes_bound: int     # the core's worst case for the stored matrix
    budget_bytes: int
    max_element_aspect: float   # 0 = slivers kept (the zonal bake does not cut them)

    def stability_keywords(self):
        """The stability settings _core.bake takes for this choice."""
        keywords = {"max_element_aspect": self.max_element_aspect}
        if self.method == "gauss_seidel":
            keywords["over_relaxation"] = AUTOMATIC_OVER_RELAXATION
        return keywords


def scene_size(exported):
    """Side of the cube with the scene's surface area. For a room it is about the room's size, and
    a long corridor is not judged by its length alone, so the element count a preset gives stays
    near 6 x divisions^2 whatever the scene's shape."""
    _, areas = export.polygon_normals_areas(exported.positions, exported.face_offsets, exported.corner_vertices)
    return math.sqrt(float(areas.sum()) / 6.0)


def choose(settings, exported, zonal=False):
    """The Choice for `settings` (pipeline.settings_of) on `exported`; `zonal`: a bake with media,
    whose core call takes no stability settings."""
    size = scene_size(exported)
    preset = PRESETS.get(settings["quality"])
    if preset is None:
        element_size = float(settings["element_size"])
        resolution = int(settings["hemicube_resolution"])
        tolerance = float(settings["tolerance"])
        refine_tolerance = float(settings["refine_tolerance"])
    else:
        element_size, resolution, tolerance = size / preset.divisions, preset.resolution, preset.tolerance
        refine_tolerance = preset.refine_tolerance
    resolution += resolution % 2  # the core's hemi-cube has a centre line: even resolutions only

    max_element_aspect = 0.0 if zonal else MAX_ELEMENT_ASPECT
    core = native.core()
    layout = core.elements(exported.positions, exported.face_offsets, exported.corner_vertices,
                           exported.reflectance, exported.emission, exported.material, element_size=element_size,
                           max_element_aspect=max_element_aspect)
    elements = int(layout["elements"])
    bound = int(core.matrix_bytes_bound(elements, resolution))
    budget = int(settings["memory_budget"]) * MEBIBYTE
    if preset is None and settings["method"] != "AUTO":
        method = CORE_METHODS[settings["method"]]
    else:
        # Within the budget the core stores F and Gauss-Seidel is fastest (docs/benchmarks.md);
        # beyond it the hierarchy's cost grows nearly linearly (docs/hierarchy.md). It has no media:
        # there progressive refinement solves in memory O(n).
        method = "gauss_seidel" if bound <= budget else ("progressive" if zonal else "hierarchical")
    if zonal and method == "hierarchical":
        raise ValueError("The hierarchical method does not bake fog or smoke yet: choose Automatic or "
                         "progressive refinement for scenes with media")
    return Choice(element_size=element_size, resolution=resolution, tolerance=tolerance,
                  refine_tolerance=refine_tolerance, method=method,
                  elements=elements, scene_size=size, matrix_bytes_bound=bound, budget_bytes=budget,
                  max_element_aspect=max_element_aspect)


def warnings_for(choice):
    """Choices an artist made that will be slow, with what to do instead."""
    if choice.method in ("gauss_seidel", "jacobi") and choice.matrix_bytes_bound > choice.budget_bytes:
        return ["The form factors of %d elements may need %.0f MB, more than the memory budget (%.0f MB): "
                "every sweep renders every hemi-cube again, which is slow. Method Automatic would shoot "
                "progressively instead" % (choice.elements, choice.matrix_bytes_bound / MEBIBYTE,
                                           choice.budget_bytes / MEBIBYTE)]
    return []
