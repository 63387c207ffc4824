"""The race against Cycles, in one Blender run: Cycles at a ladder of sample counts and
the add-on's whole bakes at Draft, Medium and High with the final gather on and off, each timed,
each judged against a deep Cycles truth of the same corners (lab/truth/deep_cycles.py, cached
outside git and made when missing); then the error against the solution's element count (Medium's
settings at other element sizes), with and without the gather.

    blender -b --factory-startup --python-exit-code 1 --python docs/charts/cycles_race.py -- \\
        --addon-zip build/bake_radiosity.zip --csv docs/charts/cycles_race.csv \\
        --summary docs/charts/cycles_race.txt [--truth-cache DIR] [--configs 16/4/4096,24/6/1024]

(tools/make_charts.sh cycles_race runs it, then plot_cycles_race.py draws cycles_race.png and
cycles_race_elements.png.) Scene: the Cornell box of blender_tests/scenes.py (emitting opening),
the mesh the add-on's bakes and Cycles both write to.

Error: relative RMS luminance error per vertex (lab/truth/vertex_error.py: corner colours averaged
per vertex, the emitter's corners left out, vertices the truth sees below 1% of the mean left
out), as measured and with the truth's own noise taken out in quadrature. Cycles' error includes
its own noise: that is what an artist gets. Time: CPU seconds of this process (all threads) and
wall seconds, from the call to its return. For every bake, the Cycles time to the same error is
interpolated on Cycles' error against time in log-log (fastest-so-far bakes), extrapolated along
its last two bakes below the ladder's end (marked), and the ratio is Cycles' time / the bake's.

--configs adds bakes at other settings: divisions/cells/gather rays, Medium's tolerance and near
field, gather on (auto_settings.PRESETS and GATHER_RAYS patched for the bake)."""

import argparse
import csv
import dataclasses
import os
import sys
import time

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "blender_tests"))
sys.path.insert(0, os.path.join(HERE, "..", "..", "lab", "truth"))
import deep_cycles  # noqa: E402
import harness  # noqa: E402
import scenes  # noqa: E402
import vertex_error  # noqa: E402

CYCLES_SAMPLES = (16, 64, 256, 1024, 4096, 16384, 32768)
PRESETS = ("DRAFT", "MEDIUM", "HIGH")
ELEMENT_DIVISIONS = (8, 12, 16, 24, 32, 48)  # at Medium's other settings; 32 is Medium itself
FIELDS = ("kind", "quality", "final_gather", "divisions", "cells", "gather_rays", "samples", "elements", "resolution",
          "cpu_seconds", "wall_seconds", "error", "error_noise_out", "error_seams", "error_elsewhere", "error_scaled",
          "cycles_cpu_seconds_same_error",
          "ratio_cpu", "cycles_wall_seconds_same_error", "ratio_wall", "extrapolated", "load")


def arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    parser = argparse.ArgumentParser()
    parser.add_argument("--addon-zip", required=True)
    parser.add_argument("--csv", required=True)
    parser.add_argument("--summary", required=True)
    parser.add_argument("--truth-cache", help="folder of the cached truth (default: $BAKE_RADIOSITY_TRUTH or "
                                              "build/truth)")
    parser.add_argument("--truth-samples", type=int, default=4096, help="samples of each seed of the truth")
    parser.add_argument("--truth-noise", type=float, default=0.003, help="the truth's target noise")
    parser.add_argument("--truth-minutes", type=float, default=60.0,
                        help="wall minutes the truth's seeds may take in total (over every run that extends it)")
    parser.add_argument("--cycles-samples", default=",".join(map(str, CYCLES_SAMPLES)))
    parser.add_argument("--configs", default="", help="extra bakes: divisions/cells/rays,...")
    parser.add_argument("--no-elements", dest="elements", action="store_false", help="skip the element chart")
    return parser.parse_args(argv)


def cycles_bake(obj, samples, seed):
    with harness.Stopwatch() as seconds:
        colors = harness.cycles_corner_bake(obj, samples, seed)
    attributes = obj.data.color_attributes
    attributes.remove(attributes["Cycles %d" % seed])
    return colors, seconds


def radiosity_bake(addon, obj, quality, final_gather, preset=None, gather_rays=None):
    """(corner colours, Stopwatch, summary) of a whole add-on bake; `preset` replaces the quality's
    auto_settings preset and `gather_rays` the rays of its gathered solution for this bake."""
    auto_settings = sys.modules["bake_radiosity.engine.auto_settings"]
    presets = dict(auto_settings.PRESETS)
    if preset is not None:
        presets[quality] = preset
    if gather_rays:
        gathered = dataclasses.replace(presets[quality].gathered, rays=gather_rays)
        presets[quality] = dataclasses.replace(presets[quality], gathered=gathered)
    with harness.patched_setting("PRESETS", presets), harness.Stopwatch() as seconds:
        summary = addon.bake(bpy.context.scene, attribute_name="Radiosity", quality=quality,
                             final_gather=final_gather)
    return harness.corner_colors(obj.data, "Radiosity"), seconds, summary


def seam_vertices(obj, vertices):
    """Mask of `vertices` that lie where a vertex of another face lies too: the room's edges and
    corners, the blocks' edges and the lines where they stand on the floor (each flat piece of the
    box has vertices of its own)."""
    positions = np.empty(len(obj.data.vertices) * 3)
    obj.data.vertices.foreach_get("co", positions)
    _, place, count = np.unique(np.round(positions.reshape(-1, 3)[vertices], 6), axis=0, return_inverse=True,
                                return_counts=True)
    return count[place.ravel()] > 1


class Race:
    def __init__(self, args):
        self.args = args
        self.addon = harness.install_addon(args.addon_zip)
        scenes.clear_scene()
        self.box = scenes.cornell_box("MESH")
        self.luminance = deep_cycles.vertex_luminance_of(self.box, deep_cycles.CORNELL_EMITTER_MATERIAL)
        self.stored, self.truth = deep_cycles.deep_truth(
            self.box, "cornell", args.truth_samples, args.truth_noise, 60 * args.truth_minutes, self.luminance,
            args.truth_cache, log=lambda s: print(s, flush=True))
        self.seams = seam_vertices(self.box, self.luminance.vertices)
        self.rows = []

    def record(self, colors, seconds, **fields):
        luminance = self.luminance(colors)
        error, error_noise_out = self.truth.error(luminance)
        row = dict(fields, cpu_seconds="%.3f" % seconds.cpu, wall_seconds="%.3f" % seconds.wall,
                   error="%.5f" % error, error_noise_out="%.5f" % error_noise_out,
                   error_seams="%.5f" % self.truth.error(luminance, self.seams)[1],
                   error_elsewhere="%.5f" % self.truth.error(luminance, ~self.seams)[1],
                   error_scaled="%.5f" % self.truth.scaled_error(luminance)[1], load="%.2f" % os.getloadavg()[0])
        print(row, flush=True)
        self.rows.append(row)

    def run(self):
        args = self.args
        self.load_start = os.getloadavg()
        # First calls pay one-time costs (Cycles' kernels, the native module): not measured.
        cycles_bake(self.box, 1, 1)
        radiosity_bake(self.addon, self.box, "DRAFT", True)
        for samples in [int(s) for s in args.cycles_samples.split(",")]:
            colors, seconds = cycles_bake(self.box, samples, seed=samples)  # seeds other than the truth's
            self.record(colors, seconds, kind="cycles", samples=samples)
        for quality in PRESETS:
            for gather in (True, False):
                self.bake_row("preset", quality, gather)
        medium = sys.modules["bake_radiosity.engine.auto_settings"].PRESETS["MEDIUM"]
        # With the gather a preset solves its gathered solution (auto_settings.Gathered): vary that one.
        for divisions in ELEMENT_DIVISIONS if args.elements else ():
            gathered = dataclasses.replace(medium.gathered, divisions=divisions)
            self.bake_row("elements", "MEDIUM", True, dataclasses.replace(medium, gathered=gathered))
            self.bake_row("elements", "MEDIUM", False, dataclasses.replace(medium, divisions=divisions))
        for config in filter(None, args.configs.split(",")):
            divisions, cells, rays = config.split("/")
            gathered = dataclasses.replace(medium.gathered, divisions=int(divisions), cells=float(cells))
            self.bake_row("config", "MEDIUM", True, dataclasses.replace(medium, gathered=gathered), int(rays))
        self.load_end = os.getloadavg()
        self.add_ratios()

    def bake_row(self, kind, quality, gather, preset=None, rays=None):
        colors, seconds, summary = radiosity_bake(self.addon, self.box, quality, gather, preset, rays)
        auto_settings = sys.modules["bake_radiosity.engine.auto_settings"]
        used = preset or auto_settings.PRESETS[quality]
        used = used.gathered if gather else used  # the solution the bake solved
        self.record(colors, seconds, kind=kind, quality=quality, final_gather=int(gather), divisions=used.divisions,
                    cells="%g" % used.cells, gather_rays=summary.get("gather_rays", 0), elements=summary["elements"],
                    resolution=summary["resolution"])

    def add_ratios(self):
        cycles = [r for r in self.rows if r["kind"] == "cycles"]
        for row in self.rows:
            if row["kind"] == "cycles":
                continue
            level = float(row["error_noise_out"])
            for clock, name in (("cpu_seconds", "cpu"), ("wall_seconds", "wall")):
                points = [(float(c[clock]), float(c["error_noise_out"])) for c in cycles]
                seconds, extrapolated = vertex_error.time_to_reach(points, level)
                if seconds is None:
                    continue
                row["cycles_%s_seconds_same_error" % name] = "%.2f" % seconds
                row["ratio_%s" % name] = "%.2f" % (seconds / float(row[clock]))
                row["extrapolated"] = int(extrapolated)

    def write(self):
        with open(self.args.csv, "w", newline="") as out:
            writer = csv.DictWriter(out, fieldnames=FIELDS, restval="")
            writer.writeheader()
            writer.writerows(self.rows)
        with open(self.args.summary, "w") as out:
            out.write("\n".join(self.summary_lines()) + "\n")

    def summary_lines(self):
        stored = self.stored
        lines = [
            "Cornell box (blender_tests/scenes.py, emitting opening), Blender %s, %d cores; load average (1, 5, 15 "
            "min) %s at the start, %s at the end" % (
                bpy.app.version_string, os.cpu_count(), "/".join("%.1f" % v for v in self.load_start),
                "/".join("%.1f" % v for v in self.load_end)),
            "Truth: %d seeds x %d samples of Cycles (unbiased light paths), %.1f CPU s a seed; its noise %.3f%% "
            "(relative RMS per vertex); %d of %d vertices judged" % (
                len(stored["seeds"]), int(stored["samples"]), float(np.mean(stored["cpu_seconds"])),
                100 * self.truth.noise(), self.truth.judged.sum(), len(self.truth.judged)),
            "Error: relative RMS luminance per vertex, measured / with the truth's noise taken out; then (noise "
            "out) on the %d seam vertices (edges, corners, contact lines: another face's vertex at the same place), "
            "on the other %d, and as RMS difference / RMS of the truth (bright vertices weigh more)" % (
                (self.seams & self.truth.judged).sum(), (~self.seams & self.truth.judged).sum()),
            "", "Cycles (no denoiser), samples: CPU s, wall s, error"]
        for r in self.rows:
            if r["kind"] == "cycles":
                lines.append("  %6d: %8s CPU s %8s s  %.2f%% / %.2f%%; %s" % (
                    int(r["samples"]), r["cpu_seconds"], r["wall_seconds"], 100 * float(r["error"]),
                    100 * float(r["error_noise_out"]), split(r)))
        titles = {"preset": "Presets", "elements": "Medium's settings at other element sizes (divisions of the "
                                                   "scene's size)", "config": "Other settings (gather on)"}
        for kind, title in titles.items():
            rows = [r for r in self.rows if r["kind"] == kind]
            if not rows:
                continue
            heading = ": elements, resolution, CPU s, wall s, error; Cycles' CPU s to the same error, ratio (CPU; wall)"
            lines += ["", title + heading]
            for r in rows:
                same = r.get("cycles_cpu_seconds_same_error")
                race = ("Cycles %s CPU s%s, %sx (wall %sx)" % (
                    same, " (extrapolated)" if r.get("extrapolated") else "", r["ratio_cpu"], r.get("ratio_wall", "?"))
                    if same else "worse than Cycles at its fewest samples")
                lines.append("  %-6s %-10s div %2d cells %-3s rays %4s %6d el res %4d %8s CPU s %8s s  "
                             "%.2f%% / %.2f%% (%s)   %s" % (
                                 r["quality"].lower(), "gather" if r["final_gather"] else "no gather",
                                 int(r["divisions"]), r["cells"], r["gather_rays"], int(r["elements"]),
                                 int(r["resolution"]), r["cpu_seconds"], r["wall_seconds"],
                                 100 * float(r["error"]), 100 * float(r["error_noise_out"]), split(r), race))
        return lines


def split(row):
    return "seams %.2f%%, elsewhere %.2f%%, scaled %.2f%%" % tuple(
        100 * float(row[k]) for k in ("error_seams", "error_elsewhere", "error_scaled"))


def main():
    start = time.perf_counter()
    race = Race(arguments())
    race.run()
    race.write()
    print("\n".join(race.summary_lines()), flush=True)
    print("whole run %.0f s wall" % (time.perf_counter() - start), flush=True)


main()
