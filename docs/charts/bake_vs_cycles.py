"""Chart 2 data: whole bakes, error against time, radiosity against Cycles, in one Blender run.

    blender -b --factory-startup --python-exit-code 1 --python docs/charts/bake_vs_cycles.py -- \\
        --addon-zip build/bake_radiosity.zip --csv docs/charts/bake_vs_cycles.csv

(tools/make_charts.sh runs it with its own user scripts folder; plot_bake_vs_cycles.py then draws
the chart and prints the time ratios.) Scenes:
- the Cornell box of blender_tests/scenes.py (1 m, ceiling opening of radiance 8). Every
  radiosity bake is compared on the same corners with a converged radiosity bake (1/64 m
  elements, resolution 256, tolerance 1e-6: discretisation convergence) and with Cycles' converged
  bake (physical truth); each Cycles bake is compared with Cycles' converged bake.
- a furnace (closed unit box, emission 1, reflectance 0.8): the exact answer 5 is the reference
  for both.

Gauss-Seidel is the over-relaxed one the add-on runs (the core's automatic omega); plain
Gauss-Seidel (omega 1), labelled GAUSS_SEIDEL_PLAIN, is measured beside it to show the gain. The
presets are baked with the near-field correction off and on (column near_field; the add-on
turns it on at Medium and High).

With --near-field-csv instead of --csv it measures only the evidence for the presets' near-field
choice (docs/accuracy.md): scenes.slab_over_floor at gaps of 5 mm and 2 cm, each preset with the
correction off and on, against Cycles' bake (two halves of 8192 samples), on the corners under and
around the slab and its underside; about 6 minutes.

Error: relative RMS over the corners (all three channels) not on the emitter. Time of the whole
bake (add-on export to written attribute; Cycles from the operator's call to its return), as CPU
seconds of this process (all threads: the machine this runs on is shared, and CPU time does not
count other jobs) and as wall-clock seconds. Writes one CSV row per bake."""

import argparse
import csv
import dataclasses
import math
import os
import sys
import time

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "blender_tests"))
import harness  # noqa: E402
import scenes  # noqa: E402

CYCLES_SAMPLES = (1, 4, 16, 64, 256, 1024, 4096)
# Two halves with different seeds: their mean is the reference, their difference its noise.
CYCLES_REFERENCE_SAMPLES = 16384
CORNELL_EMITTER_MATERIAL = 3
METHODS = ("GAUSS_SEIDEL", "GAUSS_SEIDEL_PLAIN", "JACOBI", "PROGRESSIVE")
PRESETS = ("DRAFT", "MEDIUM", "HIGH")
CORNELL_ELEMENT_SIZES = (1 / 8, 1 / 16, 1 / 32)
RESOLUTIONS = (64, 128, 256)
CORNELL_REFERENCE = dict(element_size=1 / 64, hemicube_resolution=256, method="GAUSS_SEIDEL",
                         tolerance=1e-6, memory_budget=8192)
FURNACE_RHO, FURNACE_EMISSION = 0.8, 1.0
FURNACE_ELEMENT_SIZES = (1 / 4, 1 / 8)
FURNACE_RESOLUTIONS = (64, 128)
FURNACE_TOLERANCES = (1e-1, 1e-2, 1e-3, 1e-4, 1e-5)
FIELDS = ("scene", "renderer", "method", "quality", "near_field", "element_size", "resolution", "tolerance", "samples",
          "elements", "cpu_seconds", "seconds", "error_converged", "error_truth")


def arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    parser = argparse.ArgumentParser()
    parser.add_argument("--addon-zip", required=True)
    target = parser.add_mutually_exclusive_group(required=True)
    target.add_argument("--csv")
    target.add_argument("--near-field-csv")
    return parser.parse_args(argv)


def install_addon(zip_path):
    assert bpy.ops.preferences.addon_install(filepath=os.path.abspath(zip_path), overwrite=True) == {"FINISHED"}
    assert bpy.ops.preferences.addon_enable(module="bake_radiosity") == {"FINISHED"}
    return sys.modules["bake_radiosity"]


def corner_colors(mesh, name):
    values = np.empty(len(mesh.loops) * 4, dtype=np.float32)
    mesh.color_attributes[name].data.foreach_get("color", values)
    return values.reshape(-1, 4)[:, :3].astype(np.float64)


def relative_rms(values, reference, reference_noise=0.0):
    """RMS difference relative to the reference's RMS, with the reference's own noise (relative,
    independent of the bake's error) taken out in quadrature."""
    scale = math.sqrt(np.mean(reference ** 2))
    measured = math.sqrt(np.mean((values - reference) ** 2)) / scale
    return math.sqrt(max(measured ** 2 - reference_noise ** 2, 0.0))


def kept_corners(mesh, skip_material):
    material = np.empty(len(mesh.polygons), dtype=np.int64)
    mesh.polygons.foreach_get("material_index", material)
    total = np.empty(len(mesh.polygons), dtype=np.int64)
    mesh.polygons.foreach_get("loop_total", total)
    return np.repeat(material != skip_material, total)


def setup_cycles(samples, seed):
    harness.use_unbiased_cycles(samples, seed)
    scene = bpy.context.scene
    scene.render.bake.target = "VERTEX_COLORS"


def cycles_bake(obj, samples, seed):
    """(corner colours, Stopwatch) of Cycles' Combined bake to a colour attribute."""
    setup_cycles(samples, seed)
    attributes = obj.data.color_attributes
    name = "Cycles"
    if name in attributes:
        attributes.remove(attributes[name])
    attributes.active_color = attributes.new(name, "FLOAT_COLOR", "CORNER")
    for other in bpy.context.view_layer.objects:
        other.select_set(False)
    obj.select_set(True)
    bpy.context.view_layer.objects.active = obj
    with harness.Stopwatch() as seconds:
        assert bpy.ops.object.bake(type="COMBINED", target="VERTEX_COLORS") == {"FINISHED"}
    return corner_colors(obj.data, name), seconds


def radiosity_bake(addon, obj, method=None, near_field=None, **settings):
    """(corner colours, Stopwatch, summary) of a whole add-on bake without the final gather (this
    chart compares the solutions); method GAUSS_SEIDEL_PLAIN is Gauss-Seidel without
    over-relaxation; near_field True or False overrides the presets' own."""
    if method is not None:
        settings["method"] = "GAUSS_SEIDEL" if method == "GAUSS_SEIDEL_PLAIN" else method
    auto_settings = sys.modules["bake_radiosity.engine.auto_settings"]
    omega = 1.0 if method == "GAUSS_SEIDEL_PLAIN" else auto_settings.AUTOMATIC_OVER_RELAXATION
    presets = auto_settings.PRESETS if near_field is None else {
        name: dataclasses.replace(preset, near_field=near_field) for name, preset in auto_settings.PRESETS.items()}
    with harness.patched_setting("AUTOMATIC_OVER_RELAXATION", omega), harness.patched_setting("PRESETS", presets), \
            harness.Stopwatch() as seconds:
        summary = addon.bake(bpy.context.scene, attribute_name="Radiosity", final_gather=False, **settings)
    return corner_colors(obj.data, "Radiosity"), seconds, summary


def row(scene, renderer, seconds, error_converged, error_truth, **fields):
    entry = dict(scene=scene, renderer=renderer, cpu_seconds="%.4f" % seconds.cpu, seconds="%.4f" % seconds.wall,
                 error_converged="%.6g" % error_converged, error_truth="%.6g" % error_truth)
    entry.update({k: ("%.6g" % v if isinstance(v, float) else v) for k, v in fields.items()})
    print(entry, flush=True)
    return entry


def cornell_rows(addon):
    scenes.clear_scene()
    box = scenes.cornell_box("MESH")
    keep = kept_corners(box.data, CORNELL_EMITTER_MATERIAL)

    halves = [cycles_bake(box, CYCLES_REFERENCE_SAMPLES, seed)[0][keep] for seed in (101, 102)]
    cycles_reference = 0.5 * (halves[0] + halves[1])
    # The halves' difference has twice each half's variance; the mean has half of it.
    cycles_noise = relative_rms(halves[0], halves[1]) / 2
    colors, seconds, summary = radiosity_bake(addon, box, **CORNELL_REFERENCE)
    radiosity_reference = colors[keep]
    gap = relative_rms(radiosity_reference, cycles_reference, cycles_noise)
    print("Cornell references: Cycles %d samples (noise %.3f%%), radiosity %d elements in %.1f s; they differ "
          "by %.2f%%" % (2 * CYCLES_REFERENCE_SAMPLES, 100 * cycles_noise, summary["elements"], seconds.wall,
                         100 * gap), flush=True)
    rows = [row("cornell", "radiosity_reference", seconds, 0.0, gap, method="GAUSS_SEIDEL", quality="CUSTOM",
                element_size=CORNELL_REFERENCE["element_size"], resolution=256, tolerance=1e-6,
                elements=summary["elements"])]

    for method in METHODS:
        for resolution in RESOLUTIONS:
            for element_size in CORNELL_ELEMENT_SIZES:
                colors, seconds, summary = radiosity_bake(addon, box, method=method, element_size=element_size,
                                                          hemicube_resolution=resolution, tolerance=1e-4)
                rows.append(row("cornell", "radiosity", seconds, relative_rms(colors[keep], radiosity_reference),
                                relative_rms(colors[keep], cycles_reference, cycles_noise), method=method,
                                quality="CUSTOM", element_size=element_size, resolution=resolution,
                                tolerance=1e-4, elements=summary["elements"]))
    for near_field in (False, True):
        for quality in PRESETS:
            colors, seconds, summary = radiosity_bake(addon, box, quality=quality, near_field=near_field)
            rows.append(row("cornell", "radiosity", seconds, relative_rms(colors[keep], radiosity_reference),
                            relative_rms(colors[keep], cycles_reference, cycles_noise),
                            method=summary["method"].upper(), quality=quality, near_field=int(summary["near_field"]),
                            element_size=summary["element_size"], resolution=summary["resolution"],
                            tolerance=summary["tolerance"], elements=summary["elements"]))
    for samples in CYCLES_SAMPLES:
        colors, seconds = cycles_bake(box, samples, seed=samples)
        error = relative_rms(colors[keep], cycles_reference, cycles_noise)
        rows.append(row("cornell", "cycles", seconds, error, error, samples=samples))
    return rows


def furnace_rows(addon):
    scenes.clear_scene()
    box = scenes.furnace_box(FURNACE_RHO, FURNACE_EMISSION, cells=4)
    exact = np.full((len(box.data.loops), 3), FURNACE_EMISSION / (1 - FURNACE_RHO))
    rows = []
    for method in METHODS:
        for resolution in FURNACE_RESOLUTIONS:
            for element_size in FURNACE_ELEMENT_SIZES:
                for tolerance in FURNACE_TOLERANCES:
                    colors, seconds, summary = radiosity_bake(addon, box, method=method, element_size=element_size,
                                                              hemicube_resolution=resolution, tolerance=tolerance)
                    error = relative_rms(colors, exact)
                    rows.append(row("furnace", "radiosity", seconds, error, error, method=method, quality="CUSTOM",
                                    element_size=element_size, resolution=resolution, tolerance=tolerance,
                                    elements=summary["elements"]))
    for samples in CYCLES_SAMPLES:
        colors, seconds = cycles_bake(box, samples, seed=samples)
        error = relative_rms(colors, exact)
        rows.append(row("furnace", "cycles", seconds, error, error, samples=samples))
    return rows


SLAB_GAPS = (0.005, 0.02)
SLAB_CYCLES_SAMPLES = 8192
SLAB_FIELDS = ("gap", "quality", "near_field", "elements", "element_size", "resolution", "cpu_seconds", "error",
               "mean_error")


def slab_rows(addon):
    rows = []
    for gap in SLAB_GAPS:
        scenes.clear_scene()
        slab = scenes.slab_over_floor(gap)
        around = scenes.under_and_around_slab(harness.corner_positions(slab.data), gap)
        halves = [cycles_bake(slab, SLAB_CYCLES_SAMPLES, seed)[0][around] for seed in (1, 2)]
        reference = 0.5 * (halves[0] + halves[1])
        noise = relative_rms(halves[0], halves[1]) / 2
        for quality in ("DRAFT", "MEDIUM", "HIGH"):
            for near_field in (False, True):
                colors, seconds, summary = radiosity_bake(addon, slab, quality=quality, near_field=near_field)
                entry = dict(gap=gap, quality=quality, near_field=int(near_field), elements=summary["elements"],
                             element_size="%.4g" % summary["element_size"], resolution=summary["resolution"],
                             cpu_seconds="%.3f" % seconds.cpu,
                             error="%.5f" % relative_rms(colors[around], reference, noise),
                             mean_error="%+.5f" % (colors[around].mean() / reference.mean() - 1))
                print(entry, flush=True)
                rows.append(entry)
    return rows


def main():
    args = arguments()
    addon = install_addon(args.addon_zip)
    start = time.perf_counter()
    if args.near_field_csv:
        path, fields, rows = args.near_field_csv, SLAB_FIELDS, slab_rows(addon)
    else:
        path, fields, rows = args.csv, FIELDS, furnace_rows(addon) + cornell_rows(addon)
    with open(path, "w", newline="") as out:
        writer = csv.DictWriter(out, fieldnames=fields, restval="")
        writer.writeheader()
        writer.writerows(rows)
    print("whole run %.0f s wall clock" % (time.perf_counter() - start), flush=True)


main()
