"""Where the light went: the power the solve was given against the power surfaces absorbed,
from the solved element radiance (numpy, no bpy).

Lamps' and the World's light arrive as power: each element's first reflection of it, rho E / pi,
is in its emission (element_emission), so it counts as emitted here.

In radiance units an element reflects pi A (L - E) = pi A rho H watts of the light H it receives,
so it absorbs pi A (1 - rho) H = pi A (1 - rho) / rho (L - E). What was emitted and not absorbed
by a reflecting surface left the scene, fell on a black surface (a lamp, an emitter) or leaked;
what was absorbed beyond what was emitted, the bake created (its error), so no share is negative.
In a closed scene without black surfaces that remainder is pi sum A r / rho for the solve's
residual r = E - (I - rho F) L: zero once converged, so it checks the whole bake."""

import math
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class EnergyBalance:
    emitted: float    # watts, mean of R, G, B: surfaces' emission plus lamps' and the World's first reflection
    absorbed: float   # watts absorbed by surfaces that reflect (rho > 0)
    leaving: float    # watts leaving all surfaces (emitted + reflected)

    @property
    def lost(self):
        """Watts that escaped, fell on black surfaces, or leaked (never below 0: see created)."""
        return max(self.emitted - self.absorbed, 0.0)

    @property
    def created(self):
        """Watts absorbed beyond what was emitted: light the bake made from nothing (a solve stopped
        while it overshoots, form factors that are not reciprocal). 0 in a sound bake."""
        return max(self.absorbed - self.emitted, 0.0)

    @property
    def absorbed_fraction(self):
        return self.absorbed / self.emitted if self.emitted > 0.0 else 0.0


def balance(result):
    """EnergyBalance of a `_core.bake` result."""
    area = result["element_area"].astype(np.float64)[:, None]
    radiance = result["element_radiance"].astype(np.float64)
    emission = result["element_emission"].astype(np.float64)
    rho = result["element_reflectance"].astype(np.float64)
    reflecting = rho > 0.0
    absorbed_per_reflected = np.divide(1.0 - rho, rho, out=np.zeros_like(rho), where=reflecting)
    absorbed = area * absorbed_per_reflected * (radiance - emission)
    return EnergyBalance(emitted=math.pi * float((area * emission).sum()) / 3.0,
                         absorbed=math.pi * float(absorbed.sum()) / 3.0,
                         leaving=math.pi * float((area * radiance).sum()) / 3.0)
