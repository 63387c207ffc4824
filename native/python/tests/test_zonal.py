"""`_core.bake` with media and `_core.principled_volume` over the binding, against closed forms:
Kirchhoff's isothermal enclosure, a scattering medium inside black emitting walls, a lamp in a closed
foggy box, and the
Principled Volume formula as Cycles' svm_node_principled_volume writes it."""
import unittest

import numpy as np

import _core
from test_binding import box_arrays, fronts


def fog(L0_emission, extinction, albedo, size=4, voxel=0.25):
    """A medium filling the unit box: size^3 voxels of uniform coefficients."""
    shape = (size, size, size, 3)
    return {"origin": (0.0, 0.0, 0.0), "voxel_size": voxel,
            "extinction": np.broadcast_to(np.asarray(extinction, np.float32), shape),
            "albedo": np.broadcast_to(np.asarray(albedo, np.float32), shape),
            "emission": np.broadcast_to(np.asarray(L0_emission, np.float32), shape)}


def bake(arrays, media, **settings):
    keywords = dict(element_size=0.5, resolution=32, tolerance=1e-7, media=media, zone_resolution=16)
    return _core.bake(*arrays, **dict(keywords, **settings))


class IsothermalTest(unittest.TestCase):
    def test_walls_and_zones_all_at_the_common_radiance(self):
        # Walls emit (1 - rho) L0, the medium K_a L0 = K_t (1 - Omega) L0: Kirchhoff says all is L0.
        L0, rho, Omega, K = np.array([1.0, 2.0, 0.5]), np.array([0.5, 0.3, 0.7]), np.array([0.3, 0.6, 0.9]), 2.0
        v, f, c, _, _ = box_arrays()
        reflectance = np.tile(rho, (6, 1)).astype(np.float32)
        emission = np.tile((1.0 - rho) * L0, (6, 1)).astype(np.float32)
        for method in ("gauss_seidel", "progressive"):
            with self.subTest(method=method):
                r = bake((v, f, c, reflectance, emission), [fog(K * (1.0 - Omega) * L0, K, Omega)], method=method)
                self.assertEqual(r["zones"], 8)  # uniform: 2^3 voxels per zone by default
                self.assertEqual(r["zones_before_merge"], 64)
                self.assertTrue(r["converged"])
                np.testing.assert_allclose(fronts(r), np.tile(L0, (24, 1)), rtol=5e-3)
                np.testing.assert_allclose(r["corner_radiance"], np.tile(L0, (24, 1)), rtol=5e-3)
                np.testing.assert_allclose(r["zone_radiance"], np.tile(L0, (8, 1)), rtol=5e-3)
                grids = r["grids"][0]  # 3 cells per zone edge by default, on the medium's corner
                self.assertEqual(grids["density"].shape, (12, 12, 12, 3))
                self.assertEqual(grids["origin"], (0.0, 0.0, 0.0))
                self.assertAlmostEqual(grids["voxel_size"], 0.25 / 3, places=7)
                np.testing.assert_allclose(grids["density"], K, rtol=1e-6)
                np.testing.assert_allclose(grids["emission"], np.broadcast_to(K * L0, (12, 12, 12, 3)), rtol=5e-3)

    def test_grid_subdivision_one_is_the_zones(self):
        v, f, c, _, _ = box_arrays()
        r = bake((v, f, c, np.zeros((6, 3), np.float32), np.ones((6, 3), np.float32)), [fog(0.0, 2.0, 0.5)],
                 grid_subdivision=1, merge_uniform_zones=False)
        self.assertEqual(r["zones"], 64)
        self.assertEqual(r["zones_before_merge"], 64)
        grids = r["grids"][0]
        self.assertEqual(grids["emission"].shape, (4, 4, 4, 3))
        self.assertEqual(grids["voxel_size"], 0.25)
        np.testing.assert_allclose(grids["emission"].reshape(-1, 3), 2.0 * r["zone_radiance"], rtol=1e-6)
        with self.assertRaisesRegex(ValueError, "grid_subdivision"):
            bake((v, f, c, np.zeros((6, 3), np.float32), np.ones((6, 3), np.float32)), [fog(0.0, 2.0, 0.5)],
                 grid_subdivision=0)

    def test_scattering_medium_takes_the_black_walls_radiance(self):
        L0 = np.array([1.0, 0.5, 2.0])
        v, f, c, _, _ = box_arrays()
        r = bake((v, f, c, np.zeros((6, 3), np.float32), np.tile(L0, (6, 1)).astype(np.float32)),
                 [fog(0.0, 3.0, 1.0)])
        np.testing.assert_allclose(r["zone_radiance"], np.tile(L0, (r["zones"], 1)), rtol=5e-3)

    def test_power_emitted_is_absorbed_by_walls_and_medium(self):
        v, f, c, _, _ = box_arrays()
        rho = np.full((6, 3), 0.5, np.float32)
        emission = np.zeros((6, 3), np.float32)
        emission[1] = 4.0  # the ceiling glows
        r = bake((v, f, c, rho, emission), [fog(0.0, 1.5, (0.5, 0.8, 0.2))])
        # The ceiling's back side (emitting polygons are two-sided) faces out of the box: what it
        # emits leaves. The power counts both sides; the walls and the medium absorb the front's.
        inside = ~r["element_back"]
        np.testing.assert_allclose(np.pi * (r["element_area"][:, None] * r["element_emission"]).sum(axis=0),
                                   2 * np.pi * 4.0, rtol=1e-6)
        area, L = r["element_area"][inside][:, None], r["element_radiance"][inside]
        E, R = r["element_emission"][inside], r["element_reflectance"][inside]
        emitted = np.pi * (area * E).sum(axis=0)
        walls = np.pi * (area * (1.0 - R) / R * (L - E)).sum(axis=0)  # reflected pi A (L - E) = pi A rho H
        zones = np.pi * (r["zone_weight"] * (1.0 - r["zone_albedo"]) * r["zone_incident"]).sum(axis=0)
        np.testing.assert_allclose((walls + zones) / emitted, 1.0, atol=1e-3)
        self.assertGreater(zones.min(), 0.05 * emitted.min())  # the medium takes a real share


class MergeAndOverRelaxationTest(unittest.TestCase):
    def test_only_the_uniform_half_merges(self):
        # 4^3 voxels: x < 2 uniform (4 blocks of 2^3), x >= 2 extinction varying per voxel (32 zones).
        medium = fog(0.0, 2.0, 0.5)
        extinction = np.array(medium["extinction"])
        extinction[:, :, 2:, :] += np.arange(32, dtype=np.float32).reshape(4, 4, 2, 1) * 0.1
        medium["extinction"] = extinction
        v, f, c, _, _ = box_arrays()
        rho, emission = np.full((6, 3), 0.5, np.float32), np.ones((6, 3), np.float32)
        merged = bake((v, f, c, rho, emission), [medium])
        self.assertEqual((merged["zones"], merged["zones_before_merge"]), (4 + 32, 64))
        self.assertEqual(len(merged["zone_radiance"]), 36)
        voxels = bake((v, f, c, rho, emission), [medium], merge_uniform_zones=False)
        self.assertEqual((voxels["zones"], voxels["zones_before_merge"]), (64, 64))
        # Each merged zone's weight is its 8 voxels' together: the medium's total 4 K_t V is the same.
        np.testing.assert_allclose(merged["zone_weight"].sum(axis=0), voxels["zone_weight"].sum(axis=0), rtol=1e-6)

    def test_over_relaxation_same_answer_fewer_sweeps(self):
        v, f, c, _, _ = box_arrays()
        rho, emission = np.full((6, 3), 0.95, np.float32), np.zeros((6, 3), np.float32)
        emission[1] = 4.0
        plain = bake((v, f, c, rho, emission), [fog(0.0, 2.0, 0.99)])
        over = bake((v, f, c, rho, emission), [fog(0.0, 2.0, 0.99)], over_relaxation=0.0)
        self.assertTrue(plain["converged"] and over["converged"])
        self.assertLess(over["iterations"], plain["iterations"] / 2)
        np.testing.assert_allclose(over["zone_radiance"], plain["zone_radiance"], rtol=1e-5)
        np.testing.assert_allclose(over["element_radiance"], plain["element_radiance"], rtol=1e-5)
        with self.assertRaisesRegex(ValueError, "over_relaxation"):
            bake((v, f, c, rho, emission), [fog(0.0, 2.0, 0.99)], over_relaxation=2.5)


class MediaInputTest(unittest.TestCase):
    def test_bad_media_name_the_medium(self):
        arrays = box_arrays()
        good = fog(0.0, 1.0, 0.5)
        wrong_shape = dict(good, albedo=np.zeros((4, 4, 3, 3), np.float32))
        with self.assertRaisesRegex(ValueError, r"medium 1: 'albedo' must have shape"):
            bake(arrays, [good, wrong_shape])
        missing = {k: val for k, val in good.items() if k != "emission"}
        with self.assertRaisesRegex(ValueError, "medium 0 has no 'emission'"):
            bake(arrays, [missing])
        bright = dict(good, albedo=np.full((4, 4, 4, 3), 1.5, np.float32))
        with self.assertRaisesRegex(ValueError, "medium 0 voxel 0: albedo outside"):
            bake(arrays, [bright])


class LampInFogTest(unittest.TestCase):
    def test_a_closed_box_reflects_rho_over_one_minus_rho_of_the_lamp(self):
        # Walls reflect rho and the fog scatters Omega = rho: all of the lamp's 4 pi I is absorbed,
        # 1 - rho of all the light that arrives anywhere, so pi (sum A L + sum w L_k) = rho / (1 - rho) 4 pi I.
        rho, intensity = 0.6, np.array([1.0, 2.0, 0.5])
        v, f, c, _, _ = box_arrays()
        reflectance = np.full((6, 3), rho, np.float32)
        lamp = {"type": "POINT", "position": (0.43, 0.52, 0.47), "intensity": tuple(intensity)}
        r = bake((v, f, c, reflectance, np.zeros((6, 3), np.float32)), [fog(0.0, 1.0, rho)], lights=[lamp],
                 element_size=0.125, resolution=64)
        self.assertTrue(r["converged"])
        leaving = np.pi * ((r["element_area"][:, None] * r["element_radiance"]).sum(axis=0)
                           + (r["zone_weight"] * r["zone_radiance"]).sum(axis=0))
        np.testing.assert_allclose(leaving, rho / (1.0 - rho) * 4.0 * np.pi * intensity, rtol=0.01)


class PrincipledVolumeTest(unittest.TestCase):
    def test_cycles_formula_per_voxel(self):
        color, absorption, emission_color = (0.8, 0.5, 0.1), (0.25, 0.0, 1.0), (1.0, 0.5, 0.25)
        density = np.array([[0.0, 1.0], [2.5, -1.0]])
        strength = np.full_like(density, 3.0)
        out = _core.principled_volume(color, density, absorption, strength, emission_color)
        d = np.maximum(density, 0.0)[..., None]
        # Cycles: sigma_s = d * color, sigma_a = d * (1 - color) * (1 - sqrt(absorption color)).
        np.testing.assert_allclose(out["scattering"], d * np.array(color), rtol=1e-6)
        np.testing.assert_allclose(out["absorption"], d * np.array([0.2 * 0.5, 0.5 * 1.0, 0.0]), rtol=1e-6, atol=1e-7)
        np.testing.assert_allclose(out["emission"], np.broadcast_to([3.0, 1.5, 0.75], (2, 2, 3)), rtol=1e-6)
        with self.assertRaisesRegex(ValueError, "same shape"):
            _core.principled_volume(color, density, absorption, np.ones(3), emission_color)


if __name__ == "__main__":
    unittest.main()
