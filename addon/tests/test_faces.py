"""bake_radiosity.engine.faces: the core's polygon indices as object faces with what to do, and
the corners of skipped faces coloured by the faces around them."""
import unittest

import numpy as np

from bake_radiosity.engine import faces
from bake_radiosity.engine.scene import ExportedScene, Part


def two_objects():
    """'Floor': a quad (face 0) and a zero-area triangle on its edge (face 1, corners on vertices
    0 and 1 and a vertex of its own, 4); 'Shelf': one triangle (face 0), flat index 2."""
    positions = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0.5, 0, 0],
                          [0, 0, 1], [1, 0, 1], [0, 1, 1]], dtype=np.float32)
    corner_vertices = np.array([0, 1, 2, 3, 0, 4, 1, 5, 6, 7], dtype=np.int32)
    face_offsets = np.array([0, 4, 7, 10], dtype=np.int32)

    def part(name, start, stop, corner_start, corner_stop):
        return Part(object_name=name, mesh_name=name, is_instance=False, polygon_start=start, polygon_stop=stop,
                    corner_start=corner_start, corner_stop=corner_stop, corner_order=np.arange(0),
                    polygon_material_index=np.zeros(stop - start, dtype=np.int32), material_names=[],
                    matrix_world=np.eye(4))

    return ExportedScene(positions=positions, face_offsets=face_offsets, corner_vertices=corner_vertices,
                         reflectance=np.full((3, 3), 0.5, dtype=np.float32), emission=np.zeros((3, 3), np.float32),
                         material=np.zeros(3, dtype=np.int32), front_only=np.zeros(3, dtype=np.uint8), lights=[],
                         parts=[part("Floor", 0, 2, 0, 7), part("Shelf", 2, 3, 7, 10)])


class NameFaces(unittest.TestCase):
    def test_the_cap_message_names_the_object_face_and_the_setting(self):
        message = ("polygon 2: element_size 0.3 m would make 2.37e+06 elements from this polygon, beyond the cap "
                   "of 2097152 for the scene; raise element_size")
        named = faces.name_faces(message, two_objects())
        self.assertTrue(named.startswith("Shelf face 0: "), named)
        self.assertNotIn("polygon 2", named)
        self.assertIn("raise Element Size (Quality: Custom), or split that face", named)

    def test_any_other_face_message_says_how_to_find_the_face(self):
        named = faces.name_faces("polygon 1: reflectance 1.2 outside [0, 1)", two_objects())
        self.assertEqual(named, "Floor face 1: reflectance 1.2 outside [0, 1) (%s; %s)"
                         % (faces.FIND_FACE, faces.CLEAN_UP))

    def test_a_message_about_no_face_is_left_alone(self):
        self.assertEqual(faces.name_faces("resolution must be even", two_objects()), "resolution must be even")


class SkippedFaces(unittest.TestCase):
    def test_the_warning_counts_names_and_says_what_to_do(self):
        skipped = [(1, "zero area")] + [(2, "zero area")] * 5
        warning = faces.skipped_warning(skipped, two_objects())
        self.assertTrue(warning.startswith("6 face(s) skipped: Floor face 1 (zero area), Shelf face 0"), warning)
        self.assertIn("Shelf face 0 (zero area) and 1 more.", warning)
        self.assertIn("Degenerate Dissolve", warning)
        self.assertIsNone(faces.skipped_warning([], two_objects()))

    def test_skipped_corners_take_the_colour_of_the_faces_on_their_vertex(self):
        scene = two_objects()
        rgb = np.zeros((10, 3))
        rgb[0:4] = [[1, 1, 1], [2, 2, 2], [3, 3, 3], [4, 4, 4]]  # the quad
        rgb[7:10] = 9.0  # the shelf
        filled = faces.fill_skipped_corners(rgb, scene, [1])
        # Corners 4 and 6 sit on the quad's vertices 0 and 1; corner 5 (vertex 4) on no other face's
        # point takes the mean of the other two.
        np.testing.assert_array_equal(filled[4:7], [[1, 1, 1], [1.5, 1.5, 1.5], [2, 2, 2]])
        np.testing.assert_array_equal(filled[:4], rgb[:4])
        np.testing.assert_array_equal(filled[7:], rgb[7:])

    def test_a_vertex_at_the_same_position_counts_as_the_same_point(self):
        scene = two_objects()
        scene.positions[4] = scene.positions[2]  # vertex 4 now where the quad's corner 2 is
        rgb = np.zeros((10, 3))
        rgb[2] = 3.0
        self.assertEqual(faces.fill_skipped_corners(rgb, scene, [1])[5].tolist(), [3.0, 3.0, 3.0])

    def test_a_face_on_no_other_face_keeps_its_colours(self):
        scene = two_objects()
        rgb = np.arange(30, dtype=np.float64).reshape(10, 3)
        np.testing.assert_array_equal(faces.fill_skipped_corners(rgb, scene, [2])[7:], rgb[7:])

    def test_a_vertex_shared_by_faces_takes_their_mean(self):
        scene = two_objects()
        scene.corner_vertices[7] = 0  # the shelf's first corner now on the quad's vertex 0 too
        rgb = np.zeros((10, 3))
        rgb[0] = 1.0
        rgb[7] = 3.0
        self.assertEqual(faces.fill_skipped_corners(rgb, scene, [1])[4].tolist(), [2.0, 2.0, 2.0])


if __name__ == "__main__":
    unittest.main()
