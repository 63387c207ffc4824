"""The race charts from the CSV that cycles_race.py writes (Debian's python3-matplotlib):

    /usr/bin/python3 docs/charts/plot_cycles_race.py docs/charts/cycles_race.csv docs/charts/cycles_race.png \\
        docs/charts/cycles_race_elements.png docs/charts/cycles_race_off_seams.txt

cycles_race.png: error against CPU seconds, log-log, over all vertices and over the vertices off
seams and contact lines: Cycles' sample ladder (black), the presets with the final gather (filled
stars) and without (hollow), other settings (diamonds, divisions/cells/rays), the accuracy targets
(Medium 1.5%, High 0.75%) as grey lines. cycles_race_elements.png:
error against the solution's element count at Medium's settings, with and without the gather,
with Cycles' error at its sample counts for scale. Errors have the truth's noise taken out. The
fourth argument, if given, receives the race on the vertices off seams and contact lines."""

import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "lab", "truth"))
import vertex_error  # noqa: E402

TARGETS = ((0.015, "Medium's target 1.5%"), (0.0075, "High's target 0.75%"))
PRESET_COLOURS = {"DRAFT": "tab:green", "MEDIUM": "tab:blue", "HIGH": "crimson"}


def read(path):
    with open(path, newline="") as source:
        return list(csv.DictReader(source))


def draw_race(axis, rows, column, clock="cpu_seconds"):
    """Error `column` against `clock`: Cycles' ladder, the presets, the other settings."""
    cycles = [r for r in rows if r["kind"] == "cycles"]
    axis.plot([float(r[clock]) for r in cycles], [float(r[column]) for r in cycles], "-s", color="black",
              markersize=4, label="Cycles (no denoiser), samples as labelled")
    for r in cycles:
        axis.annotate(r["samples"], (float(r[clock]), float(r[column])), textcoords="offset points",
                      xytext=(4, 2), fontsize=7)
    for r in rows:
        point = (float(r[clock]), float(r[column]))
        if r["kind"] == "preset":
            gather = r["final_gather"] == "1"
            colour = PRESET_COLOURS[r["quality"]]
            axis.plot(*point, "*", color=colour, markersize=14, markerfacecolor=colour if gather else "none",
                      label="%s, gather %s" % (r["quality"].title(), "on" if gather else "off"))
        elif r["kind"] == "config":
            axis.plot(*point, "D", color="tab:purple", markersize=5)
            axis.annotate("%s/%s/%s" % (r["divisions"], r["cells"], r["gather_rays"]), point,
                          textcoords="offset points", xytext=(4, -9), fontsize=6, color="tab:purple")
    for level, label in TARGETS:
        axis.axhline(level, color="grey", linewidth=0.7, linestyle="--")
        axis.text(0.01, level, label, transform=axis.get_yaxis_transform(), fontsize=7, color="grey",
                  verticalalignment="bottom")
    axis.set_xscale("log")
    axis.set_yscale("log")
    axis.set_xlabel("CPU seconds of the whole bake (all threads; wall seconds are in the CSV)")
    axis.set_ylabel("relative RMS luminance error per vertex (truth's noise out)")
    axis.grid(True, which="both", linewidth=0.3)


def draw_elements(axis, rows):
    for gather, style in (("1", "-o"), ("0", "--o")):
        points = sorted((int(r["elements"]), float(r["error_noise_out"]), float(r["error_elsewhere"]), r["divisions"])
                        for r in rows if r["kind"] == "elements" and r["final_gather"] == gather)
        if not points:
            continue
        on = "on" if gather == "1" else "off"
        axis.plot([p[0] for p in points], [p[1] for p in points], style, color="tab:blue",
                  label="Medium's settings, gather %s: all vertices" % on)
        axis.plot([p[0] for p in points], [p[2] for p in points], style, color="tab:orange", markersize=3,
                  label="gather %s: vertices off seams and contact lines" % on)
        for elements, error, _, divisions in points:
            axis.annotate("size/%s" % divisions, (elements, error), textcoords="offset points", xytext=(4, 2),
                          fontsize=7)
    for r in rows:
        if r["kind"] == "preset":
            colour = PRESET_COLOURS[r["quality"]]
            axis.plot(int(r["elements"]), float(r["error_noise_out"]), "*", color=colour, markersize=12,
                      markerfacecolor=colour if r["final_gather"] == "1" else "none")
    for r in rows:
        if r["kind"] == "cycles" and int(r["samples"]) >= 256:
            axis.axhline(float(r["error_noise_out"]), color="black", linewidth=0.5, linestyle=":")
            axis.annotate("Cycles %s samples" % r["samples"], (axis.get_xlim()[1], float(r["error_noise_out"])),
                          textcoords="offset points", xytext=(-80, 2), fontsize=7)
    axis.set_xscale("log")
    axis.set_yscale("log")
    axis.set_xlabel("elements of the radiosity solution")
    axis.set_ylabel("relative RMS luminance error per vertex (truth's noise out)")
    axis.set_title("Cornell box: output error against the solution's elements (stars: the presets)", fontsize=10)
    axis.grid(True, which="both", linewidth=0.3)
    axis.legend(fontsize=8)


def off_seam_lines(rows):
    """The race on the vertices off seams and contact lines alone: each bake's error there, and
    Cycles' CPU time to the same error on the same vertices."""
    cycles = [(float(r["cpu_seconds"]), float(r["error_elsewhere"])) for r in rows if r["kind"] == "cycles"]
    lines = ["On the vertices off seams and contact lines only (error there, noise out; Cycles' CPU s to the same "
             "error there; ratio):"]
    for r in rows:
        if r["kind"] == "cycles":
            continue
        level = float(r["error_elsewhere"])
        seconds, extrapolated = vertex_error.time_to_reach(cycles, level)
        race = "worse than Cycles at its fewest samples" if seconds is None else "Cycles %.2f CPU s%s, %.1fx" % (
            seconds, " (extrapolated)" if extrapolated else "", seconds / float(r["cpu_seconds"]))
        lines.append("  %-8s %-6s gather %-3s div %2s cells %-3s rays %4s: %6.2f%% in %7.2f CPU s; %s" % (
            r["kind"], r["quality"].lower(), "on" if r["final_gather"] == "1" else "off", r["divisions"], r["cells"],
            r["gather_rays"], 100 * level, float(r["cpu_seconds"]), race))
    return lines


def main(csv_path, race_png, elements_png, off_seams_txt=None):
    rows = read(csv_path)
    figure, axes = plt.subplots(1, 2, figsize=(15, 6.5))
    draw_race(axes[0], rows, "error_noise_out")
    draw_race(axes[1], rows, "error_elsewhere")
    axes[0].set_title("Cornell box against a deep Cycles truth: all vertices", fontsize=10)
    axes[1].set_title("the same bakes on the vertices off seams and contact lines (305 of 604)", fontsize=10)
    axes[0].legend(fontsize=7, loc="upper right")
    figure.tight_layout()
    figure.savefig(race_png, dpi=110)

    figure, axis = plt.subplots(figsize=(8, 6))
    draw_elements(axis, rows)
    figure.tight_layout()
    figure.savefig(elements_png, dpi=110)

    lines = off_seam_lines(rows)
    print("\n".join(lines))
    if off_seams_txt:
        with open(off_seams_txt, "w") as out:
            out.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main(*sys.argv[1:5])
