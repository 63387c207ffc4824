"""Chart 2 from the CSV that bake_vs_cycles.py writes: the plot (Debian's python3-matplotlib) and
the ratio "our time / Cycles' time to reach the same error" at 5%, 2% and 1%:

    /usr/bin/python3 docs/charts/plot_bake_vs_cycles.py docs/charts/bake_vs_cycles.csv \
        docs/charts/bake_vs_cycles.png docs/charts/bake_vs_cycles_ratios.txt

Three panels, error against time on log-log axes: the Cornell box against each renderer's own
converged bake, the Cornell box against Cycles' converged bake (physical truth), and the furnace
against its exact answer. One line per method and hemi-cube resolution (points: element sizes,
or tolerances in the furnace), Cycles' sample ladder, the quality presets as labelled stars.
Gauss-Seidel is the over-relaxed solve the add-on runs; plain Gauss-Seidel (omega 1) is drawn
beside it. Presets with the near-field correction (near_field 1; the add-on's Medium and High) are
hollow stars, without it filled ones; the ratios file lists both."""

import csv
import math
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

METHOD_COLOURS = {"GAUSS_SEIDEL": "tab:blue", "GAUSS_SEIDEL_PLAIN": "tab:purple", "JACOBI": "tab:orange",
                  "PROGRESSIVE": "tab:green"}
METHOD_LABELS = {"GAUSS_SEIDEL": "Gauss-Seidel (over-relaxed)", "GAUSS_SEIDEL_PLAIN": "plain Gauss-Seidel",
                 "JACOBI": "Jacobi", "PROGRESSIVE": "progressive"}
RESOLUTION_STYLES = {64: ":", 128: "--", 256: "-"}
PANELS = (("cornell", "error_converged", "Cornell box: each against its own converged bake"),
          ("cornell", "error_truth", "Cornell box: against Cycles' converged bake"),
          ("furnace", "error_truth", "Furnace (rho 0.8): against the exact answer"))
LEVELS = (0.05, 0.02, 0.01)
METHODS = ("GAUSS_SEIDEL", "GAUSS_SEIDEL_PLAIN", "JACOBI", "PROGRESSIVE")
PRESETS = ("DRAFT", "MEDIUM", "HIGH")
# CPU seconds of the whole bake (every thread): the machine that measures is shared, and CPU time
# does not count the other jobs.
CLOCK = "cpu_seconds"


def read(path):
    with open(path, newline="") as source:
        return list(csv.DictReader(source))


def near_field(row):
    return row.get("near_field") == "1"


def series_key(row, scene):
    # Cornell lines join element sizes; furnace lines join tolerances at one element size.
    key = (row["method"], int(row["resolution"]))
    return key + ((float(row["element_size"]),) if scene == "furnace" else ())


def draw(axis, rows, scene, column, title):
    lines = defaultdict(list)
    for row in rows:
        if row["scene"] != scene or row["renderer"] != "radiosity" or row["quality"] != "CUSTOM":
            continue
        lines[series_key(row, scene)].append((float(row[CLOCK]), float(row[column])))
    for key, points in sorted(lines.items()):
        points.sort()
        method, resolution = key[0], key[1]
        label = "%s, res %d" % (METHOD_LABELS[method], resolution)
        if len(key) > 2:
            label += ", %.3g m" % key[2]
        axis.plot(*zip(*points), RESOLUTION_STYLES[resolution], marker="o", markersize=3,
                  color=METHOD_COLOURS[method], label=label, alpha=0.8 if len(key) == 2 or key[2] < 0.2 else 0.45)
    # In sample order: the first bake also pays Cycles' set-up, so time is not monotonic there.
    cycles = sorted(((float(r[CLOCK]), float(r[column]), int(r["samples"]))
                     for r in rows if r["scene"] == scene and r["renderer"] == "cycles"), key=lambda c: c[2])
    axis.plot([c[0] for c in cycles], [c[1] for c in cycles], "-s", color="black", markersize=4,
              label="Cycles, 1 to 4096 samples")
    for seconds, error, samples in cycles:
        axis.annotate(str(samples), (seconds, error), textcoords="offset points", xytext=(4, 2), fontsize=7)
    for row in rows:
        if row["scene"] == scene and row["renderer"] == "radiosity" and row["quality"] != "CUSTOM":
            point = (float(row[CLOCK]), float(row[column]))
            if near_field(row):
                axis.plot(*point, "*", color="crimson", markersize=15, markerfacecolor="none")
                continue
            axis.plot(*point, "*", color="crimson", markersize=11)
            axis.annotate(row["quality"].title(), point, textcoords="offset points", xytext=(5, -9),
                          fontsize=8, color="crimson")
    for level in LEVELS:
        axis.axhline(level, color="grey", linewidth=0.6)
    axis.set_xscale("log")
    axis.set_yscale("log")
    axis.set_xlabel("CPU seconds for the whole bake (all threads; same run, same machine)")
    axis.set_ylabel("relative RMS error over the corners")
    axis.set_title(title, fontsize=10)
    axis.grid(True, which="both", linewidth=0.3)


def time_to_reach(points, level):
    """Seconds at which the fastest-so-far error first falls to `level`, interpolated on the
    log-log line between the two bakes around it; None if never; the first bake's time if the
    fastest bake is already below (an upper bound)."""
    front, best = [], math.inf
    for seconds, error in sorted(points):
        if error < best:
            best = error
            front.append((seconds, error))
    for k, (seconds, error) in enumerate(front):
        if error <= level:
            if k == 0:
                return seconds, True
            (t0, e0), (t1, e1) = front[k - 1], (seconds, max(error, 1e-12))
            fraction = (math.log(level) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + fraction * (math.log(t1) - math.log(t0))), False
    return None, False


def ratio_lines(rows, clock):
    lines = []
    comparisons = (("cornell", "error_converged", "each against its own converged bake (radiosity: 1/64 m elements; "
                                                  "Cycles: 2 x 16384 samples)"),
                   ("cornell", "error_truth", "both against Cycles' converged bake (physical truth)"),
                   ("furnace", "error_truth", "both against the exact answer"))
    for scene, column, title in comparisons:
        lines.append("%s, %s:" % (scene, title))
        cycles = [(float(r[clock]), float(r[column])) for r in rows
                  if r["scene"] == scene and r["renderer"] == "cycles"]
        for method in METHODS:
            ours = [(float(r[clock]), float(r[column])) for r in rows if r["scene"] == scene
                    and r["renderer"] == "radiosity" and r["method"] == method and not near_field(r)]
            parts = []
            for level in LEVELS:
                t_ours, ours_first = time_to_reach(ours, level)
                t_cycles, cycles_first = time_to_reach(cycles, level)
                if t_ours is None or t_cycles is None:
                    who = " and ".join(n for n, t in (("radiosity", t_ours), ("Cycles", t_cycles)) if t is None)
                    parts.append("%g%%: not reached by %s" % (100 * level, who))
                    continue
                note = " (Cycles below it at its fastest bake: ratio is a lower bound)" if cycles_first else ""
                note += " (radiosity below it at its fastest bake: ratio is an upper bound)" if ours_first else ""
                parts.append("%g%%: %.3g s / %.3g s = %.2g%s"
                             % (100 * level, t_ours, t_cycles, t_ours / t_cycles, note))
            lines.append("  %-18s %s" % (method.lower(), "; ".join(parts)))
    return lines


def preset_lines(rows):
    """The presets as the add-on chooses them, without and with the near-field correction."""
    lines = ["cornell presets (error against the converged radiosity bake / against Cycles' converged bake):"]
    for quality in PRESETS:
        for r in rows:
            if r["scene"] == "cornell" and r["quality"] == quality:
                lines.append("  %-6s near field %-3s %5d elements, resolution %3d: %6.2f CPU s, %.2f%% / %.2f%%" % (
                    quality.lower(), "on" if near_field(r) else "off", int(r["elements"]), int(r["resolution"]),
                    float(r["cpu_seconds"]), 100 * float(r["error_converged"]), 100 * float(r["error_truth"])))
    return lines


def main(csv_path, png_path, ratios_path):
    rows = read(csv_path)
    figure, axes = plt.subplots(1, 3, figsize=(20, 6.5))
    for axis, (scene, column, title) in zip(axes, PANELS):
        draw(axis, rows, scene, column, title)
    axes[0].legend(fontsize=7, loc="lower left")
    axes[2].legend(fontsize=6, loc="lower left", ncol=2)
    figure.tight_layout()
    figure.savefig(png_path, dpi=110)

    lines = ["Our time / Cycles' time to reach the same relative RMS corner error, in CPU seconds:"]
    lines += ratio_lines(rows, "cpu_seconds")
    lines += ["", "The same in wall-clock seconds (shared machine: other jobs ran too):"]
    lines += ratio_lines(rows, "seconds")
    lines += [""] + preset_lines(rows)
    with open(ratios_path, "w") as out:
        out.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main(*sys.argv[1:4])
