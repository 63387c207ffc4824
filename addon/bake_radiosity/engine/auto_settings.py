"""The artist's Quality and the Automatic method as concrete bake settings: element size from the
scene's size, resolution from the elements the scene is made of and the distance they see each
other at (the core's recommended_resolution and plan's resolution_distance), tolerance from the preset,
method from the core's own memory model (plan's matrix_bytes_planned) and the memory budget. No
bpy: numbers from the exported arrays only."""

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from . import native, polygons

CORE_METHODS = {"GAUSS_SEIDEL": "gauss_seidel", "JACOBI": "jacobi", "PROGRESSIVE": "progressive",
                "HIERARCHICAL": "hierarchical"}
MEBIBYTE = 1 << 20
# Stability mitigations of docs/stability.md, on for every quality: slivers are cut until no
# element is longer than 4 times its width, and Gauss-Seidel over-relaxes with the core's
# recommended omega (over_relaxation 0 = automatic), which pays off where reflectance is near 1.
MAX_ELEMENT_ASPECT = 4.0
AUTOMATIC_OVER_RELAXATION = 0.0
# The core's largest resolution. Beyond it a preset averages hemi-cubes turned about the normal:
# a factor's aliasing error goes as cells^-0.7 and as rotations^-0.5 (docs/stability.md), so
# needing N > 1024 takes (N / 1024)^2.8 rotations for the same error, at most MAX_ROTATIONS
# (each costs a whole 1024 hemi-cube per element).
MAX_RESOLUTION = 1024
ROTATION_EXPONENT = 2.8
MAX_ROTATIONS = 4


@dataclass(frozen=True)
class Gathered:
    """A preset's solution when the final gather writes the output corners: the gather computes the
    direct light and the light at seams at the corners themselves and reads only the smooth
    indirect light from the solution, which can therefore be much coarser."""
    divisions: int
    cells: float
    near_field: bool
    rays: int           # indirect rays per output corner
    field_rays: int = 0  # indirect rays per element vertex for the field the corners read (0: the solution)
    shadow_rays: int = 64  # shadow rays per output corner, shared by the emitting elements it sees
    cache_accuracy: float = 0.0  # Ward's a: corners read indirect light from gathered neighbours (0: all gather)


@dataclass(frozen=True)
class Preset:
    divisions: int      # element size = scene size / divisions (about 6 divisions^2 elements)
    cells: float        # hemi-cube cells the smallest elements and emitters must cover (accuracy target)
    tolerance: float
    refine_tolerance: float  # hierarchical: error per link, share of the mean reflected radiance
    near_field: bool    # exact area factors between elements closer than their size
    gathered: Gathered  # the solution when the final gather writes the output


# Cells: the smallest elements (and emitting elements) holding a tenth of their area, seen head-on
# from plan's resolution_distance, cover this many cells; their factors then alias by about 0.35
# cells^-0.7 RMS (13%, 10%, 8%). On the 1 m Cornell box that is resolution 56, 136 and 236. That
# distance is half the scene's diagonal, where the presets were tuned, or 1.9 times the distance the
# surfaces see each other at where that is less (the core's resolution.h): a game level's rooms,
# far smaller than its diagonal, no longer pay for its size.
# Near field, measured against Cycles (docs/accuracy.md): a slab 5 mm over a floor, corners under
# and around it, Medium 7.5% -> 5.6% RMS and High 7.9% -> 7.1% with it, at the same time; the
# Cornell box unchanged. At Draft's resolution it made the slab worse (15.7% -> 16.5%, bias +9% ->
# +13%: partly hidden near pairs count as unhidden), so Draft leaves it off.
# Final Gather (Lischinski, Tampieri & Greenberg 1993's local pass; the final gather of photon
# maps): every output corner takes its direct light from each emitter and lamp at the point and its
# indirect light from rays into the solution, corners next to seams again from the seams' gathered
# light. Medium and High first gather a field at every element vertex (64 rays: exact direct light
# at each vertex, the solution's error reaching the output only after one more reflection). The
# presets on the Cornell box, per vertex against the 50-seed deep Cycles truth
# (lab/final_gather/by_category.py; docs/accuracy.md, the race): Medium's 1,728 elements with 3136
# (56 x 56) rays 1.42% before the field, 1.23% with it, 1.16% with 256 shadow rays a corner; High's
# 6,912 elements with 4096 rays 1.13%, 1.04%, 0.95%, and 0.91% with 6400 rays; 3,888 elements
# reach 1.06% with 4096. With the field, the corners on seams also keep how the light turns around
# them (corner_wedges.h): Medium 0.92%, High 0.58%. Draft's 256 rays are its limit: a field changes
# nothing there (3.85% -> 3.80%), and without one it keeps no such tables.
# Sharing (irradiance caching between output corners, Ward's accuracy a: cache_accuracy): Medium's
# error at the 8-quad box's own vertices with its quads cut into 1, 2x2 and 4x4 (lab/dense_cornell/
# measure.py): gathered everywhere 0.93%, 0.97%, 0.62%; a = 0.15 0.93%, 1.09%, 0.72% for half the
# CPU time at 4x4; a = 0.2 1.21%, 1.24%, 0.73% for little less. High keeps more margin under its
# 0.75% target with a = 0.1 (docs/benchmarks.md, the Cornell box subdivided). Draft is not shared.
PRESETS = {
    "DRAFT": Preset(16, 4.0, 1e-3, 0.05, near_field=False, gathered=Gathered(16, 4.0, near_field=False, rays=256)),
    "MEDIUM": Preset(32, 6.0, 1e-4, 0.02, near_field=True,
                     gathered=Gathered(16, 4.0, near_field=True, rays=3136, field_rays=64, shadow_rays=256,
                                       cache_accuracy=0.15)),
    "HIGH": Preset(48, 8.0, 1e-5, 0.01, near_field=True,
                   gathered=Gathered(32, 4.0, near_field=True, rays=6400, field_rays=64, shadow_rays=256,
                                     cache_accuracy=0.1)),
}
# Custom quality's final gather.
GATHER_RAYS = 1024
# Emitting elements smaller than the resolution resolves (fewer than the preset's cells from half
# the scene's diagonal) light every element directly (analytic factors and shadow rays) instead of
# driving the resolution of the whole bake (a 1 cm emitter in a 2 m room asked for 850). Larger
# emitters stay with the hemi-cube: far from them a pair gets one shadow ray, noisier in a penumbra
# than a hemi-cube that resolves them (a slab 5 mm over a floor under a 0.5 m emitter: 9.1% against
# 5.6% RMS around it at ungathered Medium with every emitter lit directly). Each pair costs one
# factor and 1 to 16 shadow rays (about a microsecond), so at most this many emitter-element pairs
# take that path, the smallest emitters first; the rest set the resolution.
DIRECT_EMITTER_PAIRS = 5_000_000


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
    matrix_bytes_planned: int   # the core's plan: the bound if it fits the budget, else estimated from sampled rows
    budget_bytes: int
    max_element_aspect: float   # 0 = slivers kept (the zonal bake does not cut them)
    hemicube_rotations: int     # hemi-cubes per element, turned about the normal (1 = one)
    resolution_reason: str      # why this resolution, in words for the summary
    resolution_distance: float  # metres: what the resolution is judged from (plan's resolution_distance)
    near_field: bool            # the core's near-field correction (a preset's choice; Custom: off)
    gather_rays: int = 0        # final gather's indirect rays per output corner (0 = no gather)
    gather_field_rays: int = 0  # its rays per element vertex for the field the corners read (0: none)
    gather_shadow_rays: int = 64  # its shadow rays per output corner
    gather_cache_accuracy: float = 0.0  # its irradiance caching between output corners (0: every corner gathers)
    direct_emitter_area: float = 0.0  # emitting elements smaller than this light elements directly
    direct_emitters: int = 0    # how many emitting elements that is

    def gather_keywords(self):
        """The final gather's settings _core.bake takes for this choice (any method)."""
        keywords = {"final_gather": self.gather_rays > 0}
        if self.gather_rays > 0:
            keywords.update(gather_rays=self.gather_rays, gather_field_rays=self.gather_field_rays,
                            gather_shadow_rays=self.gather_shadow_rays,
                            gather_cache_accuracy=self.gather_cache_accuracy)
        return keywords

    def stability_keywords(self):
        """The stability and output settings _core.bake takes for this choice (uniform methods)."""
        keywords = {"max_element_aspect": self.max_element_aspect, "hemicube_rotations": self.hemicube_rotations,
                    "near_field": self.near_field, "direct_emitter_area": self.direct_emitter_area}
        keywords.update(self.gather_keywords())
        if self.method == "gauss_seidel":
            keywords["over_relaxation"] = AUTOMATIC_OVER_RELAXATION
        return keywords


def scene_size(exported):
    """Side of the cube with the scene's surface area. For a room it is about the room's size, and
    a long corridor is not judged by its length alone, so the element count a preset gives stays
    near 6 x divisions^2 whatever the scene's shape. Polygons with a non-finite vertex do not count:
    the core skips them with a warning naming each."""
    _, areas = polygons.polygon_normals_areas(exported.positions, exported.face_offsets, exported.corner_vertices)
    return math.sqrt(float(areas[np.isfinite(areas)].sum()) / 6.0)


@dataclass(frozen=True)
class Resolution:
    resolution: int
    rotations: int
    reason: str
    direct_emitter_area: float = 0.0
    direct_emitters: int = 0


def direct_emitter_area(layout, emitting, resolution, preset):
    """Emitting elements smaller than what `resolution` resolves (`_core.resolved_area`) light the
    elements directly, the smallest first within DIRECT_EMITTER_PAIRS emitter-element pairs: (area
    bound, how many). `emitting`: per element the solve has as an unknown (solved_areas)."""
    area = solved_areas(layout)
    bound = native.core().resolved_area(layout["resolution_distance"], resolution, preset.cells)
    small = np.sort(area[emitting & (area < bound)])
    most = DIRECT_EMITTER_PAIRS // max(1, len(solved_areas(layout)))
    if len(small) > most:  # the largest of them go back to the hemi-cube
        bound = float(small[most]) if most > 0 else 0.0
        small = small[small < bound]
    return (float(bound), len(small)) if len(small) else (0.0, 0)


def preset_resolution(layout, emitting, preset, zonal=False):
    """The Resolution at which the smallest elements, and emitting elements, holding a tenth of their
    area (a small lamp aliases most visibly: blotchy light) cover `preset.cells` cells seen from
    plan's resolution_distance (`_core.recommended_resolution`).
    Emitting elements that resolution resolves poorly light the elements directly instead
    (direct_emitter_area; not in the zonal bake).
    Capped at 1024 it adds rotations, except in the zonal bake, which takes none."""
    core = native.core()
    distance, area = layout["resolution_distance"], solved_areas(layout)
    direct = (0.0, 0)
    if not zonal and emitting.any():
        direct = direct_emitter_area(layout, emitting, core.recommended_resolution(area, distance, preset.cells),
                                     preset)
        emitting = emitting & ~(area < direct[0])
    seen_from = _seen_from(layout)
    found = _resolution_for_groups(core, area, area[emitting], distance, seen_from, preset, zonal)
    if not direct[1]:
        return found
    reason = found.reason + "; %d small emitting element%s light the scene directly" % (
        direct[1], "" if direct[1] == 1 else "s")
    return Resolution(found.resolution, found.rotations, reason, *direct)


def solved_polygons(layout):
    """The input polygon of each element the solve has as an unknown (a merged one's first member's)."""
    return layout.get("solve_element_polygon", layout["element_polygon"])


def solved_areas(layout):
    """The areas of the elements the solve has as unknowns: `_core.plan` merges small coplanar ones
    (solve_element_area); a layout without them solves its elements."""
    return layout.get("solve_element_area", layout["element_area"])


def _seen_from(layout):
    """Where the resolution is judged from, in words for the summary."""
    half_diagonal = 0.5 * float(np.linalg.norm(np.ptp(layout["element_vertices"], axis=0)))
    if layout["resolution_distance"] < 0.999 * half_diagonal:
        return "%.3g m, 1.9 times the distance the surfaces see each other at" % layout["resolution_distance"]
    return "half the scene's diagonal"


def _resolution_for_groups(core, area, emitting_area, distance, seen_from, preset, zonal):
    groups = [("elements", area)] + ([("emitting elements", emitting_area)] if len(emitting_area) else [])
    wanted = [(core.recommended_resolution(a, distance, preset.cells), name, a) for name, a in groups]
    resolution, name, driving = max(wanted, key=lambda w: w[0])
    if resolution < MAX_RESOLUTION:
        return Resolution(resolution, 1, "the smallest %s holding a tenth of their area cover %g cells from %s"
                          % (name, preset.cells, seen_from))
    # N grows as sqrt(cells): a quarter of the cells asks for N / 2. Halve until inside the core's range.
    scale = 2
    while core.recommended_resolution(driving, distance, preset.cells / scale ** 2) >= MAX_RESOLUTION and scale < 64:
        scale *= 2
    needed = scale * core.recommended_resolution(driving, distance, preset.cells / scale ** 2)
    rotations = 1 if zonal else min(MAX_ROTATIONS, math.ceil((needed / MAX_RESOLUTION) ** ROTATION_EXPONENT))
    reason = "the smallest %s holding a tenth of their area would need %d to cover %g cells from %s, capped at " \
             "%d" % (name, needed, preset.cells, seen_from, MAX_RESOLUTION)
    if rotations > 1:
        reason += ", %d hemi-cubes turned about the normal" % rotations
    return Resolution(MAX_RESOLUTION, rotations, reason)


def choose(settings, exported, media=()):
    """The Choice for `settings` (pipeline.settings_of) on `exported`; `media`: the media's grids
    as `_core.bake` takes them (a zonal bake, whose core call takes no stability settings). With a
    preset and the final gather, the preset's gathered solution, whichever method solves it: the
    gather writes the output corners of the uniform and the hierarchical bake alike."""
    size = scene_size(exported)
    preset = PRESETS.get(settings["quality"])
    return _choose(settings, exported, media, size, preset, gathered=preset is not None and gathers(settings, media))


def gathers(settings, media):
    """Whether the final gather writes the output: it sets the mesh's own corners (Subdivided Copies
    show every element's corners, most not gathered), and the zonal bake has none."""
    return bool(settings["final_gather"]) and len(media) == 0 and settings["target"] == "ORIGINAL"


def _choose(settings, exported, media, size, preset, gathered):
    zonal = len(media) > 0
    if preset is None:
        element_size = float(settings["element_size"])
        resolution = int(settings["hemicube_resolution"])
        tolerance = float(settings["tolerance"])
        refine_tolerance = float(settings["refine_tolerance"])
        near_field, rays, field_rays, shadow_rays = False, GATHER_RAYS, 0, Gathered.shadow_rays
        cache_accuracy = Gathered.cache_accuracy
    else:
        solution = preset.gathered if gathered else preset
        element_size, tolerance = size / solution.divisions, preset.tolerance
        refine_tolerance = preset.refine_tolerance
        near_field, rays = solution.near_field, preset.gathered.rays
        field_rays, shadow_rays = preset.gathered.field_rays, preset.gathered.shadow_rays
        cache_accuracy = preset.gathered.cache_accuracy
        # The resolution follows the solution's cells (a preset's own, or its gathered one's).
        preset = dataclasses.replace(preset, cells=solution.cells)

    max_element_aspect = 0.0 if zonal else MAX_ELEMENT_ASPECT
    core = native.core()
    # The elements a uniform method would solve, with the media where there are any: plan() builds
    # them as bake() will.
    media_settings = {"media": list(media)} if zonal else {"max_element_aspect": max_element_aspect}
    layout = core.plan(*exported.scene_arrays(), front_only=exported.front_only, element_size=element_size,
                       **media_settings)
    elements, unknowns = int(layout["elements"]), int(layout.get("solve_elements", layout["elements"]))
    if preset is None:
        resolution += resolution % 2  # the core's hemi-cube has a centre line: even resolutions only
        chosen = Resolution(resolution, 1, "set by hand (Custom)")
    else:
        emitting = exported.emission[solved_polygons(layout)].max(axis=1) > 0.0
        chosen = preset_resolution(layout, emitting, preset, zonal)
    resolution = chosen.resolution
    budget = int(settings["memory_budget"]) * MEBIBYTE
    if zonal:
        bound = planned = int(core.matrix_bytes_bound(unknowns, resolution))
    else:
        bound, planned = _matrix_bytes(core, exported, budget, element_size=element_size,
                                       max_element_aspect=max_element_aspect, resolution=resolution,
                                       hemicube_rotations=chosen.rotations, near_field=near_field)
    if preset is None and settings["method"] != "AUTO":
        method = CORE_METHODS[settings["method"]]
    else:
        # Within the budget the core stores F and Gauss-Seidel is fastest (docs/benchmarks.md);
        # beyond it the hierarchy's memory grows about as the triangle count, not as n^2
        # (docs/hierarchy.md). It has no media: there progressive refinement solves in memory O(n).
        method = "gauss_seidel" if planned <= budget else ("progressive" if zonal else "hierarchical")
    if zonal and method == "hierarchical":
        raise ValueError("The hierarchical method does not bake fog or smoke yet: choose Automatic or "
                         "progressive refinement for scenes with media")
    if method == "hierarchical":  # visibility by ray tracing: no hemi-cubes
        chosen = Resolution(resolution, 1, "not used, the hierarchical method traces rays")
    gather = gathers(settings, media)
    return Choice(element_size=element_size, resolution=resolution, tolerance=tolerance,
                  refine_tolerance=refine_tolerance, method=method,
                  elements=elements, scene_size=size, matrix_bytes_bound=bound, matrix_bytes_planned=planned,
                  budget_bytes=budget,
                  max_element_aspect=max_element_aspect, hemicube_rotations=chosen.rotations,
                  resolution_reason=chosen.reason,
                  resolution_distance=float(layout["resolution_distance"]),
                  # The hierarchy traces rays and the zonal bake takes no stability settings.
                  near_field=near_field and method != "hierarchical" and not zonal,
                  gather_rays=rays if gather else 0, gather_field_rays=field_rays if gather else 0,
                  gather_shadow_rays=shadow_rays, gather_cache_accuracy=cache_accuracy if gather else 0.0,
                  direct_emitter_area=chosen.direct_emitter_area, direct_emitters=chosen.direct_emitters)


def _matrix_bytes(core, exported, budget, **keywords):
    """The core's bound and planned bytes (plan's matrix_bytes_bound and matrix_bytes_planned: beyond
    the budget, estimated from a sample of F's rows rendered as the bake will render them) of F over
    the elements the bake will solve: with the lamps, beside which faces keep elements of their own."""
    planned = core.plan(*exported.scene_arrays(), front_only=exported.front_only, lights=exported.lights,
                        matrix_budget_bytes=budget, **keywords)
    return int(planned["matrix_bytes_bound"]), int(planned["matrix_bytes_planned"])


def warnings_for(choice):
    """Choices an artist made that will be slow, with what to do instead."""
    if choice.method in ("gauss_seidel", "jacobi") and choice.matrix_bytes_planned > choice.budget_bytes:
        return ["The form factors of %d elements may need %.0f MB, more than the memory budget (%.0f MB): "
                "every sweep renders every hemi-cube again, which is slow. Method Automatic would bake "
                "hierarchically instead (progressively with fog or smoke)"
                % (choice.elements, choice.matrix_bytes_planned / MEBIBYTE, choice.budget_bytes / MEBIBYTE)]
    return []
