"""bake_radiosity.engine.light_groups: which layer each source lights, the layers' attribute names,
and whether their memory fits the budget."""
import unittest

import numpy as np

from bake_radiosity.engine import light_groups


class LayersOf(unittest.TestCase):
    def test_groups_that_light_in_the_view_layers_order_no_group_first(self):
        # Polygons: a wall in 'Key' that does not emit, a panel in 'Fill' that does, a floor without a group
        # that emits; lamps in 'Key' and in 'Rim' (not in the view layer: no group); the World in 'Sky'.
        names = ["", "Key", "Fill"]
        polygon_group = np.array([1, 2, 0])
        emission = np.array([[0, 0, 0], [2, 2, 2], [1, 0, 0]], dtype=np.float32)
        layers = light_groups.layers_of(names, polygon_group, emission, ["Key", "Rim"], "Sky",
                                        ["Sky", "Fill", "Key", "Unused"])
        self.assertEqual(layers.names, ["", "Sky", "Fill", "Key"])
        self.assertEqual(layers.polygon.tolist(), [3, 2, 0])
        self.assertEqual(layers.lamp.tolist(), [3, 0])
        self.assertEqual(layers.world, 1)
        self.assertEqual(layers.keyword()["count"], 4)

    def test_a_group_whose_sources_give_no_light_has_no_layer(self):
        layers = light_groups.layers_of(["", "Key"], np.array([1, 1]), np.zeros((2, 3), np.float32), ["Key"], None,
                                        ["Key", "Fill"])
        self.assertEqual(layers.names, ["Key"])
        self.assertEqual(layers.polygon.tolist(), [0, 0])
        self.assertEqual(layers.lamp.tolist(), [0])
        self.assertEqual(layers.world, 0)


class Names(unittest.TestCase):
    def test_attribute_names(self):
        self.assertEqual(light_groups.attribute_name("Radiosity", "Key"), "Radiosity Key")
        self.assertEqual(light_groups.attribute_name("Radiosity", ""), "Radiosity (no group)")


class Budget(unittest.TestCase):
    def layers(self, count):
        return light_groups.Layers([str(k) for k in range(count)], np.zeros(0, np.int32), np.zeros(0, np.int32), 0)

    def test_layer_bytes_are_the_cores_bound_and_the_add_ons_copies(self):
        # Per layer the core holds 2 colours per input corner, 2 x 4 per element and 2 per element in doubles
        # (24 bytes); the add-on's float32 copies half that.
        self.assertEqual(light_groups.layer_bytes(8, 1000, 4000), int(8 * (8000 + 8000 + 2000) * 24 * 1.5))

    def test_refused_beyond_the_budget_with_the_form_factors_and_for_the_hierarchy(self):
        needed = light_groups.layer_bytes(8, 1000, 4000)
        refusal = light_groups.refusal
        self.assertIsNone(refusal(self.layers(8), "gauss_seidel", False, True, 1000, 1000, 4000, needed + 1000))
        message = refusal(self.layers(8), "gauss_seidel", False, True, 1001, 1000, 4000, needed + 1000)
        self.assertIn("memory budget", message)
        self.assertIn("baked without them", message)
        self.assertIsNone(refusal(self.layers(8), "hierarchical", False, True, 0, 1000, 4000, needed + 1))
        self.assertIn("memory budget", refusal(self.layers(8), "hierarchical", False, True, 0, 1000, 4000, needed))
        self.assertIn("Final Gather", refusal(self.layers(2), "hierarchical", False, False, 0, 10, 10, 1 << 30))
        self.assertIn("fog or smoke", refusal(self.layers(2), "progressive", True, True, 0, 10, 10, 1 << 30))

    def test_refused_when_a_group_has_the_no_group_layers_name(self):
        layers = light_groups.Layers(["", "(no group)"], np.zeros(0, np.int32), np.zeros(0, np.int32), 0)
        self.assertIn("rename it", light_groups.refusal(layers, "gauss_seidel", False, True, 0, 10, 10, 1 << 30))


if __name__ == "__main__":
    unittest.main()
