"""A bake's summary in words: the report line, the accuracy line and progress lines."""

import math

from .bake_cache import cache_text

METHOD_LABELS = {"gauss_seidel": "Gauss-Seidel", "jacobi": "Jacobi", "progressive": "progressive refinement",
                 "hierarchical": "hierarchical"}


def report_line(summary):
    seconds = sum(summary["seconds"].values())
    state = "converged" if summary["converged"] else "NOT converged"
    zones = ""
    if summary.get("zones"):
        # Uniform regions merge into larger zones (docs/volumes.md): both counts.
        zones = ", %d zones (%d voxels of %.3g m)" % (summary["zones"], summary["zones_before_merge"],
                                                      summary["zone_size"])
    hierarchy = summary.get("hierarchy")
    if hierarchy:
        zones = " (%d leaves of %d faces, %d links; %d leaves split for lamp shadows)" % (
            hierarchy["leaves"], hierarchy["patches"], hierarchy["links"], hierarchy["lamp_splits"])
    if summary.get("gather_rays"):
        gather = ", final gather (%d rays a corner)" % summary["gather_rays"]
    elif summary.get("zones"):
        gather = ", no final gather (its rays do not yet pass through fog or smoke: the corners show the solution)"
    else:
        gather = ""
    lit = ", lit by %s" % summary["lit_by"] if summary.get("world") else ""
    return "%d elements%s, %s%s%s%s, %d iterations, residual %.2g (%s), %.1f s" % (
        summary["elements"], zones, METHOD_LABELS[summary["method"]], gather, lit, layers_text(summary),
        summary["iterations"], summary["residual"], state, seconds)


def layers_text(summary):
    """The light group layers written and their memory against the budget ("" without)."""
    layers = summary.get("light_layers")
    if not layers:
        return ""
    groups = ", ".join(g or "no group" for g in layers["groups"])
    return ", %d light group layers (%s; %.0f MB of the %.0f MB memory budget)" % (
        len(layers["groups"]), groups, layers["bytes"] / (1 << 20), summary["memory_budget_bytes"] / (1 << 20))


# The bake's phases (the core's seconds and the add-on's own) and the final gather's, as the cost
# line names them, in the order they run.
PHASE_NAMES = {"export": "export", "world_map": "World map", "elements": "elements", "lights": "lamps",
               "world": "World light", "small_emitters": "small emitters", "form_factors": "form factors",
               "solve": "solve", "zones": "zones", "interpolate": "interpolation", "gather": "final gather",
               "writeback": "writeback"}
GATHER_PHASE_NAMES = {"field": "field", "wedges": "light around corners", "probes": "probes",
                      "points": "output points", "seams": "near surfaces", "other": "other"}


def gather_cost(final_gather):
    """The final gather's counts and phases from the core's result (None when it did not run)."""
    if not final_gather:
        return None
    return {"points": int(final_gather["points"]), "interpolated": int(final_gather.get("interpolated", 0)),
            "buried": int(final_gather["buried"]),
            "phases": {name: {"seconds": float(phase["seconds"]), "rays": int(phase["rays"])}
                       for name, phase in final_gather.get("phases", {}).items()}}


def cost_line(summary):
    """What the bake cost and why, in words: its elements (and the unknowns solved where small faces
    merged into fewer), the output points the final gather gathered and those whose indirect light
    it interpolated between them, the rays it traced, and each phase's seconds (the gather's own
    phases in brackets); phases under 0.05 s are left out; then whether it reused the previous
    bake's geometry (bake_cache.cache_text)."""
    gather = summary.get("gather")
    parts = ["%s elements" % format(summary["elements"], ",")]
    solved = summary.get("solve_elements", summary["elements"])
    if solved < summary["elements"]:  # small coplanar faces merged: the unknowns the solve had
        parts[0] += " (%s solved)" % format(solved, ",")
    if gather:
        points = "%s output points gathered, %s interpolated" % (format(gather["points"], ","),
                                                                 format(gather["interpolated"], ","))
        if gather["buried"]:
            points += ", %s inside other geometry" % format(gather["buried"], ",")
        rays = sum(phase["rays"] for phase in gather["phases"].values())
        parts += [points, "%.3g million rays" % (rays / 1e6)]
    phases = []
    for name, seconds in summary["seconds"].items():
        if seconds < 0.05:
            continue
        text = "%s %.1f s" % (PHASE_NAMES.get(name, name), seconds)
        if name == "gather" and gather:
            inner = ["%s %.1f s" % (GATHER_PHASE_NAMES.get(part, part), phase["seconds"])
                     for part, phase in gather["phases"].items() if phase["seconds"] >= 0.05]
            text += " (%s)" % ", ".join(inner) if inner else ""
        phases.append(text)
    line = "Cost: %s; %s" % ("; ".join(parts), ", ".join(phases))
    cache = cache_text(summary.get("cache"))
    return "%s. %s" % (line, cache) if cache else line


def accuracy_line(summary):
    """Residual; energy balance; error estimate; resolution and why (the panel shows one part a line)."""
    return "; ".join((
        "Residual %.1e" % summary["residual"],
        power_text(summary["energy"]),
        error_text(summary["error_estimate"]),
        "Hemi-cube resolution %d%s%s: %s" % (
            summary["resolution"], " x %d rotations" % summary["hemicube_rotations"]
            if summary["hemicube_rotations"] > 1 else "", ", near field" if summary["near_field"] else "",
            summary["resolution_reason"]),
    ))


def power_text(power):
    """Where the emitted watts went, every share at least 0: absorbed, escaped or on black surfaces,
    and light the bake created (absorbed beyond what was emitted) when there is any."""
    emitted = power["emitted"]
    share = (lambda watts: 100 * watts / emitted) if emitted > 0.0 else (lambda watts: 0.0)
    text = "Power %.3g W emitted: %.1f%% absorbed, %.1f%% escaped or on black" % (
        emitted, share(min(power["absorbed"], emitted)), share(power["lost"]))
    if power["created"] > 0.0:
        text += ", and %.1f%% more absorbed than emitted (created by the bake's error)" % share(power["created"])
    return text


def error_text(error):
    """The error estimate in words; where a quantity is undefined (None) the words say why."""
    solve = ("under %.2g%% from the solve's residual" % (100 * error["solve_bound"]) if error["solve_bound"] is not None
             else "no bound from the solve (a surface reflects all light)")
    if error.get("undefined"):
        if error["typical"] is not None:  # light created from nothing: at least its share
            return "Error %s %.1f%% per corner (light created by the bake; otherwise %s) + %s" % (
                error["relation"], 100 * error["typical"], error["undefined"], solve)
        return "Error per corner: none estimated, %s + %s" % (error["undefined"], solve)
    if error["source"] == "gather":
        where = "this bake's gather: sampling %.1f%%, solution's bias %.1f%%, field's light %.1f%%" % (
            100 * error["sampling"], 100 * error["solution_bias"], 100 * error["field_light"])
    else:
        where = ("element size, measured on the Cornell box against Cycles; without the final gather this "
                 "scene's own error is not seen")
    return "Error %s %.1f%% per corner (%s) + %s" % (error["relation"], 100 * error["typical"], where, solve)


def progress_text(info, tolerance):
    """One status line. The solve's share is how far the residual has come on a log scale
    from 1 to the tolerance: iteration counts are only caps."""
    if info["phase"] == "solve":
        residual = max(info["residual"], 1e-300)
        share = min(1.0, max(0.0, math.log(residual) / math.log(tolerance)))
        return "Bake Radiosity: solving %d%%, residual %.1e of %.0e" % (100 * share, info["residual"], tolerance)
    phase = {"form_factors": "form factors", "lights": "lamps", "elements": "preparing", "output": "output mesh",
             "gather wedges": "light around the seams' corners",
             "gather field": "final gather at the elements' vertices", "gather": "final gather",
             "gather lamp bubbles": "lamps' light within the elements",
             "gather probes": "final gather's probe rays",
             "gather near surfaces": "final gather again beside near surfaces",
             "world": "world light", "textures": "texture means",
             "solve rows": "solving, rows of this sweep"}.get(info["phase"], info["phase"])
    return "Bake Radiosity: %s %d/%d" % (phase, info["done"], info["total"])
