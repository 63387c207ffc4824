"""Messy geometry as bought and downloaded models have it: a shelf whose mesh holds, beside its
ordinary faces, zero-area triangles, degenerate triangles (collinear points, up to 1 m long) and
slivers of aspect 10^3 to 10^9 (lying in its plane along its edges, as in real models). At every
quality it bakes in about the time of the same shelf without them, with the same light on the
ordinary faces; the faces without area are counted and named, and their corners take the light of
the shelf around them."""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402
import numpy as np  # noqa: E402

import harness  # noqa: E402
import scenes  # noqa: E402

args = harness.arguments()
addon = harness.install_addon(args.addon_zip)

SHELF = ((0.5, 0.5), 1.0, 0.6)  # corner (x, y), side, height: a 1 m plate facing up, 4 x 4 quads
ORDINARY = 16


def messy_faces():
    """(vertices, triangles, [what each is]) of the messy faces in the plate's plane."""
    (x, y), side, z = SHELF
    vertices, triangles, kinds = [], [], []

    def triangle(points, kind):
        triangles.append(len(vertices) + np.arange(3))
        vertices.extend(points)
        kinds.append(kind)

    for k in range(3):  # three corners at one point of the plate
        triangle([(x + 0.25 * (k + 1), y + 0.25, z)] * 3, "zero area")
    direction = np.array([0.8, 0.6, 0.0])
    for length in (1e-3, 0.1, 1.0):  # collinear in reals, rounded to float
        triangle([np.array((x, y, z)) + t * length * direction for t in (0.0, 0.37, 1.0)], "degenerate")
    # Slivers 1 m long outside each edge of the plate: caps (apex over 0.3 of the edge) and needles
    # (short edge at the far end), of widths 1 mm to 1 nm.
    edges = [((x, y + side), (1, 0), (0, 1)), ((x + side, y + side), (0, -1), (1, 0)),
             ((x + side, y), (-1, 0), (0, -1)), ((x, y), (0, 1), (-1, 0))]
    shapes = zip(edges, (1e3, 1e5, 1e7, 1e9), (False, True, False, True))
    for ((ox, oy), (ux, uy), (nx, ny)), aspect, needle in shapes:
        along, width = (1.0 if needle else 0.3), side / aspect
        triangle([(ox, oy, z), (ox + ux * side, oy + uy * side, z),
                  (ox + ux * along + nx * width, oy + uy * along + ny * width, z)], "sliver 1e%d" % np.log10(aspect))
    return np.array(vertices, dtype=np.float64), np.array(triangles), kinds


def shelf_scene(messy):
    """The room lit by its panel, with the shelf (its messy faces after the ordinary ones if `messy`)."""
    scenes.room_with_panel(0.5)
    (x, y), side, z = SHELF
    pieces = [scenes.grid((x, y, z), (side, 0, 0), (0, side, 0), 4, 4) + (0,)]
    if messy:
        vertices, triangles, _ = messy_faces()
        pieces.append((vertices, triangles, 0))
    return scenes.mesh_object("Shelf", pieces, [scenes.diffuse("Wood", (0.6, 0.5, 0.4))])


def bake(messy, quality):
    """(the shelf's corner colours, the room's, the summary, CPU seconds) of a fresh bake (CPU
    seconds of every thread: the machine's other load changes them less than wall seconds)."""
    shelf = shelf_scene(messy)
    with harness.Stopwatch() as seconds:
        summary = addon.bake(bpy.context.scene, quality=quality)
    room = harness.corner_colors(bpy.data.objects["Room"].data, "Radiosity")
    return harness.corner_colors(shelf.data, "Radiosity"), room, summary, seconds.cpu


def test_messy_faces_bake_like_the_clean_shelf_at_every_quality():
    for quality in ("DRAFT", "MEDIUM", "HIGH"):
        clean_shelf, clean_room, clean, clean_seconds = bake(False, quality)
        shelf, room, summary, seconds = bake(True, quality)
        ordinary = 4 * ORDINARY
        shelf_error = np.abs(shelf[:ordinary] - clean_shelf).max() / clean_shelf.mean()
        room_error = np.abs(room - clean_room).max() / clean_room.mean()
        print("%s: %d elements in %.1f CPU s clean, %d in %.1f CPU s messy; ordinary faces differ by at most %.2e "
              "(shelf) and %.2e (room) of their mean"
              % (quality, clean["elements"], clean_seconds, summary["elements"], seconds, shelf_error, room_error))
        # The 1 mm sliver is a real strip (5e-4 m^2): cut to its 4:1 rows up to s/32 long; the rest add
        # the few rows their length asks for.
        assert summary["elements"] <= 1.1 * clean["elements"], (summary["elements"], clean["elements"])
        assert seconds <= 1.25 * clean_seconds + 1.0, (seconds, clean_seconds)
        assert shelf_error < 0.01 and room_error < 0.01, (shelf_error, room_error)
        # The faces without area are left out, counted and named by object and face, with what to do:
        # the six of one point or in a line, and the slivers 1e-7 and 1e-9 m high, below the float
        # round-off of their coordinates (2 units in the last place: 3.6e-7 m at 1.5 m).
        warning = next(w for w in summary["warnings"] if "skipped" in w)
        named = ", ".join("Shelf face %d (zero area)" % f for f in range(ORDINARY, ORDINARY + 5))
        assert warning.startswith("8 face(s) skipped: %s and 3 more." % named), warning
        assert "Degenerate Dissolve" in warning, warning
        # Their corners (and every messy face's) show the shelf's light where they lie, not black.
        skipped = shelf[4 * ORDINARY:]
        assert (skipped > 0.5 * clean_shelf.min()).all(), skipped.reshape(-1, 3, 3)


def test_a_message_about_a_face_names_its_object_and_what_to_do():
    """A face beyond the element cap (a 1 km plate at a fixed 1 cm element size): the message names
    the object and face and points to Element Size, not the core's polygon index."""
    scenes.room_with_panel(0.5)
    scenes.mesh_object("Runway", [scenes.grid((0, 0, -1), (1000, 0, 0), (0, 1000, 0), 1, 1) + (0,)],
                       [scenes.diffuse("Tarmac", (0.3, 0.3, 0.3))])
    try:
        addon.bake(bpy.context.scene, quality="CUSTOM", element_size=0.01)
    except addon.pipeline.BakeError as error:
        message = str(error)
    else:
        raise AssertionError("a 1 km face at 1 cm elements baked")
    assert "Runway face 0" in message and "polygon" not in message.split(":")[0], message
    assert "Element Size" in message, message


harness.run(test_messy_faces_bake_like_the_clean_shelf_at_every_quality,
            test_a_message_about_a_face_names_its_object_and_what_to_do)
