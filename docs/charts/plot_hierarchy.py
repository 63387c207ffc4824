"""Plots the hierarchy charts from the CSVs radiosity_hierarchy_charts writes (tools/make_charts.sh hierarchy).

    /usr/bin/python3 docs/charts/plot_hierarchy.py docs/charts

hierarchy_scaling.csv  -> hierarchy_scaling.png, hierarchy_scaling_fit.txt     time, memory, links against triangles
hierarchy_accuracy.csv -> hierarchy_accuracy.png, hierarchy_accuracy_ratios.txt  error against elements
hierarchy_oracle.csv   -> drawn on hierarchy_accuracy.png; the most any bake could save, in the ratios
"""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def fit_slope(x, y):
    """Least-squares slope and intercept of log y against log x."""
    lx, ly = [math.log(v) for v in x], [math.log(v) for v in y]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    slope = sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sum((a - mx) ** 2 for a in lx)
    return slope, my - slope * mx


def scaling(rows, png, txt):
    n = [float(r["triangles"]) for r in rows]
    series = {"bake seconds": [float(r["seconds"]) for r in rows],
              "peak memory MB": [float(r["peak_mb"]) for r in rows],
              "links / 1000": [float(r["links"]) / 1000 for r in rows]}
    fig, ax = plt.subplots(figsize=(8, 6))
    lines = []
    for name, y in series.items():
        slope, intercept = fit_slope(n, y)
        at_million = math.exp(intercept) * 1e6 ** slope
        ax.loglog(n, y, marker="o", label=f"{name}: slope {slope:.2f}")
        lines.append(f"{name}: slope {slope:.2f} (log-log least squares over {len(n)} sizes), "
                     f"extrapolated to 1e6 triangles: {at_million:.3g}")
    ax.axhline(600, color="grey", linestyle=":", label="targets: 600 (s), 4096 (MB)")
    ax.axhline(4096, color="grey", linestyle=":")
    ax.set_xlabel("triangles in the scene")
    ax.set_title("Hierarchical bake of the object room (2 cores)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    with open(txt, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


def uniform_elements_at(error, uniform):
    """Uniform element count with this error: log-log interpolation between the uniform points
    (sorted by elements); outside their range the end segment is extended (marked)."""
    pts = sorted(uniform)
    for (n0, e0), (n1, e1) in zip(pts, pts[1:]):
        if min(e0, e1) <= error <= max(e0, e1) and e0 != e1:
            t = math.log(error / e0) / math.log(e1 / e0)
            return math.exp(math.log(n0) + t * math.log(n1 / n0)), ""
    (n0, e0), (n1, e1) = (pts[-2], pts[-1]) if error < pts[-1][1] else (pts[0], pts[1])
    t = math.log(error / e0) / math.log(e1 / e0)
    return math.exp(math.log(n0) + t * math.log(n1 / n0)), " (extrapolated)"


def oracle_elements_at(error, curve):
    """The oracle's elements at this error: log-log interpolation between its rounds."""
    for (n0, e0), (n1, e1) in zip(curve, curve[1:]):
        if e1 <= error <= e0 and e0 != e1:
            t = math.log(error / e0) / math.log(e1 / e0)
            return math.exp(math.log(n0) + t * math.log(n1 / n0))
    return float("nan")


def oracle_bounds(scene, uniform, oracle):
    """Per uniform run: the oracle's elements at its RMS, and how many times fewer that is."""
    out = [f"{scene}, oracle (the truth exact at the corners, elements placed by the truth's error) at each "
           f"uniform run's rms: uniform size, uniform elements, rms, then per split: oracle elements, "
           f"uniform / oracle"]
    splits = sorted({r["split"] for r in oracle if r["scene"] == scene})
    for size, elements, error in uniform:
        cells = []
        for split in splits:
            curve = [(int(r["elements"]), float(r["rms"])) for r in oracle
                     if r["scene"] == scene and r["split"] == split]
            equal = oracle_elements_at(error, curve)
            cells.append(f"{split} {equal:8.0f} {elements / equal:6.2f}")
        out.append(f"  {size:>6} {elements:>8} {error:.4f}   " + "   ".join(cells))
    return out


def accuracy(rows, png, txt, oracle):
    scenes = sorted({r["scene"] for r in rows})
    fig, axes = plt.subplots(1, len(scenes), figsize=(6 * len(scenes), 5), squeeze=False)
    axes = axes[0]
    out = []
    for ax, scene in zip(axes, scenes):
        mine = [r for r in rows if r["scene"] == scene]
        uniform = [(int(r["elements"]), float(r["rms"])) for r in mine if r["method"] == "uniform"]
        ax.loglog(*zip(*sorted(uniform)), marker="o", label="uniform mesh")
        methods = sorted({r["method"] for r in mine if r["method"].startswith("hierarchy")})
        for method in methods:
            hier = [r for r in mine if r["method"] == method]
            name = f"{method} (leaves to {hier[0]['min_size']} m, lamp detail {hier[0]['lamp_levels']} levels)"
            line, = ax.loglog([int(r["elements"]) for r in hier], [float(r["rms"]) for r in hier], marker="s",
                              label=f"{name}: leaves")
            ax.loglog([int(r["output_elements"]) for r in hier], [float(r["rms"]) for r in hier], marker="^",
                      linestyle="--", color=line.get_color(), label="  the same: output mesh")
            for r in hier:
                ax.annotate(r["parameter"], (int(r["elements"]), float(r["rms"])), textcoords="offset points",
                            xytext=(3, 3), fontsize=7)
        for split in sorted({r["split"] for r in oracle if r["scene"] == scene}):
            curve = [r for r in oracle if r["scene"] == scene and r["split"] == split]
            ax.loglog([int(r["elements"]) for r in curve], [float(r["rms"]) for r in curve], color="grey",
                      linestyle=":" if split == "quadtree" else "-.",
                      label=f"oracle, {split} (the truth at the corners)")
        agree = next(r for r in mine if r["method"] == "reference_uniform")
        ax.axhline(float(agree["rms"]), color="grey", linewidth=0.8, label="the two references' difference")
        # Below the references' difference the oracle only retraces the reference's own mesh.
        lowest = min(float(r["rms"]) for r in mine if r["method"] in methods or r["method"] == "uniform")
        ax.set_ylim(bottom=min(lowest, float(agree["rms"])) / 2)
        ax.set_title(f"{scene} (references differ by rms {float(agree['rms']):.3f})")
        ax.set_xlabel("elements")
        ax.set_ylabel("RMS colour error / mean radiance")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
        for column, reference in (("rms", "hierarchy"), ("rms_vs_uniform_ref", "uniform")):
            points = [(int(r["elements"]), float(r[column])) for r in mine if r["method"] == "uniform"]
            for method in methods:
                out.append(f"{scene}, {method}, against the {reference} reference: refine_tolerance, leaves, "
                           f"output elements, rms, uniform elements at that rms, ratio to leaves, "
                           f"ratio to output elements")
                for r in (r for r in mine if r["method"] == method):
                    equal, note = uniform_elements_at(float(r[column]), points)
                    out.append(f"  {r['parameter']:>6} {int(r['elements']):>8} {int(r['output_elements']):>8} "
                               f"{float(r[column]):.4f} {equal:>10.0f} {equal / int(r['elements']):6.2f} "
                               f"{equal / int(r['output_elements']):6.2f}{note}")
        if oracle:
            out += oracle_bounds(scene, [(r["parameter"], int(r["elements"]), float(r["rms"])) for r in mine
                                         if r["method"] == "uniform"], oracle)
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    with open(txt, "w") as f:
        f.write("\n".join(out) + "\n")
    print("\n".join(out))


def main(folder):
    for name, plot in (("hierarchy_scaling", scaling), ("hierarchy_accuracy", accuracy)):
        path = os.path.join(folder, name + ".csv")
        if os.path.exists(path) and read(path):
            suffix = "_fit.txt" if plot is scaling else "_ratios.txt"
            extra = ()
            if plot is accuracy:
                oracle = os.path.join(folder, "hierarchy_oracle.csv")
                extra = (read(oracle) if os.path.exists(oracle) else [],)
            plot(read(path), os.path.join(folder, name + ".png"), os.path.join(folder, name + suffix), *extra)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__)))
