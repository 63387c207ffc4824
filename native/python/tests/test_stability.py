"""Stability through the binding (docs/stability.md): degenerate input, scales, the element cap,
and the stability settings of `_core.bake`. Numbers are checked against closed forms.
"""
import math
import time
import unittest

import numpy as np

import _core
from test_binding import fronts


def box_arrays(size=1.0, rho=0.5, emitted=1.0):
    """The six inward-facing sides of a 1 x 1.5 x 0.8 box scaled by `size`, uniform rho and E."""
    sx, sy, sz = size, 1.5 * size, 0.8 * size
    v = np.array([[0, 0, 0], [sx, 0, 0], [sx, sy, 0], [0, sy, 0],
                  [0, 0, sz], [sx, 0, sz], [sx, sy, sz], [0, sy, sz]], dtype=np.float32)
    quads = [[0, 1, 2, 3], [4, 7, 6, 5], [0, 3, 7, 4], [1, 5, 6, 2], [0, 4, 5, 1], [3, 2, 6, 7]]
    return (v, np.arange(0, 25, 4, dtype=np.int32), np.array(quads, dtype=np.int32).ravel(),
            np.full((6, 3), rho, dtype=np.float32), np.full((6, 3), emitted, dtype=np.float32))


def add_triangle(arrays, corners):
    v, offsets, indices, reflectance, emission = arrays
    first = len(v)
    return (np.vstack([v, np.array(corners, dtype=np.float32)]),
            np.append(offsets, offsets[-1] + 3).astype(np.int32),
            np.concatenate([indices, [first, first + 1, first + 2]]).astype(np.int32),
            np.vstack([reflectance, [[0.5, 0.5, 0.5]]]).astype(np.float32),
            np.vstack([emission, [[0, 0, 0]]]).astype(np.float32))


class ScaleTest(unittest.TestCase):
    def test_furnace_from_micrometres_to_thousands_of_kilometres(self):
        for size in (1e-6, 1.0, 1e6):
            with self.subTest(size=size):
                result = _core.bake(*box_arrays(size), element_size=0.3 * size, resolution=32, tolerance=1e-7)
                self.assertEqual(result["elements"], 2 * 94)  # the emitting walls' back sides too
                np.testing.assert_allclose(fronts(result), 2.0, rtol=1e-4)
                self.assertTrue(np.isfinite(result["corner_radiance"]).all())


class DegenerateInputTest(unittest.TestCase):
    def test_zero_area_nan_and_inf_polygons_are_skipped(self):
        arrays = box_arrays()
        for corners in ([[0.2, 0.2, 0.5], [0.4, 0.2, 0.5], [0.3, 0.2, 0.5]],
                        [[0.2, 0.2, 0.5], [math.nan, 0.2, 0.5], [0.2, 0.4, 0.5]],
                        [[0.2, 0.2, 0.5], [math.inf, 0.2, 0.5], [0.2, 0.4, 0.5]]):
            arrays = add_triangle(arrays, corners)
        result = _core.bake(*arrays, element_size=0.3, resolution=32, tolerance=1e-7)
        self.assertEqual(result["skipped"], [(6, "zero area"), (7, "non-finite coordinates"),
                                             (8, "non-finite coordinates")])
        self.assertTrue(np.isfinite(result["corner_radiance"]).all())
        np.testing.assert_allclose(fronts(result), 2.0, rtol=1e-4)

    def test_nan_emission_names_the_polygon(self):
        v, offsets, corners, reflectance, emission = box_arrays()
        emission[2, 1] = math.nan
        with self.assertRaisesRegex(ValueError, "polygon 2"):
            _core.bake(v, offsets, corners, reflectance, emission)

    def test_too_many_elements_is_a_clear_error_and_quick(self):
        v = np.array([[0, 0, 0], [1e6, 0, 0], [1e6, 1e6, 0], [0, 1e6, 0]], dtype=np.float32)
        floor = (v, np.array([0, 4], dtype=np.int32), np.arange(4, dtype=np.int32),
                 np.full((1, 3), 0.5, dtype=np.float32), np.ones((1, 3), dtype=np.float32))
        start = time.monotonic()
        with self.assertRaisesRegex(ValueError, r"polygon 0: element_size 0.01 m would make 2e\+16 elements from this "
                                                r"polygon \(both sides: it emits\)"):
            _core.bake(*floor, element_size=0.01)
        self.assertLess(time.monotonic() - start, 1.0)
        with self.assertRaisesRegex(ValueError, "cap of 100"):
            _core.bake(*box_arrays(), element_size=0.1, max_elements=100)


class StabilitySettingsTest(unittest.TestCase):
    def test_over_relaxation_converges_to_the_furnace_in_fewer_sweeps(self):
        rho = 0.99
        arrays = box_arrays(rho=rho)
        plain = _core.bake(*arrays, element_size=0.25, resolution=32, tolerance=1e-7, max_iterations=5000)
        omega = 2.0 / (1.0 + math.sqrt(1.0 - rho * rho))
        sor = _core.bake(*arrays, element_size=0.25, resolution=32, tolerance=1e-7, max_iterations=5000,
                         over_relaxation=omega)
        np.testing.assert_allclose(fronts(sor), 1.0 / (1.0 - rho), rtol=1e-4)
        self.assertLess(sor["iterations"], plain["iterations"] / 5)
        with self.assertRaisesRegex(ValueError, "over_relaxation"):
            _core.bake(*arrays, over_relaxation=2.0)

    def test_near_field_gives_the_area_factor_of_opposed_squares(self):
        # Receiver (one element) under an emitter 1 m away: L = rho F_area E, F_area = 0.1998249.
        v = np.array([[0, 0, 1], [0, 1, 1], [1, 1, 1], [1, 0, 1],
                      [0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=np.float32)
        arrays = (v, np.array([0, 4, 8], dtype=np.int32), np.arange(8, dtype=np.int32),
                  np.array([[0, 0, 0], [0.5, 0.5, 0.5]], dtype=np.float32),
                  np.array([[1, 1, 1], [0, 0, 0]], dtype=np.float32))
        before = _core.bake(*arrays, resolution=64)["element_radiance"][1, 0]
        after = _core.bake(*arrays, resolution=64, near_field=True)["element_radiance"][1, 0]
        self.assertAlmostEqual(before, 0.5 * 0.239456, delta=1e-5)  # the centre-point value
        self.assertAlmostEqual(after, 0.5 * 0.1998249, delta=1e-5)

    def test_aspect_split_cuts_slivers(self):
        v = np.array([[0, 0, 0], [1, 0, 0], [1, 0.01, 0], [0, 0.01, 0]], dtype=np.float32)
        strip = (v, np.array([0, 4], dtype=np.int32), np.arange(4, dtype=np.int32),
                 np.full((1, 3), 0.5, dtype=np.float32), np.zeros((1, 3), dtype=np.float32))
        self.assertEqual(_core.plan(*strip)["elements"], 1)
        self.assertEqual(_core.bake(*strip, resolution=16, max_element_aspect=4.0)["elements"], 25)


class RecommendedResolutionTest(unittest.TestCase):
    """N = 2 d sqrt(cells / A) for A the largest of the smallest elements that hold a tenth of the area,
    seen from the plan's resolution_distance d, even, within [32, 1024] (docs/stability.md), computed here
    from the geometry."""

    @staticmethod
    def cube(element_size):
        _, offsets, corners, reflectance, emission = box_arrays()
        v = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]],
                     dtype=np.float32)
        return _core.plan(v, offsets, corners, reflectance, emission, element_size=element_size)

    def test_unit_cube_at_10_cm_and_3_cm(self):
        d = 0.5 * math.sqrt(3.0)  # 1.9 x its sight distance is more: half the diagonal
        for element_size, per_side, expected in ((0.1, 10, 50), (0.03, 34, 168)):
            layout = self.cube(element_size)
            self.assertEqual(layout["elements"], 2 * 6 * per_side ** 2)  # the emitting walls' back sides too
            self.assertAlmostEqual(layout["resolution_distance"], d, places=6)
            exact = 2 * d * math.sqrt(8.0 / (1.0 / per_side) ** 2)
            self.assertEqual(expected, 2 * math.ceil(exact / 2))
            self.assertEqual(_core.recommended_resolution(layout["element_area"], d), expected)
            # N grows as sqrt(cells), never below 32.
            self.assertEqual(_core.recommended_resolution(layout["element_area"], d, cells=2.0),
                             max(32, 2 * math.ceil(exact / 4)))

    def test_sight_distance_of_the_cube_is_its_chords(self):
        """The power mean (1.4) of the chords of a unit cube from its walls, cosine-weighted, those
        shorter than the sending element left out: more than Cauchy's mean chord 4 V / S = 2/3, less
        than the longest chord sqrt(3), and the same whatever the elements."""
        coarse, fine = self.cube(0.1)["sight_distance"], self.cube(0.03)["sight_distance"]
        self.assertGreater(coarse, 2.0 / 3.0)
        self.assertLess(coarse, 0.85)
        self.assertAlmostEqual(coarse, fine, delta=0.03)

    def test_resolved_area_inverts_the_resolution(self):
        """A = cells (2 d / N)^2: at N = 50 the unit cube's 10 cm elements (0.01 m^2) are resolved with
        the 8 cells they were chosen for, to N's rounding (exact N = 48.99)."""
        d = self.cube(0.1)["resolution_distance"]
        for resolution, cells in ((50, 8.0), (128, 6.0)):
            self.assertAlmostEqual(_core.resolved_area(d, resolution, cells), cells * (2 * d / resolution) ** 2,
                                   places=9)
        self.assertLess(_core.resolved_area(d, 50, 8.0), 0.01)
        self.assertGreater(_core.resolved_area(d, 48, 8.0), 0.01)
        with self.assertRaises(_core.InputError):
            _core.resolved_area(d, 0, 8.0)
        with self.assertRaises(_core.InputError):
            _core.resolved_area(-1.0, 50, 8.0)

    def test_tenth_of_the_area_clamps_and_errors(self):
        area, d = self.cube(0.1)["element_area"], 0.5 * math.sqrt(3.0)
        # Tiny elements, however many, hold no area and do not set the resolution; smaller elements
        # that hold a tenth of the area do: a fifth of the elements at a quarter of the area (1 / 21
        # of the total) do not, half of them (1 / 5) do, N = 2 d sqrt(8 / (0.01 / 4)).
        tiny, fifth, half = area.copy(), area.copy(), area.copy()
        tiny[:len(area) // 2] = 1e-9
        fifth[:len(area) // 5] *= 0.25
        half[:len(area) // 2] *= 0.25
        self.assertEqual(_core.recommended_resolution(tiny, d), 50)
        self.assertEqual(_core.recommended_resolution(fifth, d), 50)
        exact = 2 * d * math.sqrt(8.0 / (0.01 / 4))
        self.assertEqual(_core.recommended_resolution(half, d), 2 * math.ceil(exact / 2))
        self.assertEqual(_core.recommended_resolution(np.full(10, 1e-9, dtype=np.float32), d), 1024)
        self.assertEqual(_core.recommended_resolution(np.full(10, 100.0, dtype=np.float32), d), 32)
        self.assertEqual(_core.recommended_resolution(np.zeros(0, dtype=np.float32), d), 32)
        with self.assertRaisesRegex(ValueError, "element_area"):
            _core.recommended_resolution(area.reshape(-1, 1), d)
        with self.assertRaisesRegex(ValueError, "cells"):
            _core.recommended_resolution(area, d, cells=0.0)
        with self.assertRaisesRegex(ValueError, "distance"):
            _core.recommended_resolution(area, -1.0)


if __name__ == "__main__":
    unittest.main()
