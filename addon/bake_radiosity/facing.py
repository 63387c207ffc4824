"""Faces modelled with their normals turned away from the light, as in a room built with outward
normals. A bake, like Cycles' own Combined bake, lights the side a face's normal points to (a colour
attribute holds one value a corner), so these come out black, while renders light both sides.
Measured on a closed 2 m room lit by a panel inside: with inward normals the room's mean corner
radiance is 0.0872 (Cycles' bake 0.0870), with outward normals 0 in both. Found after the solve
and named, so that the artist flips them rather than wonders."""

import numpy as np
from mathutils import Vector
from mathutils.bvhtree import BVHTree

from . import visibility
from .engine import polygons

# A corner this much below the brightest corner of the bake counts as black.
BLACK = 1e-6
# Light sources a face's back is tested against: the brightest emitting polygons and the lamps.
MOST_SOURCES = 64


def turned_away_warnings(exported, corner_radiance):
    """A warning naming the objects with faces that bake black while light reaches their back
    directly (with how many such faces each), or [] if there are none."""
    black = _black_reflecting_polygons(exported, corner_radiance)
    if not black.any():
        return []
    normals, areas = polygons.polygon_normals_areas(exported.positions, exported.face_offsets, exported.corner_vertices)
    centres = _polygon_centres(exported)
    sources = _light_sources(exported, centres, areas)
    if not sources:
        return []
    tree = _tree(exported)
    counts = {}
    for polygon in np.flatnonzero(black):
        if _lit_from_behind(tree, centres[polygon], normals[polygon], areas[polygon], sources):
            part = next(p for p in exported.parts if p.polygon_start <= polygon < p.polygon_stop)
            counts[part.object_name] = counts.get(part.object_name, 0) + 1
    if not counts:
        return []
    items = [(name, "%d face%s" % (count, "s" if count > 1 else ""))
             for name, count in sorted(counts.items(), key=lambda c: -c[1])]
    return [visibility.listing("Faces turned away from all light bake black while light reaches their back (renders "
                               "light both sides, a bake the side the normal shows, as Cycles' bake does): flip their "
                               "normals (Mesh > Normals > Flip, or Recalculate Inside for a room)", "object", items)]


def _black_reflecting_polygons(exported, corner_radiance):
    """Per polygon: whether it reflects (and does not emit) and all its corners baked black."""
    counts = np.diff(exported.face_offsets)
    polygon_of_corner = np.repeat(np.arange(len(counts)), counts)
    brightest = np.zeros(len(counts))
    np.maximum.at(brightest, polygon_of_corner, np.nan_to_num(corner_radiance.max(axis=1), nan=np.inf))
    scale = float(np.nan_to_num(corner_radiance, nan=0.0, posinf=0.0).max(initial=0.0))
    in_parts = np.zeros(len(counts), dtype=bool)
    for part in exported.parts:
        in_parts[part.polygon_start:part.polygon_stop] = True
    finite = np.isfinite(exported.positions[exported.corner_vertices]).all(axis=1)
    finite_polygon = np.ones(len(counts), dtype=bool)
    np.logical_and.at(finite_polygon, polygon_of_corner, finite)
    return (in_parts & finite_polygon & (scale > 0.0) & (brightest <= BLACK * scale)
            & (exported.reflectance.max(axis=1) > 0.0) & ~(exported.emission.max(axis=1) > 0.0))


def _polygon_centres(exported):
    counts = np.diff(exported.face_offsets)
    polygon_of_corner = np.repeat(np.arange(len(counts)), counts)
    sums = np.zeros((len(counts), 3))
    np.add.at(sums, polygon_of_corner, exported.positions[exported.corner_vertices].astype(np.float64))
    return sums / np.maximum(counts, 1)[:, None]


def _light_sources(exported, centres, areas):
    """[(point, direction)]: a point to test visibility towards (emitting polygons' centres and point
    and spot lamps), or a direction towards the light (sun lamps), the other None."""
    power = exported.emission.max(axis=1) * np.nan_to_num(areas)
    emitting = np.flatnonzero(power > 0.0)
    emitting = emitting[np.argsort(-power[emitting])][:MOST_SOURCES]
    sources = [(Vector(centres[p]), None) for p in emitting]
    for light in exported.lights[:MOST_SOURCES]:
        if light["type"] == "SUN":
            sources.append((None, -Vector(light["direction"])))
        else:
            sources.append((Vector(light["position"]), None))
    return sources


def _tree(exported):
    polygons = np.split(exported.corner_vertices, exported.face_offsets[1:-1])
    finite = np.isfinite(exported.positions).all(axis=1)
    usable = [p.tolist() for p in polygons if finite[p].all()]
    return BVHTree.FromPolygons(np.nan_to_num(exported.positions).tolist(), usable, all_triangles=False)


def _lit_from_behind(tree, centre, normal, area, sources):
    """Whether a light source lies behind the polygon's plane and nothing hides it from the centre."""
    offset = 1e-4 * max(float(np.sqrt(area)), 1e-3)
    origin = Vector(centre - offset * normal)
    back = Vector(-normal)
    for point, direction in sources:
        if point is not None:
            direction = point - origin
            distance = direction.length - offset
        else:
            distance = 1e30
        if distance <= 0.0 or direction.dot(back) <= 0.0:
            continue
        if tree.ray_cast(origin, direction.normalized(), distance)[0] is None:
            return True
    return False
