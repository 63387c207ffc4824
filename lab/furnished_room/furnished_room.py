"""A living room furnished with real third-party models (Debian's sweethome3d-furniture: sofa,
tables, chairs, bookcase, books, plants) inside walls, floor and ceiling with a window opening and
a ceiling emitter, its messy faces counted, then baked at the add-on's defaults.

    blender -b --factory-startup --python-exit-code 1 --python lab/furnished_room/furnished_room.py -- \\
        --addon-zip build/bake_radiosity.zip --work /tmp/furnished_room [--quality MEDIUM] [--save room.blend]
"""

import argparse
import os
import re
import sys
import time
import zipfile

here = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [os.path.join(here, "..", "..", "blender_tests")]

import bpy  # noqa: E402
import numpy as np  # noqa: E402
from mathutils import Matrix, Vector  # noqa: E402

import harness  # noqa: E402
import scenes  # noqa: E402

CATALOGS = "/usr/share/sweethome3d/furniture"
ROOM = (5.0, 4.0, 2.6)  # metres: x, y, height
# (object name, catalog file, model path in it, (x, y) of its footprint's centre, turn about z in
# degrees, its base's height). A model's front faces -y before the turn.
FURNITURE = [
    ("Sofa", "BlendSwap-CC-BY", "sofa3/sofa3.obj", (2.5, 3.55), 0, 0.0),
    ("Coffee table", "BlendSwap-CC-BY", "coffeeTable/coffeeTable.obj", (2.5, 2.5), 0, 0.0),
    ("Table", "BlendSwap-CC-BY", "table/table.obj", (1.1, 1.0), 0, 0.0),
    ("Chair 1", "BlendSwap-CC-BY", "chair3/chair3.obj", (1.1, 0.35), 180, 0.0),
    ("Chair 2", "BlendSwap-CC-BY", "chair3/chair3.obj", (1.1, 1.65), 0, 0.0),
    ("Bookcase", "BlendSwap-CC-BY", "bookcase/bookcase.obj", (4.8, 1.5), -90, 0.0),
    ("Book 1", "BlendSwap-CC-BY", "book/book.obj", (2.3, 2.45), 20, 0.45),
    ("Book 2", "BlendSwap-CC-BY", "book/book.obj", (1.0, 1.0), -10, 0.75),
    ("Plant", "BlendSwap-CC-0", "plantie/plantie.obj", (4.5, 3.5), 0, 0.0),
]


def arguments():
    argv = sys.argv[sys.argv.index("--") + 1:]
    parser = argparse.ArgumentParser()
    parser.add_argument("--addon-zip", required=True)
    parser.add_argument("--work", required=True)
    parser.add_argument("--quality", default=None, help="a preset; default: the scene's default")
    parser.add_argument("--save", default=None, help="save the baked scene to this .blend")
    return parser.parse_args(argv)


def catalog_size(archive, model):
    """(width, depth, height) in metres of `model` as the catalog gives it (centimetres)."""
    text = archive.read("PluginFurnitureCatalog.properties").decode("latin-1")
    number = re.search(r"^model#(\d+)=/?[^\n]*%s\s*$" % re.escape(model), text, re.M).group(1)
    return tuple(float(re.search(r"^%s#%s=(.*)$" % (key, number), text, re.M).group(1)) / 100.0
                 for key in ("width", "depth", "height"))


def extract(catalog, model, work):
    """The model's folder (OBJ, MTL, textures) unpacked under `work`; returns the OBJ's path and size."""
    with zipfile.ZipFile(os.path.join(CATALOGS, catalog + ".sh3f")) as archive:
        folder = next(n for n in archive.namelist() if n.endswith("/" + model)).rsplit("/", 1)[0]
        for name in archive.namelist():
            if name.startswith(folder + "/"):
                archive.extract(name, work)
        return os.path.join(work, folder, model.rsplit("/", 1)[1]), catalog_size(archive, model)


def import_model(name, path, size, centre, turn, base):
    """The OBJ as one object called `name`, scaled to the catalog's size, standing at `centre`."""
    bpy.ops.object.select_all(action="DESELECT")
    bpy.ops.wm.obj_import(filepath=path)
    parts = list(bpy.context.selected_objects)
    bpy.context.view_layer.objects.active = parts[0]
    if len(parts) > 1:
        bpy.ops.object.join()
    obj = bpy.context.view_layer.objects.active
    obj.name = name
    bpy.ops.object.transform_apply(location=True, rotation=True, scale=True)
    corners = np.array([v.co[:] for v in obj.data.vertices])
    low, high = corners.min(axis=0), corners.max(axis=0)
    scale = np.array(size) / np.maximum(high - low, 1e-9)
    obj.data.transform(Matrix.Translation(Vector(-(low + high) / 2)))
    obj.data.transform(Matrix.Diagonal(Vector(tuple(scale) + (1.0,))))
    obj.data.transform(Matrix.Rotation(np.radians(turn), 4, "Z"))
    obj.location = (centre[0], centre[1], base + size[2] / 2)
    return obj


def room_shell():
    """Floor, ceiling and four walls (0.25 m quads, normals inwards), a 1.2 x 1.2 m window opening
    in the wall x = 0, and a 1 x 0.6 m emitter 5 cm under the ceiling facing down."""
    x, y, z = ROOM
    cell = 0.25
    pieces = []
    for origin, u, v in [((0, 0, 0), (x, 0, 0), (0, y, 0)), ((0, 0, z), (0, y, 0), (x, 0, 0)),
                         ((0, 0, 0), (0, 0, z), (x, 0, 0)), ((0, y, 0), (x, 0, 0), (0, 0, z)),
                         ((x, 0, 0), (0, 0, z), (0, y, 0))]:
        cells = [int(round(np.linalg.norm(w) / cell)) for w in (u, v)]
        pieces.append(scenes.grid(origin, u, v, *cells) + (0,))
    vertices, quads = scenes.grid((0, 0, 0), (0, y, 0), (0, 0, z), int(y / 0.25), int(z / 0.2))
    centres = vertices[quads].mean(axis=1)
    window = (np.abs(centres[:, 1] - y / 2) < 0.6) & (np.abs(centres[:, 2] - 1.5) < 0.6)
    pieces.append((vertices, quads[~window], 0))
    scenes.mesh_object("Room", pieces, [scenes.diffuse("Plaster", (0.7, 0.7, 0.7))])
    scenes.mesh_object("Ceiling light", [scenes.grid((2.0, 1.7, z - 0.05), (0, 0.6, 0), (1.0, 0, 0), 1, 1) + (0,)],
                       [scenes.emission("Light", (1.0, 0.95, 0.9), 20.0)])


def messy_faces(objects):
    """Counts over the furniture's faces: longer than 1,000x their width, under 1e-7 m^2, zero area."""
    slivers = tiny = zero = 0
    for obj in objects:
        mesh = obj.data
        co = np.array([(obj.matrix_world @ v.co)[:] for v in mesh.vertices])
        for polygon in mesh.polygons:
            p = co[list(polygon.vertices)]
            twice_area = np.linalg.norm(sum(np.cross(p[k], p[(k + 1) % len(p)]) for k in range(len(p))))
            longest = max(np.linalg.norm(p[(k + 1) % len(p)] - p[k]) for k in range(len(p)))
            zero += twice_area == 0.0
            tiny += 0.5 * twice_area < 1e-7
            slivers += twice_area > 0.0 and longest * longest / twice_area > 1000.0
    return slivers, tiny, zero


def main():
    args = arguments()
    addon = harness.install_addon(args.addon_zip)
    scenes.clear_scene()
    room_shell()
    furniture = [import_model(name, *extract(catalog, model, args.work), centre, turn, base)
                 for name, catalog, model, centre, turn, base in FURNITURE]
    vertices = sum(len(o.data.vertices) for o in furniture)
    faces = sum(len(o.data.polygons) for o in furniture)
    slivers, tiny, zero = messy_faces(furniture)
    print("furniture: %d objects, %d vertices, %d faces: %d longer than 1,000x their width, %d under 1e-7 m^2, "
          "%d of zero area" % (len(furniture), vertices, faces, slivers, tiny, zero))
    overrides = {"quality": args.quality} if args.quality else {}
    start = time.perf_counter()
    summary = addon.bake(bpy.context.scene, **overrides)
    print("baked in %.1f s (wall): %s, %s, %d elements" % (time.perf_counter() - start, summary["quality"],
                                                           summary["method"], summary["elements"]))
    for warning in summary["warnings"]:
        print("warning:", warning)
    if args.save:
        bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(args.save))


main()
