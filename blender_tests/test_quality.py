"""The artist's Quality setting and the Automatic method, through the panel's properties, the
operator and the command line; and the bake's summary (residual, energy balance, error estimate)
against the furnace's exact answer."""

import dataclasses
import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402
import numpy as np  # noqa: E402

import harness  # noqa: E402
import scenes  # noqa: E402

args = harness.arguments()
addon = harness.install_addon(args.addon_zip)
pipeline = sys.modules[harness.MODULE + ".pipeline"]
auto_settings = sys.modules[harness.MODULE + ".engine.auto_settings"]
ui = sys.modules[harness.MODULE + ".ui"]

# The presets as the user guide documents them: (element size as a fraction of the scene's size,
# hemi-cube cells the smallest elements must cover, tolerance).
# (element size as a share of the scene's size, cells, tolerance) with the final gather (the default)
# and without it.
DOCUMENTED_PRESETS = {"DRAFT": (1 / 16, 4, 1e-3), "MEDIUM": (1 / 16, 4, 1e-4), "HIGH": (1 / 32, 4, 1e-5)}
UNGATHERED_PRESETS = {"DRAFT": (1 / 16, 4, 1e-3), "MEDIUM": (1 / 32, 6, 1e-4), "HIGH": (1 / 48, 8, 1e-5)}


def surface_area(obj):
    areas = np.empty(len(obj.data.polygons))
    obj.data.polygons.foreach_get("area", areas)
    return areas.sum()


def job_for(scene):
    view_layer, depsgraph = pipeline.view_layer_and_depsgraph(scene)
    return pipeline.BakeJob(scene, depsgraph, view_layer)


def even_resolution(distance, area, cells):
    """docs/stability.md: the resolution at which `area` seen head-on from `distance` covers `cells`
    cells, N = 2 d sqrt(cells / A), rounded up to even."""
    return 2 * math.ceil(distance * math.sqrt(cells / area))


def test_presets_map_to_settings():
    scenes.clear_scene()
    box = scenes.cornell_box("MESH")
    # The scene's size is the side of the cube with the same surface area (Blender's own areas).
    size = math.sqrt(surface_area(box) / 6)
    settings = bpy.context.scene.radiosity
    assert settings.quality == "MEDIUM" and settings.final_gather, "an artist starts from Medium, gathered"
    presets = [(quality, True, preset) for quality, preset in DOCUMENTED_PRESETS.items()]
    presets += [(quality, False, preset) for quality, preset in UNGATHERED_PRESETS.items()]
    for quality, gathered, (fraction, cells, tolerance) in presets:
        settings.quality, settings.final_gather = quality, gathered
        choice = job_for(bpy.context.scene).choice
        assert (choice.gather_rays > 0) == gathered, choice
        print("%s: element size %.5f (scene size %.4f), resolution %d (%s), tolerance %g, %d elements, %s"
              % (quality, choice.element_size, size, choice.resolution, choice.resolution_reason, choice.tolerance,
                 choice.elements, choice.method))
        assert abs(choice.element_size - fraction * size) < 1e-6 * size, choice
        # The walls' faces (1/8 m) split into whole elements, the smallest holding a tenth of the area among
        # them; seen from half the 1 m cube's diagonal.
        face = 1 / scenes.CORNELL_CELLS
        wall_element = face / math.ceil(face / choice.element_size)
        resolution = max(32, even_resolution(0.5 * math.sqrt(3), wall_element ** 2, cells))  # the core's least
        assert (choice.resolution, choice.hemicube_rotations, choice.tolerance, choice.method) == (
            resolution, 1, tolerance, "gauss_seidel"), (choice, resolution)
        reason = "smallest elements holding a tenth of their area cover %d cells" % cells
        assert reason in choice.resolution_reason, choice
        # About 6 / fraction^2 elements whatever the shape (faces split into whole elements: more).
        assert 6 / fraction ** 2 <= choice.elements <= 1.3 * 6 / fraction ** 2, choice.elements

    # Setting one of the individual values (as a script would) means Custom, and Custom uses them.
    settings.quality, settings.final_gather = "DRAFT", True
    settings.element_size = 0.1
    assert settings.quality == "CUSTOM"
    settings.hemicube_resolution, settings.tolerance, settings.method = 97, 2e-3, "JACOBI"
    choice = job_for(bpy.context.scene).choice
    assert (choice.element_size, choice.resolution, choice.tolerance, choice.method) == (
        np.float32(0.1), 98, np.float32(2e-3), "jacobi"), choice


def test_automatic_method_follows_the_memory_budget():
    scenes.clear_scene()
    box = scenes.cornell_box("MESH", cells=4)
    settings = bpy.context.scene.radiosity
    settings.quality = "CUSTOM"
    settings.method, settings.element_size, settings.hemicube_resolution = "AUTO", 0.0625, 32
    settings.tolerance = 1e-4
    settings.final_gather = False  # the two solutions compared as they are, not the gather's corners
    elements = job_for(bpy.context.scene).choice.elements
    # The core's bound, computed here independently: n rows of min(n, 3 N^2) float + int32 entries.
    bound = elements * min(elements, 3 * 32 ** 2) * 8
    fits_mb = math.ceil(bound / 2 ** 20)

    settings.memory_budget = fits_mb
    assert bpy.ops.radiosity.bake() == {"FINISHED"}
    assert "Gauss-Seidel" in settings.last_report, settings.last_report
    stored = harness.corner_colors(box.data, "Radiosity")
    actual = addon.bake(bpy.context.scene)["matrix_bytes"]  # the matrix the bake stored
    # Under the bound but over the stored matrix (the box is open at the front: rows see part of it),
    # the core's estimate from sampled rows (at most 1.25 times the matrix, test_matrix_estimate.cpp)
    # still stores it; under the matrix itself, the estimate (never under it) does not.
    between_mb, too_small_mb = math.ceil(1.25 * actual / 2 ** 20), math.floor(actual / 2 ** 20) - 1
    assert between_mb < math.floor(bound / 2 ** 20) and too_small_mb >= 1, (actual, bound)
    settings.memory_budget = between_mb
    assert bpy.ops.radiosity.bake() == {"FINISHED"}
    assert "Gauss-Seidel" in settings.last_report, settings.last_report
    assert np.allclose(harness.corner_colors(box.data, "Radiosity"), stored, rtol=1e-6, atol=0), "another solve"

    settings.memory_budget = too_small_mb
    assert bpy.ops.radiosity.bake() == {"FINISHED"}
    assert "hierarchical" in settings.last_report and "NOT" not in settings.last_report, settings.last_report
    assert "leaves" in settings.last_report and "links" in settings.last_report, settings.last_report
    summary = addon.bake(bpy.context.scene)
    assert summary["method"] == "hierarchical" and not summary["matrix_stored"] and summary["converged"], summary
    assert summary["hierarchy"]["leaves"] <= summary["elements"], summary["hierarchy"]
    hierarchical = harness.corner_colors(box.data, "Radiosity")
    # Another discretisation of the same scene (elements where the light needs them, links between
    # groups): close to the stored solve, not equal (docs/hierarchy.md).
    difference = np.sqrt(np.mean((hierarchical - stored) ** 2)) / np.sqrt(np.mean(stored ** 2))
    print("%d elements, bound %d bytes, stored %d bytes; budget %d and %d MB: Gauss-Seidel; %d MB: hierarchical "
          "(%d leaves), %.2f%% RMS from the stored solve"
          % (elements, bound, actual, fits_mb, between_mb, too_small_mb, summary["hierarchy"]["leaves"],
             100 * difference))
    assert 0 < difference < 0.05

    # The batch command takes the same budget.
    path = os.path.join(args.work, "budget.blend")
    bpy.ops.wm.save_as_mainfile(filepath=path)
    run = subprocess.run(harness.batch_command(path, "--output", path, "--memory-budget", str(fits_mb)),
                         capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr
    assert "Gauss-Seidel" in run.stdout and "Power" in run.stdout, run.stdout


class RecordingLayout:
    """Stands in for Blender's UILayout (there is none with -b): records what the panel draws and
    fails on a property the settings do not have."""

    def __init__(self, drawn):
        self.drawn = drawn

    def __getattr__(self, name):  # row, column, box: nested layouts into the same record
        return lambda *args, **kwargs: RecordingLayout(self.drawn)

    def prop(self, data, name, **_):
        assert name in data.bl_rna.properties, name
        self.drawn.append(name)

    def label(self, text="", **_):
        self.drawn.append(text)

    def operator(self, name, **_):
        self.drawn.append(name)


def drawn_panel():
    drawn = []
    ui.draw_panel(RecordingLayout(drawn), bpy.context)
    return drawn


def test_panel_shows_quality_and_summary():
    settings = bpy.context.scene.radiosity
    settings.quality = "MEDIUM"
    drawn = drawn_panel()
    assert "quality" in drawn and "memory_budget" in drawn and "element_size" not in drawn, drawn
    assert "Elements 1/32 of the scene, resolution from the scene (6 cells), near field, tolerance 0.0001, " \
           "refinement 0.02" in drawn, drawn
    settings.quality = "CUSTOM"
    drawn = drawn_panel()
    for name in ("method", "element_size", "hemicube_resolution", "tolerance", "max_iterations"):
        assert name in drawn, (name, drawn)
    # After a bake (test_summary_on_the_furnace) the summary's parts are one line each.
    assert settings.last_report in drawn and settings.last_accuracy, drawn
    for part in settings.last_accuracy.split("; "):
        assert part in drawn, (part, drawn)


def test_summary_on_the_furnace():
    rho, emitted = 0.5, 1.0
    scenes.clear_scene()
    scenes.furnace_box(rho, emitted, cells=4)
    settings = bpy.context.scene.radiosity
    settings.element_size, settings.hemicube_resolution, settings.method = 0.125, 64, "GAUSS_SEIDEL"
    # A loose tolerance, so that the solve's error is large enough to compare with its bound. Half
    # of 1e-2 since the walls emit from both sides: their back sides double |E| (not the fronts'
    # error), so this leaves the fronts as far from converged as 1e-2 did with one side.
    settings.tolerance = 5e-3
    # Plain Gauss-Seidel, whose residual keeps its sign (below); over-relaxation overshoots.
    with harness.patched_setting("AUTOMATIC_OVER_RELAXATION", 1.0):
        job = job_for(bpy.context.scene)
        radiance = job.solve()["element_radiance"]
    summary = job.write(bpy.context.scene)
    power, estimate = summary["energy"], summary["error_estimate"]
    # A Lambertian surface of radiance L and area A sends pi L A watts; the box's area is 6. Its
    # walls emit from both sides (as in Cycles): the back sides face out, and what they send,
    # pi 6 emitted, leaves the box.
    outward = math.pi * 6 * emitted
    exact_emitted, exact_leaving = 2 * outward, math.pi * 6 * emitted / (1 - rho) + outward
    print("furnace: residual %.3g, emitted %.6f W (exact %.6f), absorbed %.6f W, leaving %.6f W (exact %.6f), "
          "solve bound %.4g" % (summary["residual"], power["emitted"], exact_emitted, power["absorbed"],
                                power["leaving"], exact_leaving, estimate["solve_bound"]))
    assert abs(power["emitted"] / exact_emitted - 1) < 1e-6
    # Closed and nothing black inside: what is not absorbed is what the back sides send out and
    # what the solve left. With residual r = E - (I - rho F) L and rows summing to 1 (the back
    # sides' rows are empty and their r is 0), emitted - outward - absorbed = pi sum A r / rho, and
    # Gauss-Seidel from zero leaves r >= 0: that share is the relative residual over rho.
    expected_lost = summary["residual"] / rho * power["emitted"]
    assert abs((power["lost"] - outward) / expected_lost - 1) < 0.01, (power["lost"], outward, expected_lost)
    assert abs(power["leaving"] / exact_leaving - 1) <= estimate["solve_bound"]

    # The solve's bound holds, and in the furnace it is nearly tight (L is nearly uniform), on the
    # baked light: the walls' fronts (the back sides are not written).
    error = np.abs(radiance[~job.result["element_back"]] / (emitted / (1 - rho)) - 1).mean()
    print("furnace: mean relative error %.4g, bound %.4g" % (error, estimate["solve_bound"]))
    assert 0.5 * estimate["solve_bound"] <= error <= estimate["solve_bound"], error

    # The panel's line says the same, in numbers computed here from the residual alone.
    report = settings.last_accuracy
    assert report.startswith("Residual %.1e" % summary["residual"]), report
    # Half the power is the back sides', which leaves the box.
    assert "%.1f%% absorbed" % (100 * (0.5 - summary["residual"] / rho)) in report, report
    # |E| / |L| = 2 (1 - rho) in the furnace (|E| counts both sides of the walls, |L| the baked
    # fronts), so the solve's bound is twice the residual.
    assert abs(estimate["solve_bound"] / (2 * summary["residual"]) - 1) < 0.01, estimate
    assert "under %.2g%% from the solve's residual" % (100 * estimate["solve_bound"]) in report, report


def test_over_relaxation_near_rho_one():
    # Draft, as an artist would bake a bright white room: the core's automatic omega against plain
    # Gauss-Seidel (over_relaxation 1), same tolerance, same answer.
    rho, emitted = 0.95, 1.0
    scenes.clear_scene()
    box = scenes.furnace_box(rho, emitted, cells=4)
    bpy.context.scene.radiosity.quality = "DRAFT"
    # The default budget (an earlier test may leave a small one), which stores F for the walls and
    # their back sides (the walls emit: two-sided).
    bpy.context.scene.radiosity.memory_budget = 2048
    with harness.patched_setting("AUTOMATIC_OVER_RELAXATION", 1.0):
        plain = addon.bake(bpy.context.scene)
    plain_colors = harness.corner_colors(box.data, "Radiosity")
    sor = addon.bake(bpy.context.scene)
    sor_colors = harness.corner_colors(box.data, "Radiosity")
    exact = emitted / (1 - rho)
    # The solve's bound is on the mean (area-weighted) error; the corners of this grid weigh alike.
    plain_error, sor_error = (np.abs(c / exact - 1).mean() for c in (plain_colors, sor_colors))
    bounds = plain["error_estimate"]["solve_bound"], sor["error_estimate"]["solve_bound"]
    print("furnace rho %.2f, Draft, %d elements: Gauss-Seidel %d sweeps (%.3f s, mean corner error %.2e, "
          "bound %.2e), over-relaxed %d sweeps (%.3f s, %.2e, bound %.2e)" % (
              rho, sor["elements"], plain["iterations"], plain["seconds"]["solve"], plain_error, bounds[0],
              sor["iterations"], sor["seconds"]["solve"], sor_error, bounds[1]))
    assert plain["method"] == sor["method"] == "gauss_seidel" and plain["converged"] and sor["converged"]
    assert sor["iterations"] < plain["iterations"] / 2, (sor["iterations"], plain["iterations"])
    # Both within their own solve bound of the exact answer, so within the two bounds of each other.
    assert plain_error <= bounds[0] and sor_error <= bounds[1], (plain_error, sor_error, bounds)
    assert np.abs(sor_colors - plain_colors).mean() / exact <= sum(bounds)


def point_to_polygon(points, normal, polygon):
    """Lambert's contour integral: the unoccluded form factor from a differential area at each of
    `points` (unit normal `normal`) to the convex polygon with corners `polygon` in order."""
    r = polygon[None, :, :] - points[:, None, :]
    r_next = np.roll(r, -1, axis=1)
    cross = np.cross(r, r_next)
    angle = np.arctan2(np.linalg.norm(cross, axis=2), (r * r_next).sum(axis=2))
    unit = cross / np.linalg.norm(cross, axis=2, keepdims=True)
    return np.abs((angle * (unit @ normal)).sum(axis=1)) / (2 * math.pi)


def floor_error(obj, lamp, rho, radiance):
    """Relative RMS of the floor's baked corners against their direct light from the lamp."""
    corners = harness.corner_positions(obj.data)
    on_floor = corners[:, 2] == 0.0
    exact = rho * radiance * point_to_polygon(corners[on_floor], np.array([0.0, 0.0, 1.0]), lamp)
    baked = harness.corner_colors(obj.data, "Radiosity")[on_floor]
    return math.sqrt(np.mean((baked - exact[:, None]) ** 2)) / math.sqrt(np.mean(exact ** 2))


LAMP_HEIGHT, FLOOR_RHO, LAMP_RADIANCE = 1.5, 0.5, 1000.0
# Half the diagonal of the 2 x 2 x 1.5 m scene: where recommended_resolution sees the lamp from.
LAMP_SCENE_HALF_DIAGONAL = 0.5 * math.sqrt(2 ** 2 + 2 ** 2 + LAMP_HEIGHT ** 2)


def test_small_distant_lamp_is_lit_directly():
    # A 2 cm lamp 1.5 m over a floor. Draft's elements (5 cm) are all larger; a hemi-cube at
    # their resolution sees the lamp as a fraction of a cell, so each floor element would catch it in
    # one cell or miss it. The lamp's elements light the floor directly instead (analytic factors
    # and shadow rays), and the resolution stays the elements' own.
    side = 0.02
    scenes.clear_scene()
    obj, lamp = scenes.small_lamp_over_floor(side, LAMP_HEIGHT, FLOOR_RHO, LAMP_RADIANCE)
    settings = bpy.context.scene.radiosity
    settings.quality = "DRAFT"
    # What the solve does with the lamp: the final gather would light the corners from the lamp
    # itself, whatever the hemi-cubes caught of it.
    settings.final_gather = False
    choice = job_for(bpy.context.scene).choice
    resolution = choice.resolution
    assert resolution < even_resolution(LAMP_SCENE_HALF_DIAGONAL, side ** 2, 4), choice
    assert choice.direct_emitters == 2, choice  # the lamp's two sides
    assert bpy.ops.radiosity.bake() == {"FINISHED"}
    direct = floor_error(obj, lamp, FLOOR_RHO, LAMP_RADIANCE)
    reason = "Hemi-cube resolution %d: the smallest elements holding a tenth of their area cover 4 cells from " \
             "half the scene's diagonal; 2 small emitting elements light the scene directly" % resolution
    assert reason in settings.last_accuracy, settings.last_accuracy
    element_size = choice.element_size

    # The same elements and resolution through the hemi-cube alone (Custom lights nothing directly).
    settings.quality = "CUSTOM"
    settings.element_size, settings.hemicube_resolution, settings.tolerance = element_size, resolution, 1e-3
    assert bpy.ops.radiosity.bake() == {"FINISHED"}
    hemicube = floor_error(obj, lamp, FLOOR_RHO, LAMP_RADIANCE)
    print("2 cm lamp at 1.5 m, Draft at resolution %d: %.2f%% RMS against the direct light lit directly, "
          "%.1f%% through the hemi-cube" % (resolution, 100 * direct, 100 * hemicube))
    assert direct < 0.01 and hemicube > 0.2, (direct, hemicube)

    # The batch command chooses and reports the same.
    path = os.path.join(args.work, "small_lamp.blend")
    settings.quality = "MEDIUM"
    bpy.ops.wm.save_as_mainfile(filepath=path)
    run = subprocess.run(harness.batch_command(path, "--output", path, "--quality", "DRAFT"),
                         capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr
    assert reason in run.stdout, run.stdout


def test_tiny_lamp_past_the_cap_adds_rotations():
    # A 5 mm lamp would need resolution 1281 for Draft's 4 cells. Lit directly, it needs none of
    # that; when the pairs it would light are over the budget, it sets the resolution: capped at
    # 1024, hemi-cubes turned about the normal make up for it: (1281 / 1024)^2.8 = 1.9, so 2
    # (docs/accuracy.md).
    side = 0.005
    scenes.clear_scene()
    obj, lamp = scenes.small_lamp_over_floor(side, LAMP_HEIGHT, FLOOR_RHO, LAMP_RADIANCE)
    bpy.context.scene.radiosity.quality = "DRAFT"
    needed = 2 * LAMP_SCENE_HALF_DIAGONAL * math.sqrt(4 / side ** 2)
    rotations = math.ceil((needed / 1024) ** 2.8)
    direct = addon.bake(bpy.context.scene)
    direct_error = floor_error(obj, lamp, FLOOR_RHO, LAMP_RADIANCE)
    assert direct["resolution"] < 1024 and direct["hemicube_rotations"] == 1, direct
    with harness.patched_setting("DIRECT_EMITTER_PAIRS", 0):
        choice = job_for(bpy.context.scene).choice
        assert (choice.resolution, choice.hemicube_rotations, rotations) == (1024, 2, 2), (choice, needed)
        summary = addon.bake(bpy.context.scene)
    error = floor_error(obj, lamp, FLOOR_RHO, LAMP_RADIANCE)
    for name, s, e in (("lit directly", direct, direct_error), ("through the hemi-cube", summary, error)):
        print("5 mm lamp at 1.5 m, Draft, %s: resolution %d x %d rotations (%s), %.1f%% RMS against the direct "
              "light, %.1f s" % (name, s["resolution"], s["hemicube_rotations"], s["resolution_reason"], 100 * e,
                                 sum(s["seconds"].values())))
    assert summary["hemicube_rotations"] == 2 and "capped at 1024" in summary["resolution_reason"], summary
    assert error < 0.15, error
    assert direct_error < 0.01, direct_error


def cycles_corners(obj, samples, seed):
    """Cycles' Combined bake of `obj` to a corner colour attribute, unbiased (harness)."""
    harness.use_unbiased_cycles(samples, seed)
    bpy.context.scene.render.bake.target = "VERTEX_COLORS"
    attributes = obj.data.color_attributes
    name = "Cycles %d" % seed
    attributes.active_color = attributes.new(name, "FLOAT_COLOR", "CORNER")
    obj.select_set(True)
    bpy.context.view_layer.objects.active = obj
    assert bpy.ops.object.bake(type="COMBINED", target="VERTEX_COLORS") == {"FINISHED"}
    return harness.corner_colors(obj.data, name)


def test_near_field_at_medium_and_high():
    # A slab 5 mm over a floor, its 3 cm Medium elements six times the gap. Against Cycles (two
    # halves of 8192 samples; their noise taken out), on the corners under and around the slab
    # and on its underside: with the near-field correction Medium's error falls from 7.5% to 5.6%
    # RMS (docs/accuracy.md). Draft leaves it off (there it made this slab worse).
    gap = 0.005
    scenes.clear_scene()
    obj = scenes.slab_over_floor(gap)
    around = scenes.under_and_around_slab(harness.corner_positions(obj.data), gap)
    halves = [cycles_corners(obj, 8192, seed)[around] for seed in (1, 2)]
    truth = 0.5 * (halves[0] + halves[1])

    def error(values):
        noise = np.sqrt(np.mean((halves[0] - halves[1]) ** 2)) / 2
        return math.sqrt(max(np.mean((values - truth) ** 2) - noise ** 2, 0.0)) / np.sqrt(np.mean(truth ** 2))

    settings = bpy.context.scene.radiosity
    assert not auto_settings.PRESETS["DRAFT"].near_field
    # The near-field correction is part of the presets' own solutions, written without the gather.
    settings.quality, settings.final_gather = "MEDIUM", False
    settings.memory_budget = settings.bl_rna.properties["memory_budget"].default  # stored factors fit
    assert bpy.ops.radiosity.bake() == {"FINISHED"}
    assert "Gauss-Seidel" in settings.last_report, settings.last_report
    assert "Hemi-cube resolution %d, near field:" % job_for(bpy.context.scene).choice.resolution \
        in settings.last_accuracy, settings.last_accuracy
    corrected = error(harness.corner_colors(obj.data, "Radiosity")[around])
    without = {name: dataclasses.replace(preset, near_field=False) for name, preset in auto_settings.PRESETS.items()}
    with harness.patched_setting("PRESETS", without):
        summary = addon.bake(bpy.context.scene)
    assert not summary["near_field"], summary
    plain = error(harness.corner_colors(obj.data, "Radiosity")[around])
    print("slab %g m over the floor, Medium: %.2f%% RMS against Cycles around the slab with the near-field "
          "correction, %.2f%% without" % (gap, 100 * corrected, 100 * plain))
    assert corrected < 0.06 and plain > 0.07, (corrected, plain)


def test_thin_quads_are_cut():
    # A strip 1 m long and 2 mm wide under an emitting square: Draft's elements (1/16 of the
    # scene's size, 2.6 cm) would be 13 times longer than wide there; cut to at most 4.
    width = 0.002
    width_float32 = float(np.float32(0.5 + width) - np.float32(0.5))  # as the core measures it
    scenes.clear_scene()
    scenes.mesh_object("Sliver", [
        scenes.grid((0, 0, 1), (0, 1, 0), (1, 0, 0), 1, 1) + (1,),        # emitter, facing down
        scenes.grid((0, 0.5, 0), (1, 0, 0), (0, width, 0), 1, 1) + (0,),  # the strip, facing up
    ], [scenes.diffuse("White", (0.8, 0.8, 0.8)), scenes.emission("Light", (1, 1, 1), 1.0)])
    bpy.context.scene.radiosity.quality = "DRAFT"
    with harness.patched_setting("MAX_ELEMENT_ASPECT", 0.0):
        kept = addon.bake(bpy.context.scene)
    cut = addon.bake(bpy.context.scene)
    along = math.ceil(1 / cut["element_size"])  # the strip's elements along it, before the cut
    print("sliver %.3f m wide, element size %.4f m: %d elements, %d with the aspect limit" % (
        width, cut["element_size"], kept["elements"], cut["elements"]))
    assert cut["elements"] - kept["elements"] == math.ceil(1 / (4 * width_float32)) - along, (kept, cut)
    assert cut["converged"] and not cut["warnings"], cut


def test_an_l_shaped_rug_does_not_set_the_resolution():
    # A 6-corner L-shaped rug (1.2 m and 0.4 m arms, 0.4 m wide) on the floor of the 2 m room: its
    # convex pieces are cut at about the preset's element size, so the resolution, the element count
    # and the time stay about the room's own (ear triangles cut by one count for all: 1,600 rug
    # elements and resolution 426 at Medium, the bake 5 times as long).
    scenes.clear_scene()
    scenes.cluttered_room(0)
    settings = bpy.context.scene.radiosity
    settings.quality = "MEDIUM"
    without = job_for(bpy.context.scene).choice
    z = 0.005
    outline = np.array([(0.4, 0.4, z), (1.6, 0.4, z), (1.6, 0.8, z), (0.8, 0.8, z), (0.8, 1.6, z), (0.4, 1.6, z)])
    rug = scenes.mesh_object("Rug", [(outline, np.arange(6)[None, :], 0)], [scenes.diffuse("Red", (0.6, 0.1, 0.1))])
    rug_area = 1.2 * 0.4 + 0.4 * 0.8
    choice = job_for(bpy.context.scene).choice
    squares = math.ceil(rug_area / choice.element_size ** 2)
    print("L-shaped rug at Medium: resolution %d (%d without it), %d elements (%d without it; the rug's area is %d "
          "element squares)" % (choice.resolution, without.resolution, choice.elements, without.elements, squares))
    assert choice.resolution == without.resolution, (choice, without)
    assert choice.elements - without.elements <= 2 * squares, (choice, without)
    assert bpy.ops.radiosity.bake() == {"FINISHED"}
    colors = harness.corner_colors(rug.data, "Radiosity")
    assert np.isfinite(colors).all() and colors[:, 0].min() > 0.0, colors


harness.run(test_presets_map_to_settings, test_automatic_method_follows_the_memory_budget, test_summary_on_the_furnace,
            test_panel_shows_quality_and_summary, test_over_relaxation_near_rho_one,
            test_small_distant_lamp_is_lit_directly, test_tiny_lamp_past_the_cap_adds_rotations,
            test_near_field_at_medium_and_high, test_thin_quads_are_cut,
            test_an_l_shaped_rug_does_not_set_the_resolution)
