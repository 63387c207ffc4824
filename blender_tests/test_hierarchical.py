"""The hierarchical method through the artist's paths (the operator with the panel's settings, the
batch command): a lamp close over a floor refines elements only near it and near the shadow,
the baked copies have no T-vertex cracks and no colour seams, and the light matches the inverse
square law; an emitting face's light and shadow are exact at the corners of faces that cannot
split; a block standing on the floor keeps a dark footprint and a lit floor around it. Scenes
with fog refuse the method with a clear message and change nothing."""

import math
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy  # noqa: E402
import numpy as np  # noqa: E402

import harness  # noqa: E402
import scenes  # noqa: E402

args = harness.arguments()
addon = harness.install_addon(args.addon_zip)
operators = sys.modules[harness.MODULE + ".operators"]

LAMP_HEIGHT = 1.0
RHO = 0.8


def floor_under_lamp():
    """A 2 m floor (one face, rho 0.8) under a 10 W point lamp, a small card casting a shadow."""
    scenes.clear_scene()
    floor = scenes.mesh_object("Floor", [scenes.grid((-1, -1, 0), (2, 0, 0), (0, 2, 0), 1, 1) + (0,)],
                               [scenes.diffuse("Floor", (RHO, RHO, RHO))])
    scenes.mesh_object("Card", [scenes.grid((0.2, -0.1, 0.5), (0, 0.2, 0), (0.2, 0, 0), 1, 1) + (0,)],
                       [scenes.diffuse("Card", (0.0, 0.0, 0.0))])
    lamp = bpy.data.lights.new("Lamp", "POINT")
    lamp.energy, lamp.shadow_soft_size = 10.0, 0.0
    lamp_object = bpy.data.objects.new("Lamp", lamp)
    lamp_object.location = (0.0, 0.0, LAMP_HEIGHT)
    bpy.context.scene.collection.objects.link(lamp_object)
    return floor


def boundary_length(mesh):
    """Total length of edges used by one polygon only: the outline of each face's elements; a
    T-vertex inside a face adds the split edges on both sides of it."""
    users = np.zeros(len(mesh.edges), dtype=np.int64)
    loop_edges = np.empty(len(mesh.loops), dtype=np.int64)
    mesh.loops.foreach_get("edge_index", loop_edges)
    np.add.at(users, loop_edges, 1)
    vertices = np.empty(3 * len(mesh.vertices))
    mesh.vertices.foreach_get("co", vertices)
    vertices = vertices.reshape(-1, 3)
    edges = np.empty(2 * len(mesh.edges), dtype=np.int64)
    mesh.edges.foreach_get("vertices", edges)
    edges = edges.reshape(-1, 2)
    lengths = np.linalg.norm(vertices[edges[:, 0]] - vertices[edges[:, 1]], axis=1)
    return float(lengths[users == 1].sum())


def bake_floor_copy(element_size, refine_tolerance):
    """The floor under the lamp baked hierarchically by the operator (Custom quality, the panel's
    Element Size and Refinement) into a subdivided copy; returns the copy's mesh."""
    floor = floor_under_lamp()
    settings = bpy.context.scene.radiosity
    settings.quality = "CUSTOM"
    settings.method, settings.element_size, settings.refine_tolerance = "HIERARCHICAL", element_size, refine_tolerance
    settings.target = "COPIES"
    assert bpy.ops.radiosity.bake() == {"FINISHED"}, settings.last_report
    assert "hierarchical" in settings.last_report and "leaves" in settings.last_report, settings.last_report
    return next(o for o in bpy.data.objects if o.get("radiosity_bake_copy") == floor.name).data


def test_operator_refines_where_the_light_changes_and_copies_have_no_cracks():
    mesh = bake_floor_copy(0.01, 0.01)
    # No cracks: the elements' outline is the face's own, 8 m (a T-vertex would add length).
    assert math.isclose(boundary_length(mesh), 8.0, rel_tol=1e-5), boundary_length(mesh)
    # No seams: every vertex carries one colour, whatever element's corner it is.
    colors = harness.corner_colors(mesh, "Radiosity")
    loop_vertex = np.empty(len(mesh.loops), dtype=np.int64)
    mesh.loops.foreach_get("vertex_index", loop_vertex)
    low = np.full((len(mesh.vertices), 3), np.inf)
    high = np.full((len(mesh.vertices), 3), -np.inf)
    np.minimum.at(low, loop_vertex, colors)
    np.maximum.at(high, loop_vertex, colors)
    assert np.abs(high - low).max() < 1e-6, np.abs(high - low).max()

    # Refined near the lamp and the shadow, coarse far off: far fewer elements than the finest
    # level everywhere (2 m / 2^7 = 1.6 cm: 128 x 128 faces).
    areas = np.array([p.area for p in mesh.polygons])
    centres = np.array([p.center[:] for p in mesh.polygons])
    assert len(areas) < 0.3 * 128 ** 2, len(areas)
    near, far = np.linalg.norm(centres[:, :2], axis=1) < 0.3, np.linalg.norm(centres[:, :2], axis=1) > 0.9
    # Measured: elements near the lamp 0.28 of the area of those far off (1.1 vs 3.9 cm^2).
    assert areas[near].mean() < 0.33 * areas[far].mean(), (areas[near].mean(), areas[far].mean())

    # The light: Cycles' point lamp of P watts has intensity P / (4 pi) per unit radiance
    # (docs/design.md); L = rho I cos / (pi r^2) at vertices far from the shadow.
    vertices = np.empty(3 * len(mesh.vertices))
    mesh.vertices.foreach_get("co", vertices)
    vertices = vertices.reshape(-1, 3)
    intensity = 10.0 / (4.0 * math.pi)
    r2 = (vertices ** 2).sum(axis=1) - 2 * vertices[:, 2] * LAMP_HEIGHT + LAMP_HEIGHT ** 2
    exact = RHO * intensity * LAMP_HEIGHT / np.sqrt(r2) / (math.pi * r2)
    lit = (vertices[:, 0] < 0.3) & (np.abs(vertices[:, :2]).max(axis=1) < 0.99)  # the card shades x > 0.4
    baked = high[lit, 0]
    error = np.abs(baked - exact[lit]) / exact[lit]
    print("%d copy faces, %d vertices checked: worst %.2f%%, mean %.2f%% from rho I cos / (pi r^2)"
          % (len(areas), lit.sum(), 100 * error.max(), 100 * error.mean()))
    assert np.median(error) < 0.01 and error.max() < 0.05, (np.median(error), error.max())


def test_a_lamps_shadow_is_sharp_on_coarse_elements():
    # Elements of 25 cm: the lamp's light shows as it is at every corner of the copy, and only
    # the faces along the card's shadow split further (twice, to 6.25 cm) after the solve.
    mesh = bake_floor_copy(0.25, 0.02)
    colors = harness.corner_colors(mesh, "Radiosity")
    loop_vertex = np.empty(len(mesh.loops), dtype=np.int64)
    mesh.loops.foreach_get("vertex_index", loop_vertex)
    vertices = np.empty(3 * len(mesh.vertices))
    mesh.vertices.foreach_get("co", vertices)
    points = vertices.reshape(-1, 3)[loop_vertex]
    # The card (x 0.2 to 0.4, |y| < 0.1, half-way up) shades x 0.4 to 0.8, |y| < 0.2; nothing else
    # lights the floor (the card is black), so every corner is the lamp's light alone.
    shadowed = (points[:, 0] > 0.4) & (points[:, 0] < 0.8) & (np.abs(points[:, 1]) < 0.2)
    r2 = (points[:, 0] ** 2 + points[:, 1] ** 2 + LAMP_HEIGHT ** 2)
    exact = np.where(shadowed, 0.0, RHO * 10.0 / (4.0 * math.pi) * LAMP_HEIGHT / np.sqrt(r2) / (math.pi * r2))
    error = np.abs(colors[:, 0] - exact) / exact.max()
    print("%d faces; corners against rho I cos / (pi r^2): worst %.2e of the brightest"
          % (len(mesh.polygons), error.max()))
    assert error.max() < 1e-4, error.max()

    # Faces across the shadow's outline are 6.25 cm or finer; the rest stay coarse.
    starts = np.array([p.loop_start for p in mesh.polygons])
    counts = np.array([p.loop_total for p in mesh.polygons])
    crossing = 0
    for start, count in zip(starts, counts):
        inside = shadowed[start:start + count]
        if inside.any() and not inside.all():
            crossing += 1
            extent = np.ptp(points[start:start + count, :2], axis=0).max()
            assert extent <= 0.0625 + 1e-4, extent
    assert crossing >= 2 * (0.4 + 0.4) / 0.0625, crossing  # the 1.6 m outline
    # A uniform mesh at 6.25 cm would have 32 x 32 faces.
    assert len(mesh.polygons) < 0.5 * 32 ** 2, len(mesh.polygons)


def point_under_rectangle_corner(a, b, c):
    """Form factor from a point to a parallel a x b rectangle c above it, the point under one of
    its corners (Howell's catalogue, B-11)."""
    A, B = a / c, b / c
    sa, sb = math.sqrt(1 + A * A), math.sqrt(1 + B * B)
    return (A / sa * math.atan(B / sa) + B / sb * math.atan(A / sb)) / (2 * math.pi)


def test_an_emitting_faces_light_and_shadow_are_exact_at_coarse_corners():
    # A 2 x 1 m floor, a 1.2 x 1 m emitting face 0.5 m over its left half and a black card across
    # its middle, 1 cm clear of it: the emitter is all in view from the floor's left corners and
    # all hidden from its right ones. With elements as large as the faces, the copy's corners
    # show rho L F at the left and nothing at the right, where the face's mean would show one
    # colour at all four.
    scenes.clear_scene()
    floor = scenes.mesh_object("Floor", [scenes.grid((0, 0, 0), (2, 0, 0), (0, 1, 0), 1, 1) + (0,)],
                               [scenes.diffuse("Floor", (RHO, RHO, RHO))])
    scenes.mesh_object("Emitter", [scenes.grid((-0.3, 0, 0.5), (0, 1, 0), (1.2, 0, 0), 1, 1) + (0,)],
                       [scenes.emission("Emitter", (1.0, 1.0, 1.0), 1.0)])
    scenes.mesh_object("Card", [scenes.grid((1, -1, 0.01), (0, 3, 0), (0, 0, 0.99), 1, 1) + (0,)],
                       [scenes.diffuse("Card", (0.0, 0.0, 0.0))])
    settings = bpy.context.scene.radiosity
    settings.quality, settings.method, settings.target = "CUSTOM", "HIERARCHICAL", "COPIES"
    settings.element_size, settings.refine_tolerance = 1.05, 0.01  # no face can split
    assert bpy.ops.radiosity.bake() == {"FINISHED"}, settings.last_report
    mesh = next(o for o in bpy.data.objects if o.get("radiosity_bake_copy") == floor.name).data
    assert len(mesh.polygons) == 1, len(mesh.polygons)
    colors = harness.corner_colors(mesh, "Radiosity")
    loop_vertex = np.empty(len(mesh.loops), dtype=np.int64)
    mesh.loops.foreach_get("vertex_index", loop_vertex)
    vertices = np.empty(3 * len(mesh.vertices))
    mesh.vertices.foreach_get("co", vertices)
    x = vertices.reshape(-1, 3)[loop_vertex, 0]
    lit = RHO * (point_under_rectangle_corner(0.3, 1, 0.5) + point_under_rectangle_corner(0.9, 1, 0.5))
    exact = np.where(x < 1, lit, 0.0)
    print("emitter over a one-face floor: corners %s against rho L F %s" % (colors[:, 0].round(5), exact.round(5)))
    assert np.abs(colors[:, 0] - exact).max() < 1e-3 * lit, colors[:, 0]


def test_batch_command_bakes_hierarchically():
    floor_under_lamp()
    path = os.path.join(args.work, "hierarchical.blend")
    bpy.ops.wm.save_as_mainfile(filepath=path)
    run = subprocess.run(harness.batch_command(path, "--output", path, "--method", "HIERARCHICAL",
                                               "--element-size", "0.05", "--refine-tolerance", "0.02"),
                         capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr
    assert "hierarchical" in run.stdout and "leaves" in run.stdout, run.stdout


def test_batch_command_keeps_the_hierarchy_within_the_memory_budget():
    # Uncapped, the Cornell box at 2 cm elements and refinement 0.01 takes tens of MB of elements
    # and links; with a 1 MB budget refinement stops there, the bake still finishes and says why.
    scenes.clear_scene()
    scenes.cornell_box("MESH")
    path = os.path.join(args.work, "hierarchical_budget.blend")
    bpy.ops.wm.save_as_mainfile(filepath=path)
    run = subprocess.run(harness.batch_command(path, "--output", path, "--method", "HIERARCHICAL",
                                               "--element-size", "0.02", "--refine-tolerance", "0.01",
                                               "--memory-budget", "1"),
                         capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr
    assert "Refinement stopped at the Memory Budget (1 MB of elements and links)" in run.stdout, run.stdout
    assert "hierarchical" in run.stdout and "leaves" in run.stdout, run.stdout


def test_copies_keep_a_blocks_footprint_dark_and_the_floor_around_it_lit():
    # A black box standing on a floor under a sun straight down: the floor is exactly rho E / pi
    # outside the footprint and 0 inside. The copy's corners must not blend the two along the
    # outline (before: the footprint's corners at 0.84 of the lit floor, the lit ones 21% dark).
    scenes.clear_scene()
    floor = scenes.mesh_object("Floor", [scenes.grid((-1, -1, 0), (2, 0, 0), (0, 2, 0), 1, 1) + (0,)],
                               [scenes.diffuse("Floor", (RHO, RHO, RHO))])
    low, high = 0.13, 0.53
    scenes.mesh_object("Box", scenes.block((low, low), (high, high), 0.4, 0.4),
                       [scenes.diffuse("Box", (0.0, 0.0, 0.0))])
    sun = bpy.data.lights.new("Sun", "SUN")
    sun.energy, sun.angle = 3.0, 0.0
    bpy.context.scene.collection.objects.link(bpy.data.objects.new("Sun", sun))  # unrotated: straight down
    settings = bpy.context.scene.radiosity
    settings.quality = "CUSTOM"
    settings.method, settings.element_size, settings.refine_tolerance = "HIERARCHICAL", 0.12, 0.02
    settings.target = "COPIES"
    assert bpy.ops.radiosity.bake() == {"FINISHED"}

    mesh = next(o for o in bpy.data.objects if o.get("radiosity_bake_copy") == floor.name).data
    corners = harness.corner_positions(mesh)
    colors = harness.corner_colors(mesh, "Radiosity")
    loop_face = np.repeat(np.arange(len(mesh.polygons)), [p.loop_total for p in mesh.polygons])
    centres = np.array([p.center[:] for p in mesh.polygons])[loop_face]
    in_footprint = (np.abs(centres[:, :2] - (low + high) / 2) < (high - low) / 2).all(axis=1)
    within_outline = (np.abs(corners[:, :2] - (low + high) / 2) <= (high - low) / 2 + 1e-6).all(axis=1)
    lit = RHO * 3.0 / math.pi
    # Corners of faces outside the footprint that lie on its outline: the lit side.
    on_lit_side = ~in_footprint & within_outline
    dark_side, lit_side = colors[in_footprint].max(), np.abs(colors[on_lit_side] - lit).max()
    print("corners on the box's outline: dark side %.2e, lit side %.2e of rho E / pi"
          % (dark_side / lit, lit_side / lit))
    assert on_lit_side.sum() > 0 and in_footprint.sum() > 0
    assert dark_side < 1e-4 * lit and lit_side < 1e-4 * lit, (dark_side / lit, lit_side / lit)


def test_esc_while_the_hierarchy_refines_changes_nothing():
    # The worker the interactive operator runs, cancelled as Esc does once the core reports the
    # links phase (refinement, the bulk of a hierarchical bake's time).
    floor_under_lamp()
    settings = bpy.context.scene.radiosity
    settings.quality = "CUSTOM"
    settings.method, settings.element_size, settings.refine_tolerance = "HIERARCHICAL", 0.005, 0.002
    before = harness.file_state()
    view_layer, depsgraph = addon.pipeline.view_layer_and_depsgraph(bpy.context.scene)
    worker = operators._Worker(addon.pipeline.BakeJob(bpy.context.scene, depsgraph, view_layer), want_layout=False)
    worker.thread.start()
    phases = []
    deadline = time.perf_counter() + 120
    while not worker.done and time.perf_counter() < deadline:
        info = worker.monitor.snapshot()
        if info is not None and (not phases or phases[-1] != info["phase"]):
            phases.append(info["phase"])
        if phases and phases[-1] == "links":
            break
        time.sleep(0.001)
    worker.cancel()
    worker.thread.join(timeout=600)
    print("phases seen before Esc:", phases)
    assert phases and phases[-1] == "links", phases
    assert worker.done and worker.cancelled and worker.error is None, (worker.done, worker.cancelled, worker.error)
    assert harness.file_state() == before


def test_fog_refuses_the_method_and_changes_nothing():
    floor = floor_under_lamp()
    fog = scenes.fog_material()
    cube = [((0, 0, 0), (0, 1, 0), (1, 0, 0)), ((0, 0, 1), (1, 0, 0), (0, 1, 0)),
            ((0, 0, 0), (1, 0, 0), (0, 0, 1)), ((0, 1, 0), (0, 0, 1), (1, 0, 0)),
            ((0, 0, 0), (0, 0, 1), (0, 1, 0)), ((1, 0, 0), (0, 1, 0), (0, 0, 1))]
    corner, size = np.array([-0.2, -0.2, 0.1]), 0.2
    scenes.mesh_object("Fog", [scenes.grid(corner + size * np.array(o), size * np.array(u), size * np.array(v), 1, 1)
                               + (0,) for o, u, v in cube], [fog])
    attributes_before = len(floor.data.color_attributes)
    try:
        addon.bake(bpy.context.scene, method="HIERARCHICAL")
    except addon.pipeline.BakeError as error:
        assert "hierarchical" in str(error) and "fog" in str(error), error
    else:
        raise AssertionError("a bake with fog and the hierarchical method must refuse")
    assert len(floor.data.color_attributes) == attributes_before


def bake_cluttered_room(blocks):
    """scenes.cluttered_room with `blocks` blocks baked hierarchically into copies (element size
    0.1 m, refinement 0.02: Medium's, coarser); returns the summary and the mean
    light (area-weighted over the copy's faces, mean of R, G, B) of its walls and its floor."""
    scenes.clear_scene()
    scenes.cluttered_room(blocks)
    summary = addon.bake(bpy.context.scene, method="HIERARCHICAL", element_size=0.1, refine_tolerance=0.02,
                         tolerance=1e-4, target="COPIES")
    for mesh in bpy.data.meshes:  # no attribute anywhere may hold anything but numbers
        if "Radiosity" in mesh.color_attributes:
            colors = harness.corner_colors(mesh, "Radiosity")
            assert np.isfinite(colors).all(), "non-finite colours in %s" % mesh.name
    room = next(o for o in bpy.data.objects if o.get("radiosity_bake_copy") == "Room").data
    colors = harness.corner_colors(room, "Radiosity").mean(axis=1)
    loop_face = np.repeat(np.arange(len(room.polygons)), [p.loop_total for p in room.polygons])
    face_light = np.bincount(loop_face, colors) / np.bincount(loop_face)
    areas = np.array([p.area for p in room.polygons])
    normals = np.array([p.normal[:] for p in room.polygons])
    centres = np.array([p.center[:] for p in room.polygons])
    walls = np.abs(normals[:, 2]) < 0.5
    floor = (normals[:, 2] > 0.5) & (centres[:, 2] < 0.5)
    mean = lambda faces: float((face_light[faces] * areas[faces]).sum() / areas[faces].sum())  # noqa: E731
    return summary, mean(walls), mean(floor)


def test_a_cluttered_room_keeps_the_empty_rooms_light_and_its_power():
    # Many small props on a floor barely change a room's light (Cycles: 1,000 blocks of 2 cm leave
    # the walls 0.977x the empty room's). Here 100 blocks (1% of the floor, a contact-cut sliver
    # thinner than the weld among them): the walls keep the empty room's light within 3%, the
    # power is accounted for, and nothing is NaN.
    empty, empty_walls, empty_floor = bake_cluttered_room(0)
    start = time.perf_counter()
    summary, walls, floor = bake_cluttered_room(100)
    seconds = time.perf_counter() - start
    power = summary["energy"]
    print("100 blocks: walls %.4f x, floor %.4f x the empty room's; %.2f%% absorbed (empty: %.2f%%), %d iterations, "
          "%.1f s" % (walls / empty_walls, floor / empty_floor, 100 * power["absorbed_fraction"],
                      100 * empty["energy"]["absorbed_fraction"], summary["iterations"], seconds))
    assert summary["method"] == "hierarchical" and summary["iterations"] > 2, summary["iterations"]
    assert math.isfinite(summary["residual"]) and summary["converged"], summary["residual"]
    assert abs(walls / empty_walls - 1.0) < 0.03, walls / empty_walls
    assert abs(floor / empty_floor - 1.0) < 0.05, floor / empty_floor
    # Emitted (both sides of the 0.25 m^2 panel of radiance 10) = absorbed + escaped or on black:
    # the panel's black faces absorb what falls on them, most of what its back sends into the 1 cm
    # gap under the ceiling. Both finite, no more absorbed than emitted, and the blocks change the
    # share the walls and floor absorb by about the light they take (1% of the floor).
    assert math.isclose(power["emitted"], 2 * math.pi * 0.25 * 10.0, rel_tol=1e-3), power["emitted"]
    assert math.isfinite(power["absorbed"]) and power["absorbed_fraction"] <= 1.0, power["absorbed_fraction"]
    assert abs(power["absorbed_fraction"] - empty["energy"]["absorbed_fraction"]) < 0.03, power["absorbed_fraction"]
    assert "nan" not in bpy.context.scene.radiosity.last_accuracy, bpy.context.scene.radiosity.last_accuracy


def test_non_finite_light_is_an_error_naming_the_phase_and_the_object():
    # The core raises NumericalError (phase, input polygon) for light that is not a number; the
    # bake refuses with the object and face, and writes nothing.
    scenes.clear_scene()
    scenes.cluttered_room(4)
    view_layer, depsgraph = addon.pipeline.view_layer_and_depsgraph(bpy.context.scene)
    job = addon.pipeline.BakeJob(bpy.context.scene, depsgraph, view_layer,
                                 {"method": "HIERARCHICAL", "element_size": 0.1})
    blocks = next(p for p in job.exported.parts if p.object_name == "Blocks")
    core = addon.engine.native.core()
    original = core.bake

    def failing(*arguments, **keywords):
        assert keywords["method"] == "hierarchical"
        error = core.NumericalError("non-finite light in phase 'solve' at input polygon %d"
                                    % (blocks.polygon_start + 5))
        error.phase, error.polygon = "solve", blocks.polygon_start + 5
        raise error

    core.bake = failing
    try:
        job.solve()
    except addon.pipeline.BakeError as error:
        assert "'solve'" in str(error) and "Blocks face 5" in str(error), error
    else:
        raise AssertionError("non-finite light must fail the bake")
    finally:
        core.bake = original
    assert issubclass(core.NumericalError, RuntimeError)


def test_the_same_scene_bakes_to_the_same_colours():
    """A hierarchical bake seeds its rays by geometry, refines in a fixed order, numbers the nodes
    the threads split as one thread would and sums each node's links in the order of their
    sources: the same scene baked twice (the cluttered room with 20 blocks, threads as they come)
    gives bit-identical colours, as the uniform bake does."""
    runs = []
    for _ in range(2):
        scenes.clear_scene()
        scenes.cluttered_room(20)
        addon.bake(bpy.context.scene, method="HIERARCHICAL", element_size=0.1, refine_tolerance=0.02, tolerance=1e-4)
        runs.append({o.name: harness.corner_colors(o.data, "Radiosity") for o in bpy.data.objects
                     if o.type == "MESH" and "Radiosity" in o.data.color_attributes})
    assert runs[0].keys() == runs[1].keys() and runs[0], runs[0].keys()
    for name in runs[0]:
        assert np.array_equal(runs[0][name], runs[1][name]), (name, np.abs(runs[0][name] - runs[1][name]).max())


harness.run(test_a_cluttered_room_keeps_the_empty_rooms_light_and_its_power,
            test_the_same_scene_bakes_to_the_same_colours,
            test_non_finite_light_is_an_error_naming_the_phase_and_the_object,
            test_operator_refines_where_the_light_changes_and_copies_have_no_cracks,
            test_a_lamps_shadow_is_sharp_on_coarse_elements,
            test_an_emitting_faces_light_and_shadow_are_exact_at_coarse_corners,
            test_batch_command_bakes_hierarchically, test_batch_command_keeps_the_hierarchy_within_the_memory_budget,
            test_copies_keep_a_blocks_footprint_dark_and_the_floor_around_it_lit,
            test_esc_while_the_hierarchy_refines_changes_nothing, test_fog_refuses_the_method_and_changes_nothing)
