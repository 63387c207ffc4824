"""Plots the native charts from the CSVs radiosity_charts writes (tools/make_charts.sh runs both).

    /usr/bin/python3 docs/charts/plot_native.py docs/charts

form_factors.csv -> form_factors.png   chart 1: |relative error| against seconds per row
aliasing.csv     -> aliasing.png       small distant patch: RMS error against seconds per row
convergence.csv  -> convergence.png    chart 3: residual against sweep (top) and time (bottom)
"""
import csv
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def form_factors(rows, png):
    series = defaultdict(list)
    for r in rows:
        series[(r["case"], r["method"])].append(
            (float(r["seconds_per_row"]), max(abs(float(r["relative_error"])), 1e-8), int(r["resolution"])))
    fig, ax = plt.subplots(figsize=(9, 6))
    for (case, method), points in sorted(series.items()):
        points.sort(key=lambda p: p[2])
        x, y, n = zip(*points)
        style = "--" if method == "near_field" else "-"
        line, = ax.loglog(x, y, style, marker="o", label=f"{case} ({method})")
        for xi, yi, ni in zip(x, y, n):
            if ni in (32, 1024):
                ax.annotate(str(ni), (xi, yi), textcoords="offset points", xytext=(3, 3), fontsize=7,
                            color=line.get_color())
    ax.set_xlabel("seconds per row (one thread)")
    ax.set_ylabel("|relative error| against Howell's closed form (floor 1e-8)")
    ax.set_title("Form factors: hemi-cube resolution 32..1024, and the near-field correction")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def aliasing(rows, png):
    series = defaultdict(list)
    for r in rows:
        series[(r["patch_side"], r["rotations"])].append(
            (float(r["seconds_per_row"]), float(r["rms_relative_error"]), int(r["resolution"])))
    fig, ax = plt.subplots(figsize=(8, 5.5))
    for (side, rotations), points in sorted(series.items()):
        points.sort(key=lambda p: p[2])
        x, y, n = zip(*points)
        line, = ax.loglog(x, y, "-" if rotations == "1" else "--", marker="o",
                          label=f"{float(side) * 100:g} cm patch at 1 m, {rotations} orientation(s)")
        for xi, yi, ni in zip(x, y, n):
            ax.annotate(str(ni), (xi, yi), textcoords="offset points", xytext=(3, 3), fontsize=7,
                        color=line.get_color())
    ax.set_xlabel("seconds per row (one thread)")
    ax.set_ylabel("RMS relative error over 64 directions")
    ax.set_title("Hemi-cube aliasing of a small distant patch (labels: resolution)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def convergence(rows, png):
    rhos = sorted({r["rho"] for r in rows}, key=float)
    series = defaultdict(list)
    for r in rows:
        series[(r["rho"], r["method"])].append((float(r["sweep"]), float(r["seconds"]), float(r["residual"])))
    fig, axes = plt.subplots(2, len(rhos), figsize=(5 * len(rhos), 8), squeeze=False)
    for col, rho in enumerate(rhos):
        for (r_rho, method), points in sorted(series.items()):
            if r_rho != rho:
                continue
            sweep, seconds, residual = zip(*points)
            axes[0][col].semilogy(sweep, residual, label=method)
            axes[1][col].loglog(seconds, residual, label=method)
        axes[0][col].set_title(f"rho = {rho}")
        axes[0][col].set_xlabel("sweep (progressive: n shots)")
        axes[1][col].set_xlabel("seconds")
        for row in (0, 1):
            axes[row][col].set_ylabel("relative residual")
            axes[row][col].grid(True, which="both", alpha=0.3)
            axes[row][col].legend(fontsize=8)
    fig.suptitle("Convergence on the Cornell box with one reflectance everywhere (730 elements, resolution 64)")
    fig.tight_layout()
    fig.savefig(png, dpi=100)


def main():
    directory = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    for name, plot in (("form_factors", form_factors), ("aliasing", aliasing), ("convergence", convergence)):
        path = os.path.join(directory, name + ".csv")
        if os.path.exists(path):
            plot(read(path), os.path.join(directory, name + ".png"))
            print("wrote", os.path.join(directory, name + ".png"))


if __name__ == "__main__":
    main()
