"""Faces the core could not use or names by index: messages that name the object and the face
within it and say what the artist can do, and colours for the corners of skipped faces."""

import re

import numpy as np

POLYGON = re.compile(r"\bpolygon (\d+)\b")
# The core's instructions in its own terms, as the artist finds them in the panel.
ADVICE = (("raise element_size", "raise Element Size (Quality: Custom), or split that face"),)
FIND_FACE = "find it in Edit Mode by its index (Spreadsheet, Face domain) and fix or delete it"
CLEAN_UP = "Mesh > Clean Up > Degenerate Dissolve removes faces without area"
SHOWN = 5


def name_faces(message, scene):
    """`message` from the core with each 'polygon N' as '<object> face n', and what to do."""
    named = POLYGON.sub(lambda m: scene.polygon_name(int(m.group(1))), message)
    if named == message:
        return message
    for core_words, artist_words in ADVICE:
        if core_words in named:
            return named.replace(core_words, artist_words)
    return "%s (%s; %s)" % (named, FIND_FACE, CLEAN_UP)


def skipped_warning(skipped, scene):
    """One warning for the skipped faces [(polygon, reason)], naming the first few; None if none."""
    if not skipped:
        return None
    names = []
    for polygon, reason in skipped[:SHOWN]:
        where = scene.polygon_name(polygon)
        names.append("%s (%s)" % ("lamp" if where == "a lamp" else where, reason))
    more = " and %d more" % (len(skipped) - SHOWN) if len(skipped) > SHOWN else ""
    return ("%d face(s) skipped: %s%s. They carry no light; their corners show the light of the faces "
            "around them. %s" % (len(skipped), ", ".join(names), more, CLEAN_UP))


def fill_skipped_corners(corner_rgb, scene, skipped_polygons):
    """`corner_rgb` (C,3) with the corners of the skipped polygons coloured by the surface they lie
    in: each the mean colour of the other faces' corners at the same point (their vertex, or one at
    the same position); a corner at no such point takes the mean of its face's corners that got one;
    a face with none keeps its colours. Returns the new array."""
    counts = np.diff(scene.face_offsets)
    polygon_of_corner = np.repeat(np.arange(len(counts)), counts)
    skipped = np.zeros(len(counts), dtype=bool)
    skipped[np.asarray(list(skipped_polygons), dtype=np.int64)] = True
    from_skipped = skipped[polygon_of_corner]
    if not from_skipped.any():
        return corner_rgb
    point = _points(scene)
    sums, seen = np.zeros((point.max(initial=-1) + 1, 3)), np.zeros(point.max(initial=-1) + 1)
    np.add.at(sums, point[~from_skipped], corner_rgb[~from_skipped])
    np.add.at(seen, point[~from_skipped], 1.0)
    filled = corner_rgb.copy()
    found = from_skipped & (seen[point] > 0.0)
    filled[found] = sums[point[found]] / seen[point[found], None]
    # Corners at no other face's point: the mean of their face's corners found above.
    face_sums, face_seen = np.zeros((len(counts), 3)), np.zeros(len(counts))
    np.add.at(face_sums, polygon_of_corner[found], filled[found])
    np.add.at(face_seen, polygon_of_corner[found], 1.0)
    rest = from_skipped & ~found & (face_seen[polygon_of_corner] > 0.0)
    filled[rest] = face_sums[polygon_of_corner[rest]] / face_seen[polygon_of_corner[rest], None]
    return filled


def _points(scene):
    """Per corner: an id of its position, shared by every corner at exactly that point (a vertex
    index out of range gets an id of its own)."""
    vertices = scene.corner_vertices.astype(np.int64)
    valid = (vertices >= 0) & (vertices < len(scene.positions))
    _, position_id = np.unique(scene.positions, axis=0, return_inverse=True)
    position_id = position_id.ravel()
    point = np.empty(len(vertices), dtype=np.int64)
    point[valid] = position_id[vertices[valid]]
    point[~valid] = len(scene.positions) + np.arange(int((~valid).sum()))
    return point
