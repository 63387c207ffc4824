"""The add-on's Blender-free layer (bake_radiosity.engine) in plain Python: settings chosen,
the core run, the result judged and put in words, on a closed box whose light is known exactly
(the furnace: L = E / (1 - rho) on every inner face; what its walls emit outwards, from their back
sides, leaves it, and everything they emit inwards is absorbed)."""
import dataclasses
import math
import sys
import unittest
import warnings

import numpy as np

from bake_radiosity.engine import auto_settings, energy, error_estimate, solve, summary
from bake_radiosity.engine.errors import BakeError
from bake_radiosity.engine.scene import ExportedScene

# The artist's settings as pipeline.settings_of gives them (scene.radiosity's defaults).
SETTINGS = {"quality": "MEDIUM", "method": "AUTO", "hemicube_resolution": 128, "element_size": 0.25,
            "tolerance": 1e-4, "refine_tolerance": 0.02, "max_iterations": 1000, "memory_budget": 2048,
            "hard_edge_angle": 0.5235988, "target": "ORIGINAL", "final_gather": True}


def closed_box(rho=0.6, emitted=2.0):
    """The six inward-facing sides of a 1 m cube, emitting from both sides as meshes do."""
    v = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0],
                  [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], dtype=np.float32)
    quads = [[0, 1, 2, 3], [4, 7, 6, 5], [0, 3, 7, 4], [1, 5, 6, 2], [0, 4, 5, 1], [3, 2, 6, 7]]
    faces = len(quads)
    return ExportedScene(positions=v, face_offsets=np.arange(0, 4 * faces + 1, 4, dtype=np.int32),
                         corner_vertices=np.array(quads, dtype=np.int32).ravel(),
                         reflectance=np.full((faces, 3), rho, dtype=np.float32),
                         emission=np.full((faces, 3), emitted, dtype=np.float32),
                         material=np.zeros(faces, dtype=np.int32), front_only=np.zeros(faces, dtype=np.uint8),
                         lights=[], parts=[])


def single_face(reflectance, emission):
    """One 1 m square, alone."""
    return ExportedScene(positions=np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=np.float32),
                         face_offsets=np.array([0, 4], dtype=np.int32), corner_vertices=np.arange(4, dtype=np.int32),
                         reflectance=np.full((1, 3), reflectance, dtype=np.float32),
                         emission=np.full((1, 3), emission, dtype=np.float32),
                         material=np.zeros(1, dtype=np.int32), front_only=np.zeros(1, dtype=np.uint8),
                         lights=[], parts=[])


def non_finite(value, path="summary"):
    """The paths of every float in `value` (dicts and lists within) that is NaN or infinite."""
    if isinstance(value, dict):
        return [p for key, item in value.items() for p in non_finite(item, "%s[%r]" % (path, key))]
    if isinstance(value, (list, tuple)):
        return [p for index, item in enumerate(value) for p in non_finite(item, "%s[%d]" % (path, index))]
    if isinstance(value, (float, np.floating)) and not math.isfinite(value):
        return [path]
    return []


def bake(scene, **overrides):
    settings = dict(SETTINGS, **overrides)
    choice = auto_settings.choose(settings, scene)
    return choice, solve.bake(scene, solve.core_settings(choice, settings, scene.lights))


class EngineTest(unittest.TestCase):
    def test_imports_no_blender(self):
        self.assertNotIn("bpy", sys.modules)

    def test_every_quality_and_method_meets_the_furnace(self):
        rho, emitted = 0.6, 2.0
        for overrides in ({"quality": "DRAFT"}, {"quality": "MEDIUM"}, {"quality": "DRAFT", "final_gather": False},
                          {"quality": "CUSTOM", "method": "HIERARCHICAL", "element_size": 0.25}):
            with self.subTest(**overrides):
                choice, result = bake(closed_box(rho, emitted), **overrides)
                np.testing.assert_allclose(result["corner_radiance"], emitted / (1.0 - rho), rtol=1e-2)
                self.assertTrue(result["converged"])

    def test_plan_gives_the_elements_the_bake_solves(self):
        scene = closed_box()
        choice = auto_settings.choose(SETTINGS, scene)
        keywords = solve.core_settings(choice, SETTINGS, scene.lights)
        planned, result = solve.plan(scene, keywords), solve.bake(scene, keywords)
        self.assertEqual(planned["elements"], result["elements"])
        np.testing.assert_array_equal(planned["element_vertices"], result["element_vertices"])
        self.assertEqual(planned["matrix_stored"], result["matrix_stored"])

    def test_summary_accounts_for_every_watt(self):
        choice, result = bake(closed_box())
        power = energy.balance(result)
        self.assertAlmostEqual(power.absorbed_fraction, 0.5, delta=1e-3)  # the inward half of the light
        self.assertEqual(power.created, 0.0)
        self.assertAlmostEqual(power.lost / power.emitted, 0.5, delta=1e-3)  # the back sides' half leaves
        line = summary.report_line({
            "elements": result["elements"], "method": choice.method, "gather_rays": choice.gather_rays,
            "iterations": result["iterations"], "residual": result["residual"], "converged": result["converged"],
            "seconds": dict(result["seconds"])})
        self.assertIn("%d elements" % result["elements"], line)
        self.assertIn("(converged)", line)

    def test_the_cost_line_names_what_the_bake_spent(self):
        # The core's counts and rays as the summary reads them, then the words an artist reads.
        choice, result = bake(closed_box())
        gather = summary.gather_cost(result["final_gather"])
        self.assertEqual(gather["points"] + gather["interpolated"] + gather["buried"], 24)
        self.assertEqual(list(gather["phases"]), ["field", "wedges", "probes", "points", "seams", "other"])
        self.assertGreater(gather["phases"]["points"]["rays"], 24 * choice.gather_rays)  # and shadow rays
        self.assertEqual(summary.gather_cost(None), None)
        line = summary.cost_line({
            "elements": 5556, "seconds": {"export": 0.21, "elements": 0.04, "form_factors": 7.94, "solve": 0.5,
                                          "gather": 12.06, "writeback": 0.3},
            "gather": {"points": 1204, "interpolated": 6240, "buried": 3, "phases": {
                "field": {"seconds": 2.0, "rays": 1_000_000}, "wedges": {"seconds": 0.8, "rays": 2_000_000},
                "probes": {"seconds": 0.3, "rays": 500_000}, "points": {"seconds": 7.2, "rays": 40_000_000},
                "seams": {"seconds": 1.74, "rays": 3_000_000}, "other": {"seconds": 0.02, "rays": 0}}}})
        self.assertEqual(
            line, "Cost: 5,556 elements; 1,204 output points gathered, 6,240 interpolated, 3 inside other geometry; "
                  "46.5 million rays; export 0.2 s, form factors 7.9 s, solve 0.5 s, final gather 12.1 s (field 2.0 "
                  "s, light around corners 0.8 s, probes 0.3 s, output points 7.2 s, near surfaces 1.7 s), "
                  "writeback 0.3 s")
        self.assertEqual(summary.cost_line({"elements": 24, "seconds": {"solve": 1.0}}),
                         "Cost: 24 elements; solve 1.0 s")
        # Small coplanar faces merged: the unknowns solved follow the elements.
        self.assertEqual(summary.cost_line({"elements": 27648, "solve_elements": 1728, "seconds": {"solve": 1.0}}),
                         "Cost: 27,648 elements (1,728 solved); solve 1.0 s")
        self.assertEqual(summary.cost_line({"elements": 24, "solve_elements": 24, "seconds": {"solve": 1.0}}),
                         "Cost: 24 elements; solve 1.0 s")

    def test_the_gathers_error_estimate_covers_the_furnaces_error(self):
        # Every inner corner's light is exactly E / (1 - rho); Medium gathers every corner.
        rho, emitted = 0.6, 2.0
        choice, result = bake(closed_box(rho, emitted))
        error = error_estimate.estimate(result)
        actual = np.sqrt(np.mean((result["corner_radiance"] @ error_estimate.LUMINANCE * (1 - rho) / emitted - 1) ** 2))
        self.assertEqual((error.source, error.relation), ("gather", "about"))
        # The walls all look alike, so the rays' sampling adds nothing, and the estimate says what
        # the furnace is: exact to well under 0.1%, within the estimate and the solve's bound.
        self.assertLess(error.sampling, 0.01 * error.typical)
        self.assertLess(actual, 1e-3)
        self.assertLess(error.typical, 1e-3)
        self.assertLessEqual(actual, error.typical + error.solve_bound)
        self.assertIn("Error about %.1f%% per corner (this bake's gather" % (100 * error.typical),
                      summary.error_text(dataclasses.asdict(error)))

    def test_light_created_from_nothing_is_a_share_of_its_own(self):
        # The furnace's radiance raised by 80%: its inner surfaces absorb more than both sides emitted.
        choice, result = bake(closed_box(), quality="DRAFT", final_gather=False)
        raised = dict(result, element_radiance=1.8 * result["element_radiance"])
        power = energy.balance(raised)
        self.assertGreater(power.absorbed, power.emitted)
        self.assertEqual(power.lost, 0.0)
        self.assertAlmostEqual(power.created, power.absorbed - power.emitted)
        text = summary.power_text(dataclasses.asdict(power) | {"lost": power.lost, "created": power.created})
        self.assertNotIn("-", text)
        self.assertIn("100.0%% absorbed, 0.0%% escaped or on black, and %.1f%% more absorbed than emitted"
                      % (100 * power.created / power.emitted), text)
        error = error_estimate.estimate(raised, power)
        self.assertEqual((error.relation, error.typical), ("at least", power.created / power.emitted))

    def test_an_emitter_among_black_surfaces_has_its_error_in_words_not_nan(self):
        # Nothing reflects light: the relative error of reflected light is 0 / 0, which the summary
        # once printed as "Error about nan% per corner". Alone, and inside a black box.
        panel = single_face(reflectance=0.0, emission=5.0)
        black_box = closed_box(rho=0.0, emitted=0.0)
        black_box.emission[1] = 5.0  # the lid emits, the other sides are black
        for name, scene in (("alone", panel), ("in a black box", black_box)):
            for overrides in ({}, {"final_gather": False}, {"quality": "CUSTOM", "method": "HIERARCHICAL"}):
                with self.subTest(name, **overrides):
                    with warnings.catch_warnings():
                        warnings.simplefilter("error")  # numpy's 0 / 0 RuntimeWarning fails the test
                        choice, result = bake(scene, **overrides)
                        error = dataclasses.asdict(error_estimate.estimate(result))
                        text = summary.error_text(error)
                    self.assertEqual((error["relation"], error["undefined"]),
                                     ("undefined", error_estimate.NO_REFLECTED_LIGHT))
                    self.assertIsNone(error["typical"])
                    self.assertEqual(non_finite(error), [])
                    self.assertIn("no reflected light to estimate from", text)
                    self.assertNotIn("nan", text.lower())
                    self.assertNotIn("inf", text.lower())

    def test_a_lit_scene_keeps_a_numeric_estimate(self):
        # A grey emitting box lights itself: its walls reflect, so the estimate is a number.
        choice, result = bake(closed_box(rho=0.5, emitted=1.0), quality="DRAFT")
        error = error_estimate.estimate(result)
        self.assertEqual(error.undefined, "")
        self.assertTrue(math.isfinite(error.typical) and error.typical > 0.0)

    def test_no_solve_bound_where_a_surface_reflects_everything(self):
        # rho_max = 1 makes the bound residual / (1 - rho_max) infinite: no bound, in words.
        choice, result = bake(closed_box(), quality="DRAFT", final_gather=False)
        reflecting_all = dict(result, element_reflectance=np.ones_like(result["element_reflectance"]))
        error = dataclasses.asdict(error_estimate.estimate(reflecting_all))
        self.assertIsNone(error["solve_bound"])
        self.assertEqual(non_finite(error), [])
        self.assertIn("no bound from the solve", summary.error_text(error))

    def test_bad_input_is_a_bake_error_naming_the_setting(self):
        scene = closed_box()
        choice = auto_settings.choose(SETTINGS, scene)
        keywords = dict(solve.core_settings(choice, SETTINGS, scene.lights), resolution=7)
        with self.assertRaisesRegex(BakeError, "resolution must be an even number"):
            solve.bake(scene, keywords)
        with self.assertRaisesRegex(TypeError, "unknown bake setting"):
            solve.bake(scene, dict(keywords, resolution=64, colour="red"))


if __name__ == "__main__":
    unittest.main()
