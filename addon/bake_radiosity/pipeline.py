"""The bake pipeline: export (needs bpy) -> solve (no bpy, may run in a worker thread) ->
write back (needs bpy). `bake(scene, **overrides)` runs all three; the operator splits them."""

import dataclasses
import math
import time

import bpy

from . import export, facing, light_mix, linked, media_export, media_writeback, outliers, world, writeback
from .engine import auto_settings, bake_cache, energy, error_estimate, faces, light_groups, media_energy, solve
from .engine import summary as summary_lines
from .engine.errors import BakeError

SETTING_NAMES = ("quality", "method", "hemicube_resolution", "element_size", "tolerance", "refine_tolerance",
                 "max_iterations",
                 "memory_budget", "hard_edge_angle", "attribute_name", "target", "separate_linked_duplicates",
                 "final_gather", "write_light_only", "make_linked_local",
                 "zone_size", "media_folder", "light_group_layers")
# Naming one of these for a bake (and not the quality) asks for exactly that value: Custom quality.
CUSTOM_SETTING_NAMES = ("method", "hemicube_resolution", "element_size", "tolerance", "refine_tolerance")
QUALITIES = ("DRAFT", "MEDIUM", "HIGH", "CUSTOM")
TARGETS = ("ORIGINAL", "COPIES")


def settings_of(scene, overrides=None):
    """The scene's bake settings as a plain dict, with `overrides` (scene.radiosity names) applied."""
    overrides = dict(overrides or {})
    unknown = sorted(set(overrides) - set(SETTING_NAMES))
    if unknown:
        raise TypeError("unknown bake setting(s) %s; known: %s" % (", ".join(unknown), ", ".join(SETTING_NAMES)))
    settings = {name: getattr(scene.radiosity, name) for name in SETTING_NAMES}
    if "quality" not in overrides and any(name in overrides for name in CUSTOM_SETTING_NAMES):
        overrides["quality"] = "CUSTOM"
    settings.update(overrides)
    if settings["quality"] not in QUALITIES:
        raise TypeError("quality must be DRAFT, MEDIUM, HIGH or CUSTOM, got %r" % settings["quality"])
    if settings["method"] not in ("AUTO",) + tuple(auto_settings.CORE_METHODS):
        raise TypeError("method must be AUTO, GAUSS_SEIDEL, PROGRESSIVE, JACOBI or HIERARCHICAL, got %r"
                        % settings["method"])
    resolution = int(settings["hemicube_resolution"])
    if settings["quality"] == "CUSTOM" and not 16 <= resolution <= auto_settings.MAX_RESOLUTION:
        raise BakeError("Resolution must be between 16 and %d, got %s (the presets turn hemi-cubes about the normal "
                        "where a scene needs more)" % (auto_settings.MAX_RESOLUTION, settings["hemicube_resolution"]))
    if settings["target"] not in TARGETS:
        raise TypeError("target must be ORIGINAL or COPIES, got %r" % settings["target"])
    return settings


class BakeJob:
    """One bake: exported arrays, settings, and after `solve` the core's result."""

    def __init__(self, scene, depsgraph, view_layer, overrides=None, reuse=True):
        self.settings = settings_of(scene, overrides)
        self.reuse = reuse  # read and keep the session's bake cache (engine/bake_cache.py)
        with solve.core_errors_as_bake_errors():
            self._prepare(scene, depsgraph, view_layer)
            self.layers = self._light_group_layers(scene, view_layer)
        self.result = None

    def _light_group_layers(self, scene, view_layer):
        """The light groups' Layers this bake writes beside the usual attribute, or None (the option off,
        or a bake that cannot take them: then a warning says why)."""
        if not self.settings["light_group_layers"]:
            return None
        e, c = self.exported, self.choice
        world_group = getattr(scene.world, "lightgroup", "") if self.world_baked() else None
        layers = light_groups.layers_of(e.light_group_names, e.polygon_light_group, e.emission, e.lamp_light_groups,
                                        world_group, [g.name for g in getattr(view_layer, "lightgroups", ())])
        stored = c.method != "hierarchical" and c.matrix_bytes_planned <= c.budget_bytes
        refusal = light_groups.refusal(layers, c.method, bool(self.media.media), c.gather_rays > 0,
                                       c.matrix_bytes_planned if stored else 0, c.elements, len(e.corner_vertices),
                                       c.budget_bytes)
        if refusal:
            self.warnings.append(refusal)
            return None
        self.layer_bytes = light_groups.layer_bytes(len(layers.names), c.elements, len(e.corner_vertices))
        return layers

    def _prepare(self, scene, depsgraph, view_layer):
        start = time.perf_counter()
        announce("exporting view layer '%s'" % view_layer.name)
        self.exported = export.export_scene(depsgraph, view_layer)
        self.seconds_export = time.perf_counter() - start
        if self.exported.polygon_count == 0:
            raise BakeError("Nothing to bake: no mesh renders in view layer '%s'" % view_layer.name)
        # Before any work: light written where it is not saved would be lost.
        self.linked = linked.find(self.exported, self.settings)
        refusal = linked.refusal(self.linked, self.settings["make_linked_local"])
        if refusal:
            raise BakeError(refusal)
        self.far_polygons, far_warnings = outliers.leave_out_far_polygons(self.exported)
        self.warnings = list(self.exported.warnings) + far_warnings
        self.media = media_export.export_media(depsgraph, view_layer, float(self.settings["zone_size"]))
        self.warnings += self.media.warnings
        if self.media.media:
            unwritable = media_writeback.unwritable_reason(self.settings["media_folder"])
            if unwritable:
                raise BakeError(unwritable)
        self.world, world_warnings = world.export_world(scene)
        self.warnings += world_warnings
        if not self.exported.lights and not self.exported.emission.any() and not any(
                m.grid["emission"].any() for m in self.media.media) and self.world is None:
            # Said before any form factor is computed: the result could only be black.
            raise BakeError("Nothing lights the scene: no lamp, emitting material, emitting medium or World light "
                            "is visible in renders")
        announce("choosing settings for %d faces" % self.exported.polygon_count)
        try:
            self.choice = auto_settings.choose(self.settings, self.exported, [m.grid for m in self.media.media])
        except ValueError as error:
            raise BakeError(faces.name_faces(str(error), self.exported)) from error
        self.warnings += auto_settings.warnings_for(self.choice)
        if self.world is not None and not self.world_baked():
            if self.lit_by() == "nothing":
                raise BakeError("Only the World lights the scene, and its light is not baked with media (fog, "
                                "smoke) yet: add a lamp or an emitting mesh")
            self.warnings.append("The World's light is not baked with media (fog, smoke) yet: the result has no "
                                 "sky light; bake the surfaces without the Volume objects to see it")

    @property
    def method(self):
        return self.choice.method

    def solve(self, progress=None):
        """Runs the core. Touches no bpy data, so it may run in a worker thread."""
        keywords = self.core_settings()
        if self.layers is not None:
            keywords["layers"] = self.layers.keyword()
            if self.method == "hierarchical":  # its nodes and links take what the layers leave of the budget
                keywords["max_bytes"] = self.choice.budget_bytes - self.layer_bytes
        cache = bake_cache.session_cache(self.reuse)
        if cache is not None:
            keywords["cache"] = cache
        self.result = solve.bake(self.exported, keywords, progress)
        self._fill_skipped_corners()
        self.warnings += self._skipped_warnings()
        self.warnings += facing.turned_away_warnings(self.exported, self.result["corner_radiance"])
        hierarchy = self.result.get("hierarchy")
        if hierarchy and hierarchy["leaf_cap_reached"]:
            self.warnings.append("Refinement stopped at the element cap (%d elements) before the light was followed "
                                 "everywhere: raise Element Size or Refinement" % hierarchy["leaves"])
        if hierarchy and hierarchy["memory_cap_reached"]:
            self.warnings.append("Refinement stopped at the Memory Budget (%.0f MB of elements and links) before the "
                                 "light was followed everywhere: raise the Memory Budget, Element Size or Refinement"
                                 % (hierarchy["bytes"] / auto_settings.MEBIBYTE))
        return self.result

    def element_layout(self):
        """(element_vertices, element_corners, element_back) in the order progress reports radiance."""
        e = self.exported
        layout = solve.plan(e, self.core_settings())
        return layout["element_vertices"], layout["element_corners"], layout["element_back"]

    def core_settings(self):
        """The settings `_core.plan` and `_core.bake` take for this bake."""
        return solve.core_settings(self.choice, self.settings, self.exported.lights,
                                   world=self.world.radiance if self.world_baked() else None,
                                   media=[m.grid for m in self.media.media])

    def write(self, scene):
        """Writes the solved light into the file and returns the bake's summary."""
        start = time.perf_counter()
        announce("writing the light into the scene")
        media_files = []
        if self.media.media:  # files first: if one cannot be written, nothing in the scene has changed
            with solve.core_errors_as_bake_errors():
                media_files = media_writeback.write_files(self.media, self.result, self.settings["media_folder"])
        made_local = linked.make_local(self.exported, self.linked)
        if made_local:
            self.warnings.append(made_local)
        layer_names = self.layers.names if self.layers is not None else []
        self.warnings += writeback.write(scene, self.exported, self.result, self.settings, layer_names)
        light_mix.remember_layers(scene, self.settings["attribute_name"], layer_names)
        if self.media.media:
            media_writeback.load(scene, self.media, media_files)
        seconds_writeback = time.perf_counter() - start
        r, c = self.result, self.choice
        power = media_energy.balance(r) if self.media.media else energy.balance(r)
        error = error_estimate.estimate(r, power)
        summary = {
            "elements": r["elements"], "solve_elements": r.get("solve_elements", r["elements"]),
            "iterations": r["iterations"], "shots": r["shots"],
            "residual": r["residual"], "converged": r["converged"], "method": self.method,
            "quality": self.settings["quality"], "element_size": c.element_size, "resolution": c.resolution,
            "tolerance": c.tolerance, "scene_size": c.scene_size, "hemicube_rotations": c.hemicube_rotations,
            "resolution_reason": c.resolution_reason, "resolution_distance": c.resolution_distance,
            "near_field": c.near_field, "gather_rays": c.gather_rays,
            "matrix_stored": r["matrix_stored"], "matrix_bytes": r["matrix_bytes"],
            "matrix_bytes_bound": c.matrix_bytes_bound, "matrix_bytes_planned": c.matrix_bytes_planned,
            "memory_budget_bytes": c.budget_bytes,
            "energy": {"emitted": power.emitted, "absorbed": power.absorbed, "lost": power.lost,
                       "created": power.created, "leaving": power.leaving,
                       "absorbed_fraction": power.absorbed_fraction},
            "error_estimate": dataclasses.asdict(error),
            "zones": r.get("zones", 0), "zones_before_merge": r.get("zones_before_merge", 0),
            "zone_size": self.media.zone_size, "media_files": media_files,
            "hierarchy": r.get("hierarchy"), "refine_tolerance": c.refine_tolerance,
            "world": self.world_summary(), "lit_by": self.lit_by(), "light_layers": self.layers_summary(),
            "gather": summary_lines.gather_cost(r.get("final_gather")), "cache": r.get("cache"),
            "warnings": list(self.warnings),
            # Every phase, so that their sum is the whole bake's time.
            "seconds": {"export": self.seconds_export, "world_map": self.world.seconds if self.world else 0.0,
                        **r["seconds"], "writeback": seconds_writeback},
        }
        scene.radiosity.last_report = summary_lines.report_line(summary)
        scene.radiosity.last_accuracy = summary_lines.accuracy_line(summary)
        scene.radiosity.last_cost = summary_lines.cost_line(summary)
        return summary

    def layers_summary(self):
        """The light group layers written: their groups and memory against the budget; None without."""
        if self.layers is None:
            return None
        return {"groups": list(self.layers.names), "bytes": self.layer_bytes,
                "attributes": [light_groups.attribute_name(self.settings["attribute_name"], g)
                               for g in self.layers.names]}

    def world_baked(self):
        return self.world is not None and not self.media.media

    def world_summary(self):
        """The World's light as baked: its name, whether Cycles rendered it, its map size; None if none."""
        if not self.world_baked():
            return None
        height, width = self.world.radiance.shape[:2]
        return {"name": self.world.name, "rendered": self.world.rendered, "width": width, "height": height,
                "description": self.world.describe()}

    def lit_by(self):
        """What lights the bake, in words: lamps, emitting surfaces and media, the World."""
        e = self.exported
        sources = []
        if e.lights or e.emission.any() or any(m.grid["emission"].any() for m in self.media.media):
            sources.append("lamps and emitters")
        if self.world_baked():
            sources.append("the World")
        if sources == ["the World"]:
            return "the World only"
        return " and ".join(sources) or "nothing"

    def _fill_skipped_corners(self):
        """Skipped faces carry no light; their corners show that of the faces around them."""
        skipped = [polygon for polygon, _ in self.result["skipped"]]
        for result in [self.result] + self.result.get("layers", []):
            for key in ("corner_radiance", "corner_light"):
                if key in result:
                    result[key] = faces.fill_skipped_corners(result[key], self.exported, skipped)

    def _skipped_warnings(self):
        skipped = [(polygon, reason) for polygon, reason in self.result["skipped"]
                   if polygon not in self.far_polygons]  # named already, as far away
        warning = faces.skipped_warning(skipped, self.exported)
        return [warning] if warning else []


def view_layer_and_depsgraph(scene):
    context = bpy.context
    if context.scene == scene:
        return context.view_layer, context.evaluated_depsgraph_get()
    view_layer = scene.view_layers[0]
    view_layer.update()  # makes its depsgraph when the scene was never shown (a batch bake's other scenes)
    return view_layer, view_layer.depsgraph


def announce(text):
    """Prints a phase the add-on runs itself, in the core's progress lines' form, when Blender runs
    without a window (-b and the batch command); a window shows phases in its status bar."""
    if bpy.app.background:
        print("Bake Radiosity: " + text, flush=True)


class ProgressPrinter:
    """Prints a progress line as each phase starts and ends, and at most every `interval` seconds
    between (for -b and the command line)."""

    def __init__(self, tolerance, interval=1.0):
        self.tolerance = tolerance
        self.interval = interval
        self.last = -math.inf
        self.phase = None

    def __call__(self, info):
        now = time.perf_counter()
        if now - self.last >= self.interval or info["done"] == info["total"] or info["phase"] != self.phase:
            self.last, self.phase = now, info["phase"]
            print(summary_lines.progress_text(info, self.tolerance), flush=True)
        return True


def bake(scene, reuse=True, **overrides):
    """Bakes `scene` now and returns a summary dict: elements, iterations, residual, converged,
    method and the settings chosen (quality, element_size, resolution, hemicube_rotations and
    resolution_reason, near_field, tolerance, matrix memory), the World's light baked (world: name,
    rendered, width, height, description; None when none) and what lights the bake (lit_by), the
    light group layers written (light_layers: groups, bytes, attributes; None without),
    energy (watts emitted, absorbed, lost, created), error_estimate (the typical relative error per
    corner, its relation and source, its parts from the gather: sampling, the solution's bias and the
    field's light; the solve's bound), warnings, and seconds per phase (export, form_factors, solve,
    writeback), and what it did with the session's bake cache (cache: reused, kept, bytes,
    direct_bytes (of bytes, the gather's direct light kept per lamp and emitter), merged_again (reused, the
    faces beside moved lamps merged anew and their form factors computed again), not_reused, not_kept;
    None with reuse=False).

    `reuse` (default True): a bake of the same geometry as the session's previous bake (only lamps,
    the World, emission strengths or material colours changed) reuses its elements, form factors and
    the final gather's rays and gives the colours a bake from scratch gives; each bake keeps its own
    for the next, within the Memory Budget (engine/bake_cache.py). reuse=False bakes from scratch
    and lets go of what the cache held.

    `overrides` take any scene.radiosity setting by name for this bake only, e.g.
    bake(scene, quality="HIGH") or bake(scene, element_size=0.05, method="PROGRESSIVE"); naming
    method, hemicube_resolution, element_size or tolerance without a quality means CUSTOM.
    make_linked_local=True gives objects whose meshes are linked from another file (or library
    overrides of such) local meshes to hold their light; without it such a bake raises BakeError
    naming them before any work, since linked data is not saved with the file.
    """
    view_layer, depsgraph = view_layer_and_depsgraph(scene)
    job = BakeJob(scene, depsgraph, view_layer, overrides, reuse=reuse)
    job.solve(progress=ProgressPrinter(job.choice.tolerance) if bpy.app.background else None)
    return job.write(scene)
