"""The `textures` keyword of `_core.bake`: a textured floor under a sun against closed forms, and
clear errors for textures that do not fit the scene."""
import math
import unittest

import numpy as np

import _core

# A 2 x 2 checker of two greys, looked up Closest: each quarter of the floor is one texel.
DARK, LIGHT = 0.2, 0.6
CHECKER = np.array([[[DARK] * 3, [LIGHT] * 3], [[LIGHT] * 3, [DARK] * 3]], dtype=np.float32)


def floor(rho):
    """A 2 x 2 m floor, one quad, its UVs spanning the texture once."""
    v = np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], dtype=np.float32)
    return (v, np.array([0, 4], dtype=np.int32), np.arange(4, dtype=np.int32),
            np.full((1, 3), rho, dtype=np.float32), np.zeros((1, 3), dtype=np.float32))


def textures(**changes):
    keyword = {"images": [{"rgb": CHECKER, "filter": "closest", "extension": "extend"}],
               "corner_uv": np.array([[0, 0], [1, 0], [1, 1], [0, 1]], dtype=np.float32),
               "reflectance_texture": np.zeros(1, dtype=np.int32),
               "reflectance_scale": np.ones((1, 3), dtype=np.float32)}
    keyword.update(changes)
    return keyword


class TexturedFloorTest(unittest.TestCase):
    def test_sun_lit_checker_shows_its_texels(self):
        irradiance = 3.0
        sun = {"type": "SUN", "direction": (0.0, 0.0, -1.0), "irradiance": (irradiance,) * 3}
        mean = (DARK + LIGHT) / 2
        result = _core.bake(*floor(mean), element_size=0.5, resolution=16, lights=[sun], textures=textures())
        # Elements of 0.5 m lie in one quarter each: each reflects that quarter's grey.
        centre = result["element_vertices"][result["element_corners"]].mean(axis=1)
        quarter_is_light = (centre[:, 0] > 0) != (centre[:, 1] > 0)
        np.testing.assert_allclose(result["element_reflectance"][:, 0], np.where(quarter_is_light, LIGHT, DARK),
                                   rtol=1e-6)
        # Nothing else reflects: each corner is its texel times the sun's E / pi. With Extend the
        # corners at u or v = 1 read the last texel: (0, 0) dark, (1, 0) light, (1, 1) dark, (0, 1) light.
        texel = np.array([DARK, LIGHT, DARK, LIGHT])
        np.testing.assert_allclose(result["corner_radiance"][:, 0], texel * irradiance / math.pi, rtol=1e-5)
        np.testing.assert_allclose(result["corner_light"][:, 0], irradiance / math.pi, rtol=1e-5)


class BadTexturesTest(unittest.TestCase):
    def test_wrong_shapes_and_indices_are_named(self):
        with self.assertRaisesRegex(ValueError, "corner_uv must have shape"):
            _core.bake(*floor(0.4), textures=textures(corner_uv=np.zeros((3, 2), dtype=np.float32)))
        with self.assertRaisesRegex(ValueError, "rgb must have shape"):
            _core.bake(*floor(0.4), textures=textures(images=[{"rgb": np.zeros((2, 2), dtype=np.float32)}]))
        with self.assertRaisesRegex(ValueError, "polygon 0: reflectance texture 3 does not exist"):
            _core.bake(*floor(0.4), textures=textures(reflectance_texture=np.full(1, 3, dtype=np.int32)))
        with self.assertRaisesRegex(ValueError, "extension must be"):
            _core.bake(*floor(0.4), textures=textures(images=[{"rgb": CHECKER, "extension": "wrap"}]))
        with self.assertRaisesRegex(ValueError, "texture 0: texel 1 is not finite"):
            bad = CHECKER.copy()
            bad[0, 1, 2] = np.nan
            _core.bake(*floor(0.4), textures=textures(images=[{"rgb": bad}]))


if __name__ == "__main__":
    unittest.main()
