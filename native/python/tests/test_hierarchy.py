"""Tests of `_core.bake(method="hierarchical")` through the binding: the furnace, bake()'s result keys,
the hierarchy's counts, errors and cancel. Numbers against closed forms."""
import unittest

import numpy as np

import _core
from test_binding import box_arrays, fronts


class HierarchicalBakeTest(unittest.TestCase):
    def test_furnace_gives_emission_over_one_minus_rho(self):
        rho, emitted = 0.6, 2.0
        result = _core.bake(*box_arrays(rho=rho, emitted=emitted), method="hierarchical", element_size=0.1,
                            refine_tolerance=0.005, tolerance=1e-7)
        expected = emitted / (1.0 - rho)
        np.testing.assert_allclose(fronts(result), expected, rtol=1e-2)
        np.testing.assert_allclose(result["corner_radiance"], expected, rtol=1e-2)
        self.assertTrue(result["converged"])

    def test_result_has_bake_keys_and_counts(self):
        result = _core.bake(*box_arrays(), method="hierarchical", element_size=0.1)
        uniform = _core.bake(*box_arrays(), element_size=0.25, resolution=16)
        self.assertLessEqual(set(uniform) - {"hierarchy"}, set(result))
        counts = result["hierarchy"]
        self.assertEqual(counts["patches"], 12)  # the emitting walls and their back sides
        self.assertEqual(counts["clusters"], 11)  # a binary tree over 12 patches
        self.assertGreaterEqual(result["elements"], counts["leaves"])
        self.assertEqual(result["element_corners"].shape, (result["elements"], 4))
        self.assertEqual(result["corner_radiance"].shape, (24, 3))
        self.assertFalse(counts["leaf_cap_reached"])

    def test_point_lamp_lights_a_floor_as_the_inverse_square_law_says(self):
        # A 0.2 m floor under a lamp 2 m up: L = rho I cos / (pi r^2) ~ rho I / (4 pi) at its centre.
        v = np.array([[-0.1, -0.1, 0], [0.1, -0.1, 0], [0.1, 0.1, 0], [-0.1, 0.1, 0]], dtype=np.float32)
        arrays = (v, np.array([0, 4], np.int32), np.array([0, 1, 2, 3], np.int32),
                  np.full((1, 3), 0.5, np.float32), np.zeros((1, 3), np.float32))
        lamp = {"type": "POINT", "position": (0, 0, 2), "intensity": (1.0, 1.0, 1.0)}
        result = _core.bake(*arrays, method="hierarchical", element_size=0.05, lights=[lamp])
        exact = 0.5 / (4.0 * np.pi) * 0.99751  # h^3 / r^3 averaged over the floor (midpoint rule, 4e6 points)
        area = result["element_area"]
        mean = float((result["element_radiance"][:, 0] * area).sum() / area.sum())
        self.assertAlmostEqual(mean, exact, delta=2e-3 * exact)
        np.testing.assert_allclose(result["element_emission"], result["element_radiance"], rtol=1e-9)

    def test_bad_settings_are_value_errors(self):
        with self.assertRaisesRegex(ValueError, "min_element_size"):
            _core.bake(*box_arrays(), method="hierarchical", element_size=0.0)
        with self.assertRaisesRegex(ValueError, "refine_tolerance"):
            _core.bake(*box_arrays(), method="hierarchical", refine_tolerance=-1.0)

    def test_progress_reports_phases_and_cancel_stops(self):
        phases = []

        def stop_in_solve(info):
            phases.append(info["phase"])
            self.assertIsNone(info["radiance"])  # leaves change as they refine: no preview
            return info["phase"] != "solve"

        with self.assertRaises(_core.Cancelled):
            _core.bake(*box_arrays(), method="hierarchical", element_size=0.05, progress=stop_in_solve)
        self.assertEqual(phases[:3], ["elements"] * 3)  # set-up stages report too (and may cancel)
        self.assertIn("links", phases)
        self.assertEqual(phases[-1], "solve")


if __name__ == "__main__":
    unittest.main()
