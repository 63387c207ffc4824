"""Geometry of the exported polygons, from the flat arrays alone."""

import numpy as np


def polygon_normals_areas(positions, face_offsets, corner_vertices):
    """Unit normals (F,3) and areas (F,) of planar polygons by Newell's method, vectorised."""
    starts = face_offsets[:-1]
    counts = np.diff(face_offsets)
    polygon_of_corner = np.repeat(np.arange(len(counts)), counts)
    following = np.arange(len(corner_vertices)) + 1
    last = face_offsets[1:] - 1
    following[last] = starts
    p = positions[corner_vertices].astype(np.float64)
    q = positions[corner_vertices[following]].astype(np.float64)
    twice = np.zeros((len(counts), 3))
    np.add.at(twice, polygon_of_corner, np.cross(p, q))
    length = np.linalg.norm(twice, axis=1)
    normals = twice / np.where(length > 0.0, length, 1.0)[:, None]
    return normals, 0.5 * length
