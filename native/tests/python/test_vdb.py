"""OpenVDB input and output of `_core`, checked against Debian's pyopenvdb (OpenVDB's own
Python binding) as the independent reader and writer."""
import os
import tempfile
import unittest

import numpy as np
import pyopenvdb as vdb

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
        with self.assertRaisesRegex(RuntimeError, "no grid 'temperature'"):
            _core.read_vdb_grid(self.path, "temperature", np.eye(4), 0.25)
        with self.assertRaisesRegex(RuntimeError, "cannot open OpenVDB file"):
            _core.read_vdb_grid(os.path.join(self.folder.name, "missing.vdb"), "density", np.eye(4), 0.25)


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
            np.testing.assert_allclose(grids["emission"].getConstAccessor().getValue((2, 1, 0)), (0.1, 0.2, 0.3), rtol=1e-6)
            # Voxel (0, 0, 0)'s centre is the first cell's centre.
            np.testing.assert_allclose(grids["density"].transform.indexToWorld((0, 0, 0)), (1.25, 2.25, 3.25))


if __name__ == "__main__":
    unittest.main()
