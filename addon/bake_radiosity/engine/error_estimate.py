"""An estimate of a bake's error for the summary (numpy, no bpy), relative RMS luminance per corner.

With the final gather it comes from the bake itself (`_core.bake`'s result["final_gather"], the
core's output/gather_statistics.h), in three parts added as squares:
  - sampling: each corner's indirect light is a stratified mean over its rays; the variance of that
    mean comes from two interleaved halves of its rays, and the noise of the field those rays read
    (gathered at the element vertices with few rays) from a probe read through the same rays;
  - the solution's bias: the share of a corner's light that is indirect comes from the solution,
    so it carries the solution's error less what the mean over the hemisphere averages out: its
    bias, the mean relative difference of the light arriving at the corners, as the solution
    interpolates it, from the light the gather found there;
  - the field's light: the field the rays read, blended between element corners, need not carry
    the light the solve found on each element (a lamp's hot spot between the vertices); the share
    of the light it misses or adds, area-weighted over the elements, comes to the corners' indirect
    light in proportion. Elements right beside a lamp or emitter, whose corners the gather scales to
    their solved light, count with what their corners missed or added before that: the light's
    shape within them is no better known.
The solve's bound (solve_bound) is given apart, and light created from nothing (more absorbed than
emitted) puts a floor under the estimate. What the bake cannot see is not in it: where the gather
and the solution make the same error (docs/accuracy.md, "The summary after a bake", measures the
estimate against Cycles). Without the gather (media, Subdivided Copies, the gather turned off) the
error is the one measured on the Cornell box for about as many elements, and the summary says that
this bake's own error is not seen."""

import dataclasses
import math
from dataclasses import dataclass
from typing import Optional

import numpy as np

from . import energy

# Rec. 709 luminance of linear RGB: Blender's scene-linear colour space.
LUMINANCE = np.array([0.2126, 0.7152, 0.0722])
# Corners darker than this share of the mean corner are left out (as the accuracy measure does).
DARK_SHARE = 0.01

# Without the gather: the Cornell box of blender_tests/scenes.py baked at Draft, Medium and High as
# the presets chose before the gather (resolution 56, 136, 236; near field at Medium and High; and
# with 1/8 m elements, resolution 128, below Draft), from docs/charts/bake_vs_cycles.csv:
# (elements, relative RMS corner error against Cycles' converged bake).
MEASURED = (
    (428, 0.122),
    (1712, 0.0575),
    (6848, 0.0278),
    (15408, 0.0224),
)


# What the estimate says, in words, where it has no number (its numbers are None then).
NO_REFLECTED_LIGHT = "no reflected light to estimate from"
NOT_FINITE = "the baked light is not finite"


@dataclass(frozen=True)
class ErrorEstimate:
    typical: Optional[float]  # relative RMS luminance error per corner to expect (solve bound apart); None: undefined
    relation: str       # "about"; "at least" (light created, or fewer elements than measured); "undefined"
    source: str         # "gather": from this bake's gather; "measured": the Cornell box's table
    sampling: Optional[float]       # the gather's sampling: its own rays and the field's noise (0 without the gather)
    solution_bias: Optional[float]  # the solution's bias as the gather's indirect light carries it (0 without)
    field_light: Optional[float]    # the light the field misses or adds, as the indirect light carries it (0 without)
    solve_bound: Optional[float]    # relative to the baked light, at most this from the solve; None: no bound
    undefined: str = ""  # why there is no estimate, in words (NO_REFLECTED_LIGHT, NOT_FINITE); "" when there is


def estimate(result, power=None):
    """ErrorEstimate of a `_core.bake` result; `power` (an energy.EnergyBalance, by default
    energy.balance(result)): a bake whose surfaces (and zones) absorbed more than was emitted made
    that light from nothing, so its error is at least that share. A relative error of reflected
    light is undefined where no corner shows any (only emitters and black surfaces): the estimate
    says so in `undefined`, its numbers None."""
    gather = result.get("final_gather") or {}
    power = power if power is not None else energy.balance(result)
    created = power.created / power.emitted if power.emitted > 0.0 else 0.0
    bound = solve_bound(result)
    if not math.isfinite(created):
        return _undefined(NOT_FINITE, "gather" if "variance" in gather else "measured", bound)
    if "variance" in gather:
        parts = gather_parts(result, gather)
        if parts is None:
            return _floored(_undefined(NO_REFLECTED_LIGHT, "gather", bound), created)
        sampling, bias, field = parts
        typical, relation, source = math.sqrt(sampling ** 2 + bias ** 2 + field ** 2), "about", "gather"
    else:
        if not reflects_light(result):
            return _floored(_undefined(NO_REFLECTED_LIGHT, "measured", bound), created)
        elements = int((~result["element_back"]).sum())  # as measured: emitters' back sides are not shown
        typical, relation, source = _interpolate(elements), _relation(elements), "measured"
        sampling = bias = field = 0.0
    if created > typical:
        typical, relation = created, "at least"
    return ErrorEstimate(typical=typical, relation=relation, source=source, sampling=sampling, solution_bias=bias,
                         field_light=field, solve_bound=bound)


def _undefined(reason, source, bound):
    return ErrorEstimate(typical=None, relation="undefined", source=source, sampling=None, solution_bias=None,
                         field_light=None, solve_bound=bound, undefined=reason)


def _floored(error, created):
    """Light created from nothing is an error of at least its share, with or without an estimate."""
    if created > 0.0:
        return dataclasses.replace(error, typical=created, relation="at least")
    return error


def reflects_light(result):
    """Whether some corner shows reflected light: it is lit (corner_light) and not black. Without
    one (an emitter alone, or among black surfaces) a relative error of reflected light is 0 / 0."""
    value = _luminance(result["corner_radiance"])
    light = _luminance(result["corner_light"])
    shown = (value > 0.0) & (light > 0.0)
    return bool(np.isfinite(light).all() and shown.any())


def gather_parts(result, gather):
    """(sampling, solution's bias, field's light) as relative RMS luminance over the corners of a
    `_core.bake` result and its gather's statistics. Corners that emit (a colour brighter than the
    light arriving: their emission would outweigh the rest in the bias), unless all do, and the
    darkest are left out. None when no corner judged shows reflected light (every one black, or
    unlit: an emitter alone), where the relative error is 0 / 0."""
    value = _luminance(result["corner_radiance"])
    reflecting = value <= _luminance(result["corner_light"]) * (1.0 + 1e-6)
    if not reflecting.any():
        reflecting = np.ones_like(reflecting)
    judged = reflecting & (value >= DARK_SHARE * value[reflecting].mean()) & (value > 0.0)
    light = _luminance(result["corner_light"])[judged]
    if not judged.any() or not np.sum(light) > 0.0:
        return None
    v = value[judged]
    own = _luminance(np.sqrt(np.maximum(gather["variance"], 0.0)))[judged]
    field = _luminance(np.sqrt(np.maximum(gather["field_noise"], 0.0)))[judged]
    sampling = math.sqrt(float(np.mean((own ** 2 + field ** 2) / v ** 2)))
    bias = float(np.sum(_luminance(gather["solution_light"])[judged] - light) / np.sum(light))
    share = math.sqrt(float(np.mean((_luminance(gather["indirect"])[judged] / v) ** 2)))
    shown = ~result["element_back"]  # read flat, not through the field
    area = result["element_area"].astype(np.float64)[shown]
    reflected = float(np.sum(area * _luminance(gather["element_reflected"])[shown]))
    missed = float(np.sum(area * _luminance(gather["element_field_error"])[shown]))
    missed = missed / reflected if reflected > 0.0 else 0.0
    return sampling, abs(bias) * share, abs(missed) * share


def solve_bound(result):
    """|L - L_exact| / |L| <= residual |E| / |L| / (1 - rho_max) in the area-weighted L1 norm.

    The residual r = E - (I - rho F) L is relative to |E|; with reciprocity (A_i F_ij = A_j F_ji)
    the area-weighted L1 norm of rho F is at most rho_max, so the error (I - rho F)^-1 r is at most
    |r| / (1 - rho_max). Hemi-cube rows are reciprocal only to about 1% (docs/design.md).
    |L| is the baked light: without the emitters' back sides (element_back), which are not written
    (their residual counts in r, their emission in |E|)."""
    if result["elements"] == 0:
        return 0.0
    area = result["element_area"].astype(np.float64)[:, None]
    emitted = float((area * np.abs(result["element_emission"])).sum())
    shown = ~result["element_back"]
    leaving = float((area[shown] * np.abs(result["element_radiance"][shown])).sum())
    if leaving == 0.0:
        return 0.0
    rho_max = float(result["element_reflectance"].max())
    bound = result["residual"] * emitted / leaving / (1.0 - rho_max) if rho_max < 1.0 else math.inf
    return bound if math.isfinite(bound) else None


def _luminance(rgb):
    return np.asarray(rgb, dtype=np.float64) @ LUMINANCE


def _relation(elements):
    # Fewer elements than measured err more than the coarsest measurement. More elements than the
    # finest need not err less: a scene's own difficulties (lamps beside walls, contacts) are not
    # in the table, so it stays "about" the finest measurement.
    if elements < MEASURED[0][0]:
        return "at least"
    return "about"


def _interpolate(elements):
    """Log-log interpolation in the measured table; the nearest end outside it."""
    counts = np.log([row[0] for row in MEASURED])
    errors = np.log([row[1] for row in MEASURED])
    return float(np.exp(np.interp(np.log(max(elements, 1)), counts, errors)))
