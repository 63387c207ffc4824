"""OpenVDB input and output of `_core`, checked against Debian's pyopenvdb (OpenVDB's own
Python binding) as the independent reader and writer."""
import os
import tempfile
import unittest

import numpy as np
try:
    import openvdb as vdb  # OpenVDB 11 and later (Debian sid: 13) name the module openvdb
except ImportError:
    import pyopenvdb as vdb  # OpenVDB 10 (Debian 12, 13)

import _core


def write_block(path, voxel_size, value=2.0, size=4):
    """A size^3 block of `value` at indices [0, size) with pyopenvdb; returns the grid's mass."""
    grid = vdb.FloatGrid()
    grid.copyFromArray(np.full((size, size, size), value, dtype=np.float32))
    grid.transform = vdb.createLinearTransform(voxelSize=voxel_size)
    grid.name = "density"
    vdb.write(path, grids=[grid])
    return value * size ** 3 * voxel_size ** 3


class ReadTest(unittest.TestCase):
    def setUp(self):
        self.folder = tempfile.TemporaryDirectory()
        self.path = os.path.join(self.folder.name, "block.vdb")

    def tearDown(self):
        self.folder.cleanup()

    def test_lists_grids(self):
        write_block(self.path, 0.25)
        self.assertEqual(_core.vdb_grids(self.path), [["density", "float"]])

    def test_aligned_cells_keep_values_and_mass(self):
        mass = write_block(self.path, 0.25)
        grid = _core.read_vdb_grid(self.path, "density", np.eye(4), 0.25)
        values = grid["values"]
        # Voxel centres at i * 0.25 for i in 0..3, widened by one voxel: cells run from centre to
        # centre, where the trilinear reconstruction is linear, so their averages are exact.
        self.assertEqual(values.shape, (5, 5, 5))
        np.testing.assert_allclose(grid["origin"], [-0.25] * 3)
        np.testing.assert_allclose(values[1:4, 1:4, 1:4], 2.0, rtol=1e-6)
        np.testing.assert_allclose(values[0, 1:4, 1:4], 1.0, rtol=1e-6)  # half way to the empty voxel
        self.assertAlmostEqual(float(values.sum()) * 0.25 ** 3, mass, places=6)

    def test_object_matrix_moves_and_scales(self):
        mass = write_block(self.path, 0.25)
        matrix = np.diag([2.0, 2.0, 2.0, 1.0])
        matrix[:3, 3] = (1.0, 2.0, 3.0)
        grid = _core.read_vdb_grid(self.path, "density", matrix, 0.5)
        np.testing.assert_allclose(grid["origin"], [1.0 - 0.5, 2.0 - 0.5, 3.0 - 0.5])
        # Density is per metre in the object's space; the mass the medium holds scales with volume.
        self.assertAlmostEqual(float(grid["values"].sum()) * 0.5 ** 3, mass * 8.0, places=4)

    def test_missing_grid_is_named(self):
        write_block(self.path, 0.25)
        with self.assertRaisesRegex(_core.FileError, "no grid 'temperature'"):
            _core.read_vdb_grid(self.path, "temperature", np.eye(4), 0.25)
        with self.assertRaisesRegex(_core.FileError, "cannot open OpenVDB file"):
            _core.read_vdb_grid(os.path.join(self.folder.name, "missing.vdb"), "density", np.eye(4), 0.25)


def cube_mesh(lo, hi):
    """A closed axis-aligned box as six quads (outward normals)."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    v = np.array([[x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0],
                  [x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]], dtype=np.float32)
    quads = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]]
    return v, np.arange(0, 25, 4, dtype=np.int32), np.array(quads, dtype=np.int32).ravel()


def uv_sphere(radius, rings=48, segments=96):
    """A closed UV sphere: quads between rings, triangles at the poles."""
    theta = np.linspace(0, np.pi, rings + 1)[1:-1]
    phi = np.linspace(0, 2 * np.pi, segments, endpoint=False)
    ring = np.stack([np.outer(np.sin(theta), np.cos(phi)), np.outer(np.sin(theta), np.sin(phi)),
                     np.outer(np.cos(theta), np.ones_like(phi))], axis=-1).reshape(-1, 3)
    v = np.vstack([[0, 0, 1], ring, [0, 0, -1]]) * radius
    faces = []
    for s in range(segments):
        t = (s + 1) % segments
        faces.append([0, 1 + s, 1 + t])
        for r in range(rings - 2):
            a, b = 1 + r * segments, 1 + (r + 1) * segments
            faces.append([a + s, b + s, b + t, a + t])
        last = 1 + (rings - 2) * segments
        faces.append([last + t, last + s, len(v) - 1])
    offsets = np.cumsum([0] + [len(f) for f in faces]).astype(np.int32)
    return v.astype(np.float32), offsets, np.concatenate(faces).astype(np.int32)


class VoxelizeTest(unittest.TestCase):
    def test_box_fills_whole_cells(self):
        grid = _core.voxelize_mesh(*cube_mesh((0, 0, 0), (1.0, 0.5, 0.75)), 0.25)
        self.assertEqual(grid["values"].shape, (3, 2, 4))
        np.testing.assert_allclose(grid["values"], 1.0)
        np.testing.assert_allclose(grid["origin"], (0, 0, 0))

    def test_sphere_volume(self):
        radius = 0.5
        grid = _core.voxelize_mesh(*uv_sphere(radius), 0.05, samples=4)
        volume = float(grid["values"].sum()) * 0.05 ** 3
        exact = 4.0 / 3.0 * np.pi * radius ** 3
        # The faceted sphere (48 x 96) holds 0.2% less than the true one; sampling adds < 0.5%.
        self.assertAlmostEqual(volume / exact, 1.0, delta=0.007)


class WriteTest(unittest.TestCase):
    def test_pyopenvdb_reads_what_we_write(self):
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "baked.vdb")
            density = np.zeros((2, 3, 4), dtype=np.float32)  # (nz, ny, nx)
            density[1, 2, 3] = 5.0
            emission = np.zeros((2, 3, 4, 3), dtype=np.float32)
            emission[0, 1, 2] = (0.1, 0.2, 0.3)
            _core.write_vdb(path, (1.0, 2.0, 3.0), 0.5, {"density": density, "emission": emission})
            grids = {g.name: g for g in vdb.readAll(path)[0]}
            self.assertEqual(grids["density"].activeVoxelCount(), 1)
            self.assertEqual(grids["density"].getConstAccessor().getValue((3, 2, 1)), 5.0)
            np.testing.assert_allclose(grids["emission"].getConstAccessor().getValue((2, 1, 0)), (0.1, 0.2, 0.3),
                                       rtol=1e-6)
            # Voxel (0, 0, 0)'s centre is the first cell's centre.
            np.testing.assert_allclose(grids["density"].transform.indexToWorld((0, 0, 0)), (1.25, 2.25, 3.25))


if __name__ == "__main__":
    unittest.main()
