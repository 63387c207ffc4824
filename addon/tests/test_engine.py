"""The add-on's Blender-free layer (bake_radiosity.engine) in plain Python: settings chosen,
the core run, the result judged and put in words, on a closed box whose light is known exactly
(the furnace: L = E / (1 - rho) on every inner face; what its walls emit outwards, from their back
sides, leaves it, and everything they emit inwards is absorbed)."""
import sys
import unittest

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
        error = error_estimate.estimate(result, power, choice.gather_rays)
        line = summary.report_line({
            "elements": result["elements"], "method": choice.method, "gather_rays": choice.gather_rays,
            "iterations": result["iterations"], "residual": result["residual"], "converged": result["converged"],
            "seconds": dict(result["seconds"])})
        self.assertIn("%d elements" % result["elements"], line)
        self.assertIn("(converged)", line)
        self.assertGreater(error.discretisation, 0.0)

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
