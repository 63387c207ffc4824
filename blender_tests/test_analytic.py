"""Bakes against closed forms: parallel plates (form factors from Howell's catalogue) and the
furnace (a closed box with uniform emission and albedo)."""

import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402
import numpy as np  # noqa: E402

import harness  # noqa: E402
import scenes  # noqa: E402

args = harness.arguments()
addon = harness.install_addon(args.addon_zip)
pipeline = sys.modules[harness.MODULE + ".pipeline"]


def corner_to_parallel_rectangle(a, b):
    """Form factor from a differential area to a parallel a x b rectangle at unit distance whose
    corner lies straight above it (Howell's catalogue, B-1)."""
    A, B = math.sqrt(1 + a * a), math.sqrt(1 + b * b)
    return (a / A * math.atan(b / A) + b / B * math.atan(a / B)) / (2 * math.pi)


def point_to_unit_square(x, y):
    """Factor from a point at (x, y) on the receiver to the unit square [0,1]^2 1 m above it:
    the sum of the four rectangles that meet above the point (signs handle points outside)."""
    total = 0.0
    for width in (x, 1.0 - x):
        for depth in (y, 1.0 - y):
            if width > 0 and depth > 0:
                total += corner_to_parallel_rectangle(width, depth)
    return total


def test_closed_forms_themselves():
    # The catalogue's values for a unit square 1 m away.
    assert abs(point_to_unit_square(0.5, 0.5) - 0.239456) < 1e-6
    assert abs(corner_to_parallel_rectangle(1, 1) - 0.138532) < 1e-6


def parallel_plates(rho):
    scenes.clear_scene()
    emitter = scenes.emission("Emitter", (1.0, 1.0, 1.0), 1.0)
    receiver = scenes.diffuse("Receiver", (rho, rho, rho))
    # Emitter faces down (-Z) at z = 1; the receiver, a 2 x 2 grid, faces up at z = 0.
    scenes.mesh_object("Emitter", [scenes.grid((0, 0, 1), (0, 1, 0), (1, 0, 0), 1, 1) + (0,)], [emitter])
    return scenes.mesh_object("Receiver", [scenes.grid((0, 0, 0), (1, 0, 0), (0, 1, 0), 2, 2) + (0,)], [receiver])


def test_parallel_plates():
    rho = 0.5
    receiver = parallel_plates(rho)
    scene = bpy.context.scene
    scene.radiosity.element_size = 0.05
    scene.radiosity.method = "GAUSS_SEIDEL"
    assert scene.radiosity.quality == "CUSTOM", "setting element size must switch quality to Custom"

    view_layer, depsgraph = pipeline.view_layer_and_depsgraph(scene)
    job = pipeline.BakeJob(scene, depsgraph, view_layer)
    result = job.solve()
    part = next(p for p in job.exported.parts if p.object_name == "Receiver")
    on_receiver = (result["element_polygon"] >= part.polygon_start) & (result["element_polygon"] < part.polygon_stop)
    area = result["element_area"][on_receiver]
    mean = (result["element_radiance"][on_receiver] * area[:, None]).sum(axis=0) / area.sum()
    expected_mean = rho * 0.19982
    print("receiver area mean %s, expected %.6f" % (mean, expected_mean))
    assert np.all(np.abs(mean / expected_mean - 1) < 0.01), mean
    job.write(scene)

    colors = harness.corner_colors(receiver.data, "Radiosity")
    positions = np.empty(len(receiver.data.vertices) * 3)
    receiver.data.vertices.foreach_get("co", positions)
    positions = positions.reshape(-1, 3)
    vertex = np.empty(len(receiver.data.loops), dtype=np.int64)
    receiver.data.loops.foreach_get("vertex_index", vertex)
    worst = 0.0
    for corner in range(len(vertex)):
        x, y, _ = positions[vertex[corner]]
        expected = rho * point_to_unit_square(x, y)
        error = np.abs(colors[corner] / expected - 1).max()
        worst = max(worst, error)
        print("point (%.1f, %.1f): baked %.6f, exact %.6f, error %.2f%%"
              % (x, y, colors[corner][0], expected, 100 * error))
    assert worst < 0.02, "worst corner error %.2f%%" % (100 * worst)


def test_furnace():
    rho, emitted = 0.5, 1.0
    scenes.clear_scene()
    box = scenes.furnace_box(rho, emitted, cells=4)
    summary = addon.bake(bpy.context.scene, element_size=0.125, method="GAUSS_SEIDEL", tolerance=1e-6)
    colors = harness.corner_colors(box.data, "Radiosity")
    expected = emitted / (1 - rho)
    error = np.abs(colors / expected - 1)
    print("furnace: %d corners, expected %.4f, min %.5f max %.5f, worst error %.3f%%, %d iterations"
          % (len(colors), expected, colors.min(), colors.max(), 100 * error.max(), summary["iterations"]))
    assert error.max() < 0.005


harness.run(test_closed_forms_themselves, test_parallel_plates, test_furnace)
