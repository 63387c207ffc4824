"""Plots the native charts from the CSVs radiosity_charts writes (tools/make_charts.sh runs both).

    /usr/bin/python3 docs/charts/plot_native.py docs/charts

form_factors.csv -> form_factors.png   chart 1: |relative error| against seconds per row
aliasing.csv     -> aliasing.png       small distant patch: RMS error against seconds per row
convergence.csv  -> convergence.png    chart 3: residual against sweep (top) and time (bottom)
stability.csv + the three above -> stability_before_after.csv/.png   every stability case, before and after
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


def stability_rows(directory):
    """Every stability case of docs/stability.md as (case, measure, before, after): stability.csv's
    own rows, and the before/after points of the form-factor, aliasing and convergence CSVs."""
    rows = [(r["case"], r["measure"] + f" ({r['before_setting']} -> {r['after_setting']})",
             float(r["before"]), float(r["after"])) for r in read(os.path.join(directory, "stability.csv"))]
    factors = {(r["case"], r["method"], r["resolution"]): abs(float(r["relative_error"]))
               for r in read(os.path.join(directory, "form_factors.csv"))}
    for case, label in (("opposed_area", "near field: opposed unit squares"),
                        ("perpendicular_area", "near field: shared edge"),
                        ("large_over_small_area", "near field: 2 m square over a 1 cm patch")):
        rows.append((label, "|relative factor error| at res 128 (near_field off -> on)",
                     factors[(case, "hemicube", "128")], factors[(case, "near_field", "128")]))
    aliasing_rms = {(r["patch_side"], r["rotations"], r["resolution"]): float(r["rms_relative_error"])
                    for r in read(os.path.join(directory, "aliasing.csv"))}
    rows.append(("small distant patch (1 cm at 1 m)", "RMS factor error (res 128 -> 512)",
                 aliasing_rms[("0.01", "1", "128")], aliasing_rms[("0.01", "1", "512")]))
    sweeps = defaultdict(float)
    for r in read(os.path.join(directory, "convergence.csv")):
        if r["rho"] == "0.99":
            sweeps[r["method"]] = max(sweeps[r["method"]], float(r["sweep"]))
    # Row k holds the residual of L^k, measured by sweep k + 1: the solver's sweep count is the last k + 1.
    rows.append(("rho 0.99, Cornell box geometry", "sweeps to 1e-6 (Gauss-Seidel -> SOR)",
                 sweeps["gauss_seidel"] + 1, sweeps["sor"] + 1))
    return rows


def stability_before_after(directory, csv_out, png):
    rows = stability_rows(directory)
    with open(csv_out, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["case", "measure", "before", "after"])
        writer.writerows(rows)
    errors = [r for r in rows if not r[1].startswith("sweeps")]
    counts = [r for r in rows if r[1].startswith("sweeps")]
    floor = 1e-7  # zeros (no leak at all) are drawn at the floor and labelled 0
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(11, 11), gridspec_kw={"height_ratios": [len(errors), 1.5]})
    y = range(len(errors))
    for offset, index, colour, label in ((-0.2, 2, "tab:red", "before"), (0.2, 3, "tab:green", "after")):
        values = [max(r[index], floor) for r in errors]
        ax.barh([k + offset for k in y], values, height=0.4, color=colour, label=label)
        for k, r in enumerate(errors):
            ax.annotate("0" if r[index] == 0 else f"{r[index]:.2g}", (max(r[index], floor), k + offset),
                        xytext=(3, 0), textcoords="offset points", va="center", fontsize=7)
    ax.set_xscale("log")
    ax.set_xlim(floor / 2, 1e3)
    ax.set_yticks(list(y))
    ax.set_yticklabels([f"{r[0]}\n{r[1]}" for r in errors], fontsize=7)
    ax.invert_yaxis()
    ax.set_xlabel("error (log; 0 drawn at 1e-7)")
    ax.grid(True, axis="x", which="both", alpha=0.3)
    ax.legend(loc="lower right")
    ax.set_title("Stability cases: error before and after the mitigation (docs/stability.md)")
    for k, r in enumerate(counts):
        ax2.barh([k - 0.2], [r[2]], height=0.4, color="tab:red")
        ax2.barh([k + 0.2], [r[3]], height=0.4, color="tab:green")
        for offset, value in ((-0.2, r[2]), (0.2, r[3])):
            ax2.annotate(f"{value:.0f}", (value, k + offset), xytext=(3, 0), textcoords="offset points", va="center",
                         fontsize=7)
    ax2.set_yticks(range(len(counts)))
    ax2.set_yticklabels([f"{r[0]}\n{r[1]}" for r in counts], fontsize=7)
    ax2.invert_yaxis()
    ax2.set_xlabel("sweeps")
    ax2.grid(True, axis="x", alpha=0.3)
    fig.tight_layout()
    fig.savefig(png, dpi=100)


def main():
    directory = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    for name, plot in (("form_factors", form_factors), ("aliasing", aliasing), ("convergence", convergence)):
        path = os.path.join(directory, name + ".csv")
        if os.path.exists(path):
            plot(read(path), os.path.join(directory, name + ".png"))
            print("wrote", os.path.join(directory, name + ".png"))
    if all(os.path.exists(os.path.join(directory, n + ".csv"))
           for n in ("stability", "form_factors", "aliasing", "convergence")):
        stability_before_after(directory, os.path.join(directory, "stability_before_after.csv"),
                               os.path.join(directory, "stability_before_after.png"))
        print("wrote", os.path.join(directory, "stability_before_after.png"))


if __name__ == "__main__":
    main()
