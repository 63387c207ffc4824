"""The session's bake cache (engine/bake_cache.py) through the core: a re-bake of the same
geometry reuses it and gives the colours of a bake from scratch; other geometry does not; the
summary's words."""

import dataclasses
import unittest

import numpy as np

from bake_radiosity.engine import auto_settings, bake_cache, solve, summary
from test_engine import SETTINGS, closed_box


def baked_with_cache(scene, reuse=True):
    """The bake test_engine's bake() makes, given the session's cache (none without `reuse`)."""
    choice = auto_settings.choose(dict(SETTINGS), scene)
    keywords = solve.core_settings(choice, dict(SETTINGS), scene.lights)
    cache = bake_cache.session_cache(reuse)
    if cache is not None:
        keywords["cache"] = cache
    return solve.bake(scene, keywords)


class BakeCacheTest(unittest.TestCase):
    def setUp(self):
        bake_cache.clear()

    def tearDown(self):
        bake_cache.clear()

    def test_one_cache_a_session_let_go_without_reuse(self):
        first = bake_cache.session_cache(True)
        self.assertIs(bake_cache.session_cache(True), first)
        self.assertIsNone(bake_cache.session_cache(False))
        self.assertEqual(bake_cache.held_bytes(), 0)
        self.assertIsNot(bake_cache.session_cache(True), first)

    def test_a_rebake_with_other_emission_reuses_it_and_equals_a_bake_from_scratch(self):
        scene = closed_box()
        first = baked_with_cache(scene)
        self.assertEqual((first["cache"]["reused"], first["cache"]["kept"]), (False, True))
        self.assertEqual(first["cache"]["not_reused"], "no earlier bake was kept")
        self.assertEqual(bake_cache.held_bytes(), first["cache"]["bytes"])
        brighter = dataclasses.replace(scene, emission=np.full_like(scene.emission, 5.0),
                                       reflectance=np.full_like(scene.reflectance, 0.3))
        again = baked_with_cache(brighter)
        self.assertTrue(again["cache"]["reused"])
        fresh = baked_with_cache(brighter, reuse=False)
        self.assertNotIn("cache", fresh)
        np.testing.assert_array_equal(again["corner_radiance"], fresh["corner_radiance"])
        self.assertFalse(np.array_equal(again["corner_radiance"], first["corner_radiance"]))

    def test_other_geometry_bakes_afresh(self):
        scene = closed_box()
        baked_with_cache(scene)
        taller = dataclasses.replace(scene, positions=scene.positions * np.float32([1, 1, 1.5]))
        again = baked_with_cache(taller)
        self.assertFalse(again["cache"]["reused"])
        self.assertEqual(again["cache"]["not_reused"], "the geometry, or a setting that chooses the elements, changed")
        self.assertTrue(again["cache"]["kept"])

    def test_the_summary_says_what_the_bake_did_with_it(self):
        mb = 1 << 20
        self.assertEqual(bake_cache.cache_text(None), "")
        self.assertEqual(bake_cache.cache_text({"reused": True, "kept": True, "bytes": 42 * mb, "not_reused": "",
                                                "not_kept": ""}),
                         "Reused the geometry of the previous bake (42 MB)")
        self.assertEqual(bake_cache.cache_text({"reused": True, "kept": True, "bytes": 42 * mb, "direct_bytes": 5 * mb,
                                                "not_reused": "", "not_kept": ""}),
                         "Reused the geometry of the previous bake (42 MB, 5 MB of it the direct light per source)")
        self.assertEqual(bake_cache.cache_text({"reused": True, "merged_again": True, "kept": True, "bytes": 42 * mb,
                                                "not_reused": "", "not_kept": ""}),
                         "Reused the geometry of the previous bake, its form factors computed again (the faces "
                         "beside the moved lamps merge otherwise) (42 MB)")
        self.assertEqual(bake_cache.cache_text({"reused": False, "kept": True, "bytes": 3 * mb,
                                                "not_reused": "no earlier bake was kept", "not_kept": ""}),
                         "Baked the geometry afresh (no earlier bake was kept) and kept it for the next bake (3 MB)")
        self.assertEqual(bake_cache.cache_text({"reused": False, "kept": False, "bytes": 0, "not_reused": "x",
                                                "not_kept": "over the budget"}),
                         "Baked the geometry afresh (x); not kept for the next bake: over the budget")
        line = summary.cost_line({"elements": 24, "seconds": {"solve": 1.0},
                                  "cache": {"reused": True, "kept": True, "bytes": mb, "not_reused": "",
                                            "not_kept": ""}})
        self.assertEqual(line, "Cost: 24 elements; solve 1.0 s. Reused the geometry of the previous bake (1 MB)")


if __name__ == "__main__":
    unittest.main()
