"""An estimate of a bake's error for the summary (numpy, no bpy): a bound on what the solve left,
from its residual, plus the discretisation error measured at about as many elements on the
Cornell box (docs/charts/bake_vs_cycles.csv, explained in docs/accuracy.md). Other scenes differ:
it is an estimate of the size of the error, not a measurement of this bake."""

import math
from dataclasses import dataclass

import numpy as np

from . import energy

# The Cornell box of blender_tests/scenes.py baked at Draft, Medium and High as the presets choose
# (resolution 56, 136, 236; near field at Medium and High; and with 1/8 m elements, resolution
# 128, below Draft), from
# docs/charts/bake_vs_cycles.csv: (elements, relative RMS corner error against a converged
# radiosity bake with 1/64 m elements, against Cycles' converged bake). The first column measures
# discretisation; the second adds what radiosity does
# not model the way Cycles does (2.1% between the two converged bakes).
MEASURED = (
    (428, 0.114, 0.122),
    (1712, 0.0478, 0.0575),
    (6848, 0.0136, 0.0278),
    (15408, 0.0087, 0.0224),
)
# The same box with the final gather (lab/final_gather/README.md), by the gather's rays a corner:
# (elements, relative RMS corner error against Cycles at 2 x 8192 samples, its noise taken out).
# The presets bake 1,728 elements with 256 (Draft) and 1024 rays (Medium), 3,888 with 4096 (High).
MEASURED_GATHER = {
    256: ((432, 0.0181), (1728, 0.0124), (6912, 0.0127)),
    1024: ((1728, 0.0068), (6912, 0.0072), (15552, 0.0049)),
    4096: ((1728, 0.0063), (3888, 0.0041), (6912, 0.0055), (15552, 0.0033)),
}


@dataclass(frozen=True)
class ErrorEstimate:
    solve_bound: float               # relative to the baked light, at most this from the solve
    discretisation: float            # measured for this many elements, against a converged radiosity bake
    discretisation_vs_cycles: float  # the same against Cycles (includes what radiosity cannot model)
    discretisation_relation: str     # "about"; beyond the measured element counts "at least" / "at most"


def estimate(result, power=None, gather_rays=0):
    """ErrorEstimate of a `_core.bake` result; with the final gather (of `gather_rays` rays a corner:
    the measurement with the nearest count), against Cycles alone (the gather is measured against
    nothing else). The table's value is only a typical size: a bake
    whose surfaces (and zones) absorbed more than was emitted (`power`, an energy.EnergyBalance,
    by default energy.balance(result)) made that light from nothing, so its error is at least that
    share, whatever the table says for its element count."""
    elements = int((~result["element_back"]).sum())  # as measured: emitters' back sides are not shown
    if result.get("final_gather"):
        rays = min(MEASURED_GATHER, key=lambda measured: abs(math.log(max(gather_rays, 1) / measured)))
        table = MEASURED_GATHER[rays]
        relation = _relation(elements, table)
        discretisation = vs_cycles = _interpolate(elements, 1, table)
    else:
        relation = _relation(elements)
        discretisation, vs_cycles = _interpolate(elements, 1), _interpolate(elements, 2)
    power = power if power is not None else energy.balance(result)
    created = (power.absorbed - power.emitted) / power.emitted if power.emitted > 0.0 else 0.0
    if not math.isfinite(created) or created > discretisation:
        created = created if math.isfinite(created) else math.inf
        relation, discretisation, vs_cycles = "at least", created, max(created, vs_cycles)
    return ErrorEstimate(solve_bound=solve_bound(result), discretisation_relation=relation,
                         discretisation=discretisation, discretisation_vs_cycles=vs_cycles)


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
    return result["residual"] * emitted / leaving / (1.0 - rho_max)


def _relation(elements, table=MEASURED):
    # Fewer elements than measured err more than the coarsest measurement, more elements less.
    if elements < table[0][0]:
        return "at least"
    if elements > table[-1][0]:
        return "at most"
    return "about"


def _interpolate(elements, column, table=MEASURED):
    """Log-log interpolation in the measured table; the nearest end outside it."""
    counts = np.log([row[0] for row in table])
    errors = np.log([row[column] for row in table])
    return float(np.exp(np.interp(np.log(max(elements, 1)), counts, errors)))
