"""A bake's summary in words: the report line, the accuracy line and progress lines."""

import math

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
    solve = ("at most %.2g%% (solve)" % (100 * error["solve_bound"]) if error["solve_bound"] is not None
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
             "gather seams": "final gather at seams",
             "world": "world light", "textures": "texture means",
             "solve rows": "solving, rows of this sweep"}.get(info["phase"], info["phase"])
    return "Bake Radiosity: %s %d/%d" % (phase, info["done"], info["total"])
