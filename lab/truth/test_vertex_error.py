"""vertex_error against numbers known in advance: corner colours averaged per vertex, dark vertices
left out, the noise of a mean of seeds with a known spread, and that noise taken out of an error."""

import math
import os
import sys
import unittest

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import vertex_error  # noqa: E402


class VertexErrorTest(unittest.TestCase):
    def test_luminance_per_vertex_leaves_out_skipped_corners(self):
        corner_vertex = np.array([0, 1, 1, 2, 2])
        kept = np.array([True, True, True, True, False])  # vertex 2's second corner is on an emitter
        colors = np.array([[1, 1, 1], [1, 0, 0], [0, 1, 0], [0, 0, 1], [100, 100, 100]], dtype=float)
        luminance = vertex_error.VertexLuminance(corner_vertex, kept)(colors)
        np.testing.assert_allclose(luminance, [1.0, (0.2126 + 0.7152) / 2, 0.0722])

    def test_dark_vertices_are_not_judged(self):
        truth = vertex_error.Truth([[1.0, 1.0, 0.008, 1.0]])  # the mean is 0.752: 1% of it is 0.00752
        self.assertEqual(truth.judged.tolist(), [True, True, True, True])
        truth = vertex_error.Truth([[1.0, 1.0, 0.005, 1.0]])
        self.assertEqual(truth.judged.tolist(), [True, True, False, True])

    def test_noise_of_the_mean_and_taken_out_of_an_error(self):
        rng = np.random.default_rng(7)
        vertices, seeds, spread, bake_error = 20000, 16, 0.04, 0.006
        exact = rng.uniform(0.1, 2.0, vertices)
        truth = vertex_error.Truth(exact * (1 + spread * rng.standard_normal((seeds, vertices))))
        expected_noise = spread / math.sqrt(seeds)  # 1%
        self.assertAlmostEqual(truth.noise() / expected_noise, 1.0, delta=0.02)
        bake = exact * (1 + bake_error * rng.standard_normal(vertices))
        measured, noise_out = truth.error(bake)
        self.assertAlmostEqual(measured / math.hypot(bake_error, expected_noise), 1.0, delta=0.02)
        self.assertAlmostEqual(noise_out / bake_error, 1.0, delta=0.05)

    def test_scaled_error_and_subsets(self):
        truth = vertex_error.Truth([[1.0, 2.0, 4.0, 3.0], [1.0, 2.0, 4.0, 3.0]])  # no spread: no noise
        bake = np.array([1.01, 2.02, 4.04, 3.0])
        self.assertAlmostEqual(truth.scaled_error(bake)[1], math.sqrt(0.0021 / 4) / math.sqrt(30 / 4))
        self.assertAlmostEqual(truth.error(bake)[1], math.sqrt(3 / 4) * 0.01)
        self.assertAlmostEqual(truth.error(bake, subset=[True, True, False, False])[1], 0.01)
        self.assertAlmostEqual(truth.error(bake, subset=[False, False, False, True])[1], 0.0)

    def test_time_to_reach_on_a_power_law(self):
        points = [(4.0, 0.05), (1.0, 0.1), (16.0, 0.025), (8.0, 0.06)]  # error = 0.1 / sqrt(t); (8, 6%) slower
        self.assertEqual(vertex_error.time_to_reach(points, 0.05), (4.0, False))
        seconds, extrapolated = vertex_error.time_to_reach(points, 0.1 / math.sqrt(8))
        self.assertAlmostEqual(seconds, 8.0)
        self.assertFalse(extrapolated)
        seconds, extrapolated = vertex_error.time_to_reach(points, 0.0125)
        self.assertAlmostEqual(seconds, 64.0)
        self.assertTrue(extrapolated)
        self.assertEqual(vertex_error.time_to_reach(points, 0.2), (None, False))


if __name__ == "__main__":
    unittest.main()
