"""Where the light went when media take part: energy.balance's surface terms plus the zones'.

A zone of weight w = 4 K_t V emits pi w E (E = emission / K_t, its emitted radiance) and absorbs
pi w (1 - Omega) H of the mean radiance H it receives (bake/media_bake.h), as a surface emits pi A E
and absorbs pi A (1 - rho) H. In a closed scene emitted = absorbed checks the whole zonal bake."""

import math

import numpy as np

from . import energy


def balance(result):
    """EnergyBalance of a `_core.bake` result with media: surfaces and zones together."""
    surfaces = energy.balance(result)
    weight = result["zone_weight"].astype(np.float64)
    emitted = math.pi * float((weight * result["zone_emitted"]).sum()) / 3.0
    absorbed = math.pi * float((weight * (1.0 - result["zone_albedo"]) * result["zone_incident"]).sum()) / 3.0
    leaving = math.pi * float((weight * result["zone_radiance"]).sum()) / 3.0
    return energy.EnergyBalance(emitted=surfaces.emitted + emitted, absorbed=surfaces.absorbed + absorbed,
                                leaving=surfaces.leaving + leaving)
