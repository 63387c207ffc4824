"""Faces far away from the rest of the scene (a stray triangle a million metres off). The automatic
settings follow the scene's extent (the resolution sees the elements from half its diagonal), so
one such face would set the cost of the whole bake: a 2 m room with a triangle 1e6 m away asked for
1024 x 1024 hemi-cubes turned four times. They are left out, and named. No bpy."""

import numpy as np

from . import visibility

# A vertex farther from the scene's middle than this many times the radius holding 90% of the
# vertices is far. A backdrop a few hundred metres around a 20 m level stays in.
FAR = 1000.0
SHARE_WITHIN = 0.9


def leave_out_far_polygons(exported):
    """Makes the vertices of faces far from the rest of `exported` non-finite, which the core skips,
    and returns (the set of polygons left out, warnings naming their objects)."""
    positions = exported.positions
    used = np.unique(exported.corner_vertices)
    used = used[np.isfinite(positions[used]).all(axis=1)]
    if len(used) < 2:
        return set(), []
    middle = np.median(positions[used].astype(np.float64), axis=0)
    distance = np.linalg.norm(positions[used].astype(np.float64) - middle, axis=1)
    radius = float(np.quantile(distance, SHARE_WITHIN, method="lower"))
    far_vertices = used[distance > FAR * max(radius, 1e-3)]
    if not len(far_vertices):
        return set(), []
    far_corner = np.isin(exported.corner_vertices, far_vertices)
    counts = np.diff(exported.face_offsets)
    far_polygon = np.zeros(len(counts), dtype=bool)
    np.logical_or.at(far_polygon, np.repeat(np.arange(len(counts)), counts), far_corner)
    positions[np.unique(exported.corner_vertices[far_corner])] = np.nan
    per_object = {}
    for part in exported.parts:
        count = int(far_polygon[part.polygon_start:part.polygon_stop].sum())
        if count:
            per_object[part.object_name] = per_object.get(part.object_name, 0) + count
    farthest = float(distance.max())
    items = [(name, "%d face%s" % (count, "s" if count > 1 else "")) for name, count in per_object.items()]
    warning = visibility.listing(
        "Faces up to %.3g m away, where 90%% of the scene lies within %.3g m, are left out: they would set the size, "
        "resolution and time of the whole bake; delete them or move them nearer" % (farthest, radius), "object", items)
    return set(np.flatnonzero(far_polygon).tolist()), [warning]
