"""Tests of the `_core` binding: dtypes, shapes, clear errors, progress and cancel.

Run by ctest with the interpreter the module was built for and PYTHONPATH at the staged add-on.
The numbers are checked against closed forms, not against the core's own output.
"""
import math
import threading
import unittest

import numpy as np

import _core


def box_arrays(size=1.0, rho=0.5, emitted=1.0):
    """The six inward-facing sides of a cube, one quad each, uniform rho and emission."""
    s = size
    v = np.array([[0, 0, 0], [s, 0, 0], [s, s, 0], [0, s, 0],
                  [0, 0, s], [s, 0, s], [s, s, s], [0, s, s]], dtype=np.float32)
    quads = [[0, 1, 2, 3],  # floor, +z
             [4, 7, 6, 5],  # ceiling, -z
             [0, 3, 7, 4],  # x = 0, +x
             [1, 5, 6, 2],  # x = s, -x
             [0, 4, 5, 1],  # y = 0, +y
             [3, 2, 6, 7]]  # y = s, -y
    corners = np.array(quads, dtype=np.int32).ravel()
    offsets = np.arange(0, 4 * len(quads) + 1, 4, dtype=np.int32)
    reflectance = np.full((len(quads), 3), rho, dtype=np.float32)
    emission = np.full((len(quads), 3), emitted, dtype=np.float32)
    return v, offsets, corners, reflectance, emission


def block_on_floor_arrays():
    """A 2 m floor with a 0.5 m block standing on it, off the floor's element grid; the block's top
    emits."""
    a, b, h = -0.3, 0.2, 0.5
    v = np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0],
                  [a, a, 0], [b, a, 0], [b, b, 0], [a, b, 0],
                  [a, a, h], [b, a, h], [b, b, h], [a, b, h]], dtype=np.float32)
    quads = [[0, 1, 2, 3],  # floor, +z
             [8, 9, 10, 11],  # block top
             [4, 5, 9, 8], [5, 6, 10, 9], [6, 7, 11, 10], [7, 4, 8, 11]]  # block sides
    corners = np.array(quads, dtype=np.int32).ravel()
    offsets = np.arange(0, 4 * len(quads) + 1, 4, dtype=np.int32)
    reflectance = np.full((len(quads), 3), 0.5, dtype=np.float32)
    emission = np.zeros((len(quads), 3), dtype=np.float32)
    emission[1] = 1.0
    return v, offsets, corners, reflectance, emission


def lit_box_arrays(cells=4):
    """A 1 m box of inward quads, `cells` x `cells` a side, reflectance 0.6, its ceiling emitting."""
    positions, corners, emission = [], [], []
    sides = [((0, 0, 0), (1, 0, 0), (0, 1, 0)), ((0, 0, 1), (0, 1, 0), (1, 0, 0)),  # floor, ceiling
             ((0, 0, 0), (0, 1, 0), (0, 0, 1)), ((1, 0, 0), (0, 0, 1), (0, 1, 0)),
             ((0, 0, 0), (0, 0, 1), (1, 0, 0)), ((0, 1, 0), (1, 0, 0), (0, 0, 1))]
    for side, (origin, a, b) in enumerate(sides):
        origin, a, b = (np.array(x, dtype=np.float64) for x in (origin, a, b))
        for i in range(cells):
            for j in range(cells):
                corners.extend(range(len(positions), len(positions) + 4))
                positions += [origin + a * (i + du) / cells + b * (j + dv) / cells
                              for du, dv in ((0, 0), (1, 0), (1, 1), (0, 1))]
                emission.append([2.0] * 3 if side == 1 else [0.0] * 3)
    faces = len(emission)
    return (np.array(positions, dtype=np.float32), np.arange(0, 4 * faces + 1, 4, dtype=np.int32),
            np.array(corners, dtype=np.int32), np.full((faces, 3), 0.6, dtype=np.float32),
            np.array(emission, dtype=np.float32))


def fronts(result, key="element_radiance"):
    """`key` of the elements that are not an emitting polygon's back side: emitting polygons are
    two-sided, and an emitting box's back sides face out (their radiance is their emission)."""
    return result[key][~result["element_back"]]


class FurnaceTest(unittest.TestCase):
    def test_closed_box_gives_emission_over_one_minus_rho(self):
        rho, emitted = 0.6, 2.0
        result = _core.bake(*box_arrays(rho=rho, emitted=emitted), element_size=0.25, resolution=64,
                            tolerance=1e-7)
        expected = emitted / (1.0 - rho)
        np.testing.assert_allclose(fronts(result), expected, rtol=1e-4)
        np.testing.assert_allclose(result["element_radiance"][result["element_back"]], emitted)  # they face out
        np.testing.assert_allclose(result["corner_radiance"], expected, rtol=1e-4)
        self.assertTrue(result["converged"])

    def test_final_gather_meets_the_furnace_at_every_corner(self):
        rho, emitted = 0.6, 2.0
        result = _core.bake(*box_arrays(rho=rho, emitted=emitted), element_size=0.25, resolution=64,
                            tolerance=1e-7, final_gather=True, gather_rays=64, gather_shadow_rays=16)
        np.testing.assert_allclose(result["corner_radiance"], emitted / (1.0 - rho), rtol=1e-4)
        gather = result["final_gather"]
        self.assertEqual((gather["points"], gather["buried"]), (24, 0))
        self.assertNotIn("final_gather", _core.bake(*box_arrays(), element_size=0.5, resolution=16))
        with self.assertRaisesRegex(ValueError, "gather_rays"):
            _core.bake(*box_arrays(), element_size=0.5, resolution=16, final_gather=True, gather_rays=0)

    def test_final_gather_reports_its_cost_and_shares(self):
        # The box's corners are all on seams, so with sharing on they still gather their own; each
        # phase's rays and seconds come back, the points phase's at least the gather rays of 24 points.
        result = _core.bake(*box_arrays(), element_size=0.25, resolution=64, final_gather=True, gather_rays=64,
                            gather_shadow_rays=16, gather_cache_accuracy=0.3)
        gather = result["final_gather"]
        self.assertEqual((gather["points"], gather["interpolated"], gather["buried"]), (24, 0, 0))
        self.assertEqual(list(gather["phases"]), ["field", "wedges", "probes", "points", "seams", "other"])
        self.assertEqual(gather["phases"]["probes"]["rays"], 24 * 64)
        self.assertGreaterEqual(gather["phases"]["points"]["rays"], 24 * 64)
        self.assertTrue(all(phase["seconds"] >= 0.0 for phase in gather["phases"].values()))
        with self.assertRaisesRegex(ValueError, "gather_cache_accuracy"):
            _core.bake(*box_arrays(), element_size=0.5, resolution=16, final_gather=True, gather_cache_accuracy=-1)

    def test_final_gathers_statistics_in_the_furnace(self):
        """What the error estimate reads: every ray sees the walls' reflected light L - E, so each
        corner's indirect share is exactly rho (L - E), its rays do not differ, the field (gathered
        at the element vertices) carries every element's light and has no noise to pass on."""
        rho, emitted = 0.6, 2.0
        light = emitted / (1.0 - rho)
        for field_rays in (0, 16):
            result = _core.bake(*box_arrays(rho=rho, emitted=emitted), element_size=0.25, resolution=64,
                                tolerance=1e-7, final_gather=True, gather_rays=64, gather_shadow_rays=16,
                                gather_field_rays=field_rays)
            gather = result["final_gather"]
            for key in ("solution_light", "indirect", "variance", "field_noise"):
                self.assertEqual(gather[key].shape, result["corner_radiance"].shape, key)
            np.testing.assert_allclose(gather["solution_light"], (light - emitted) / rho, rtol=1e-4)
            np.testing.assert_allclose(gather["indirect"], rho * (light - emitted), rtol=1e-4)
            np.testing.assert_allclose(gather["variance"], 0.0, atol=1e-9)
            np.testing.assert_allclose(gather["field_noise"], 0.0, atol=1e-9)
            self.assertEqual(gather["element_field_error"].shape, (result["elements"], 3))
            np.testing.assert_allclose(gather["element_field_error"], 0.0, atol=1e-4)
            np.testing.assert_allclose(gather["element_reflected"][~result["element_back"]], light - emitted, rtol=1e-4)

    def test_emitters_lit_directly_meet_the_furnace(self):
        """Every element of the box is smaller than direct_emitter_area, so each lights the others
        directly (analytic factors) instead of through the hemi-cube: the same L = E / (1 - rho)."""
        rho, emitted = 0.6, 2.0
        result = _core.bake(*box_arrays(rho=rho, emitted=emitted), element_size=0.25, resolution=16,
                            tolerance=1e-7, direct_emitter_area=1.0)
        self.assertEqual(result["direct_emitters"], result["elements"])
        np.testing.assert_allclose(fronts(result), emitted / (1.0 - rho), rtol=1e-3)
        # Emission as given: the first reflection of their light is light received, not emission.
        np.testing.assert_allclose(result["element_emission"], emitted)
        self.assertNotIn("direct_emitters", _core.bake(*box_arrays(), element_size=0.5, resolution=16))
        with self.assertRaisesRegex(ValueError, "direct_emitter_area"):
            _core.bake(*box_arrays(), element_size=0.5, resolution=16, direct_emitter_area=-1.0)

    def test_every_method_agrees(self):
        arrays = box_arrays(rho=0.5, emitted=1.0)
        for method in ("gauss_seidel", "jacobi", "progressive"):
            with self.subTest(method=method):
                result = _core.bake(*arrays, element_size=0.5, resolution=32, method=method, tolerance=1e-8)
                np.testing.assert_allclose(fronts(result), 2.0, rtol=1e-5)


class GatherStatisticsTest(unittest.TestCase):
    def test_final_gathers_sampling_variance_is_its_rays_error(self):
        """The variance a corner's 64 rays give its colour, from their two halves, against what they
        actually miss: the same bake (same solution) gathered with 128 times the rays."""
        def bake(rays):
            return _core.bake(*lit_box_arrays(), element_size=0.125, resolution=64, tolerance=1e-7,
                              final_gather=True, gather_rays=rays, gather_shadow_rays=64)
        coarse, fine = bake(64), bake(8192)
        luminance = np.array([0.2126, 0.7152, 0.0722])
        reflecting = fine["corner_radiance"] @ luminance < fine["corner_light"] @ luminance  # not the ceiling
        value = fine["corner_radiance"][reflecting] @ luminance
        missed = (coarse["corner_radiance"] - fine["corner_radiance"])[reflecting] @ luminance / value
        estimated = np.sqrt(coarse["final_gather"]["variance"][reflecting]) @ luminance / value
        ratio = math.sqrt(np.mean(estimated ** 2) / np.mean(missed ** 2))
        self.assertGreater(np.sqrt(np.mean(missed ** 2)), 0.005)  # 64 rays miss about 1% here
        self.assertGreater(ratio, 0.7)
        self.assertLess(ratio, 1.4)


class OutputShapesTest(unittest.TestCase):
    def test_dtypes_and_shapes(self):
        arrays = box_arrays()
        result = _core.bake(*arrays, element_size=0.5, resolution=16)
        elements = result["elements"]
        self.assertEqual(elements, 2 * 6 * 4)  # the emitting walls' back sides too
        self.assertEqual(result["element_back"].shape, (elements,))
        self.assertEqual(int(result["element_back"].sum()), 6 * 4)
        self.assertEqual(result["corner_radiance"].shape, (24, 3))
        self.assertEqual(result["corner_radiance"].dtype, np.float32)
        self.assertEqual(result["element_radiance"].shape, (elements, 3))
        self.assertEqual(result["element_corners"].shape, (elements, 4))
        self.assertEqual(result["element_corners"].dtype, np.int32)
        self.assertEqual(result["element_corner_radiance"].shape, (elements, 4, 3))
        self.assertEqual(result["element_polygon"].shape, (elements,))
        self.assertAlmostEqual(float(fronts(result, "element_area").sum()), 6.0, places=5)
        self.assertEqual(set(result["seconds"]),
                         {"elements", "lights", "world", "small_emitters", "form_factors", "solve", "interpolate",
                          "gather"})

    def test_elements_match_the_bake_without_solving(self):
        arrays = box_arrays()
        layout = _core.plan(*arrays, element_size=0.3)
        result = _core.bake(*arrays, element_size=0.3, resolution=16)
        for key in ("element_vertices", "element_corners", "element_polygon", "element_area", "element_back"):
            np.testing.assert_array_equal(layout[key], result[key], err_msg=key)
        self.assertEqual(layout["elements"], 2 * 6 * 16)  # the emitting walls' back sides too
        self.assertEqual(layout["skipped"], [])

    def test_elements_have_the_bakes_contact_cuts(self):
        """A block standing on a floor: the floor is cut along the block's footprint in bake(), and
        elements() must return that same mesh (the automatic settings and the preview read it)."""
        arrays = block_on_floor_arrays()
        layout = _core.plan(*arrays, element_size=0.5)
        result = _core.bake(*arrays, element_size=0.5, resolution=16)
        self.assertGreater(result["elements"], 23)  # without the cut: 16 floor, 6 block, the top's back side
        for key in ("element_vertices", "element_corners", "element_polygon", "element_area"):
            np.testing.assert_array_equal(layout[key], result[key], err_msg=key)

    def test_float64_and_list_input_is_accepted(self):
        v, offsets, corners, reflectance, emission = box_arrays()
        result = _core.bake(v.astype(np.float64), offsets.tolist(), corners.astype(np.int64),
                            reflectance.astype(np.float64), emission, resolution=16)
        self.assertEqual(result["corner_radiance"].shape, (24, 3))


class BadInputTest(unittest.TestCase):
    def test_wrong_shape_names_the_array(self):
        v, offsets, corners, reflectance, emission = box_arrays()
        with self.assertRaisesRegex(ValueError, "positions must have shape"):
            _core.bake(v[:, :2], offsets, corners, reflectance, emission)
        with self.assertRaisesRegex(ValueError, "reflectance must have shape"):
            _core.bake(v, offsets, corners, reflectance[:3], emission)

    def test_reflectance_of_one_names_the_polygon(self):
        v, offsets, corners, reflectance, emission = box_arrays()
        reflectance[4] = 1.0
        with self.assertRaisesRegex(ValueError, "4"):
            _core.bake(v, offsets, corners, reflectance, emission)

    def test_nan_polygon_is_reported_not_used(self):
        v, offsets, corners, reflectance, emission = box_arrays()
        v = np.vstack([v, [[0, 0, 0], [math.nan, 0, 0], [0, 1, 0]]]).astype(np.float32)
        corners = np.concatenate([corners, [8, 9, 10]]).astype(np.int32)
        offsets = np.append(offsets, offsets[-1] + 3).astype(np.int32)
        reflectance = np.vstack([reflectance, [[0.5, 0.5, 0.5]]]).astype(np.float32)
        emission = np.vstack([emission, [[0, 0, 0]]]).astype(np.float32)
        result = _core.bake(v, offsets, corners, reflectance, emission, resolution=16)
        self.assertEqual([p for p, _ in result["skipped"]], [6])
        self.assertTrue(np.isfinite(result["corner_radiance"]).all())

    def test_unknown_method(self):
        with self.assertRaisesRegex(ValueError, "method"):
            _core.bake(*box_arrays(), method="magic")


class ErrorVocabularyTest(unittest.TestCase):
    """Each failure has its own class, is also a `_core.Error` (one place reports them all), and
    keeps the built-in base its meaning has."""

    def test_bad_input_is_an_input_error(self):
        v, offsets, corners, reflectance, emission = box_arrays()
        reflectance[2] = 1.0
        with self.assertRaisesRegex(_core.InputError, "polygon 2: reflectance") as caught:
            _core.bake(v, offsets, corners, reflectance, emission)
        self.assertIsInstance(caught.exception, ValueError)
        self.assertIsInstance(caught.exception, _core.Error)
        with self.assertRaisesRegex(_core.InputError, "resolution"):
            _core.bake(*box_arrays(), resolution=7)

    def test_too_many_elements_is_a_budget_error(self):
        with self.assertRaisesRegex(_core.BudgetError, "cap of 100") as caught:
            _core.bake(*box_arrays(), element_size=0.1, max_elements=100)
        self.assertIsInstance(caught.exception, _core.InputError)

    def test_divergence_is_not_converged(self):
        """Over-relaxed Gauss-Seidel in a closed 2 m room with reflectance 0.999 (what an albedo of
        1 becomes) grows its residual: the solver stops and says why."""
        v, offsets, corners, reflectance, emission = box_arrays(size=2.0, rho=0.999, emitted=0.0)
        emission[1] = 1.0
        with self.assertRaisesRegex(_core.NotConverged, "Gauss-Seidel diverged") as caught:
            _core.bake(v, offsets, corners, reflectance, emission, element_size=0.2, resolution=16,
                       near_field=True, over_relaxation=0.0)
        self.assertIsInstance(caught.exception, RuntimeError)
        self.assertIsInstance(caught.exception, _core.Error)

    def test_missing_file_is_a_file_error(self):
        with self.assertRaisesRegex(_core.FileError, "no-such-file.vdb") as caught:
            _core.vdb_grids("/no-such-folder/no-such-file.vdb")
        self.assertIsInstance(caught.exception, OSError)

    def test_cancel_is_not_a_failure(self):
        self.assertFalse(issubclass(_core.Cancelled, _core.Error))


class LightsTest(unittest.TestCase):
    def floor(self, rho=0.5):
        v = np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], dtype=np.float32)
        return (v, np.array([0, 4], dtype=np.int32), np.arange(4, dtype=np.int32),
                np.full((1, 3), rho, dtype=np.float32), np.zeros((1, 3), dtype=np.float32))

    def test_sun_on_a_floor_gives_rho_e_cos_over_pi(self):
        theta, irradiance, rho = 0.5, 3.0, 0.5
        sun = {"type": "SUN", "direction": (math.sin(theta), 0.0, -math.cos(theta)), "irradiance": (irradiance,) * 3}
        result = _core.bake(*self.floor(rho), element_size=0.25, resolution=16, lights=[sun])
        expected = rho * irradiance * math.cos(theta) / math.pi
        np.testing.assert_allclose(result["element_radiance"], expected, rtol=1e-5)

    def test_point_lamp_power_is_conserved_on_the_floor(self):
        intensity, h, rho = 2.0, 1.0, 0.5
        lamp = {"type": "POINT", "position": (0.0, 0.0, h), "intensity": (intensity,) * 3}
        result = _core.bake(*self.floor(rho), element_size=0.1, resolution=16, lights=[lamp])
        # Solid angle of the 2 x 2 floor from 1 m above its centre: 4 atan(1 / (1 * sqrt(3))).
        solid_angle = 4.0 * math.atan(1.0 / math.sqrt(3.0))
        power = float((result["element_radiance"][:, 0] * result["element_area"]).sum()) * math.pi / rho
        self.assertAlmostEqual(power, intensity * solid_angle, delta=1e-3 * power)

    def test_lamp_radius_is_a_disk_or_a_sphere(self):
        # 10 cm over the floor's corner (1, 1, 0), radius 5 cm: at that corner a disk facing it
        # gives I / (h^2 + r^2), a sphere I / h^2 (its cone of 30 degrees is above the horizon).
        intensity, h, r, rho = 2.0, 0.1, 0.05, 0.5
        for shape, irradiance in (("DISK", intensity / (h * h + r * r)), ("SPHERE", intensity / (h * h))):
            lamp = {"type": "POINT", "position": (1.0, 1.0, h), "intensity": (intensity,) * 3, "radius": r,
                    "shape": shape}
            result = _core.bake(*self.floor(rho), element_size=0.25, resolution=16, lights=[lamp], final_gather=True)
            corner = result["corner_radiance"][2, 0]
            self.assertAlmostEqual(corner, rho * irradiance / math.pi, delta=1e-4 * corner)

    def test_uniform_world_on_a_lone_floor_gives_rho_w(self):
        rho, sky = 0.5, np.array([0.3, 0.6, 1.2], dtype=np.float32)
        for method in ("gauss_seidel", "hierarchical"):
            result = _core.bake(*self.floor(rho), element_size=0.25, world=sky.reshape(1, 1, 3), method=method)
            np.testing.assert_allclose(result["corner_radiance"], np.tile(rho * sky, (4, 1)), rtol=1e-6)

    def test_bad_world_map_is_a_value_error(self):
        with self.assertRaisesRegex(ValueError, "world must be an equirectangular map"):
            _core.bake(*self.floor(), world=np.ones((4, 8), dtype=np.float32))
        with self.assertRaisesRegex(ValueError, "finite and >= 0"):
            _core.bake(*self.floor(), world=np.full((4, 8, 3), -1.0, dtype=np.float32))

    def test_bad_lamp_is_named(self):
        with self.assertRaisesRegex(ValueError, "light 0: type"):
            _core.bake(*self.floor(), lights=[{"type": "LASER"}])
        with self.assertRaisesRegex(ValueError, "light 1: 'direction' has zero length"):
            _core.bake(*self.floor(), lights=[{"type": "POINT", "position": (0, 0, 1), "intensity": (1, 1, 1)},
                                              {"type": "SUN", "direction": (0, 0, 0), "irradiance": (1, 1, 1)}])
        with self.assertRaisesRegex(ValueError, "light 0: shape must be"):
            _core.bake(*self.floor(), lights=[{"type": "POINT", "position": (0, 0, 1), "intensity": (1, 1, 1),
                                               "shape": "CUBE"}])
        with self.assertRaisesRegex(ValueError, "light 0: 'radius' must be"):
            _core.bake(*self.floor(), lights=[{"type": "POINT", "position": (0, 0, 1), "intensity": (1, 1, 1),
                                               "radius": -1.0}])


class ProgressTest(unittest.TestCase):
    def test_progress_reports_phases_and_cancel_stops(self):
        phases = []

        def stop_in_solve(info):
            phases.append(info["phase"])
            return info["phase"] != "solve"

        with self.assertRaises(_core.Cancelled):
            _core.bake(*box_arrays(), element_size=0.1, resolution=16, tolerance=1e-9,
                       progress=stop_in_solve)
        self.assertIn("form_factors", phases)
        self.assertEqual(phases[-1], "solve")

    def test_progressive_preview_brightens(self):
        means = []

        def record(info):
            if info["radiance"] is not None:
                means.append(float(info["radiance"].mean()))

        _core.bake(*box_arrays(), element_size=0.25, resolution=16, method="progressive",
                   tolerance=1e-6, progress=record)
        self.assertGreater(len(means), 2)
        self.assertTrue(all(b >= a - 1e-9 for a, b in zip(means, means[1:])))

    def test_exception_in_callback_reaches_the_caller(self):
        def fail(info):
            raise KeyError("from the callback")

        with self.assertRaisesRegex(KeyError, "from the callback"):
            _core.bake(*box_arrays(), element_size=0.25, resolution=16, progress=fail)


class ProgressMonitorTest(unittest.TestCase):
    """A bake in a worker thread, polled from the main thread as Blender's modal timer does."""

    def bake_in_thread(self, monitor, **settings):
        outcome = {}

        def run():
            try:
                outcome["result"] = _core.bake(*box_arrays(), progress=monitor, **settings)
            except _core.Cancelled:
                outcome["cancelled"] = True

        thread = threading.Thread(target=run)
        thread.start()
        return thread, outcome

    def test_snapshot_reports_and_finishes(self):
        monitor = _core.ProgressMonitor()
        self.assertIsNone(monitor.snapshot())
        thread, outcome = self.bake_in_thread(monitor, element_size=0.25, resolution=16, method="progressive",
                                              tolerance=1e-6)
        thread.join(60)
        self.assertFalse(thread.is_alive())
        np.testing.assert_allclose(fronts(outcome["result"]), 2.0, rtol=1e-5)
        last = monitor.snapshot()
        self.assertEqual(last["phase"], "solve")
        self.assertEqual(last["radiance"].shape, (outcome["result"]["elements"], 3))
        self.assertIsNone(monitor.snapshot(radiance=False)["radiance"])
        self.assertEqual(monitor.snapshot(radiance=False)["residual"], last["residual"])

    def test_reports_counts_the_reports(self):
        monitor = _core.ProgressMonitor()
        self.assertEqual(monitor.reports, 0)
        thread, _ = self.bake_in_thread(monitor, element_size=0.25, resolution=16)
        thread.join(60)
        first = monitor.reports
        self.assertGreater(first, 1)
        thread, _ = self.bake_in_thread(monitor, element_size=0.25, resolution=16)
        thread.join(60)
        self.assertEqual(monitor.reports, 2 * first)  # the same bake again makes as many reports

    def test_cancel_from_another_thread_while_it_holds_the_gil(self):
        monitor = _core.ProgressMonitor()
        thread, outcome = self.bake_in_thread(monitor, element_size=0.05, resolution=32, tolerance=1e-12,
                                              max_iterations=100000)
        # Busy Python code on this thread, as Blender's main thread: the core must not wait for us.
        while monitor.snapshot() is None or monitor.snapshot()["phase"] != "solve":
            sum(range(1000))
        monitor.cancel()
        thread.join(60)
        self.assertFalse(thread.is_alive())
        self.assertTrue(outcome.get("cancelled"))
        self.assertTrue(monitor.cancelled)


if __name__ == "__main__":
    unittest.main()
