"""The accuracy targets' error measure: relative RMS luminance error per vertex against a deep Cycles truth.

Corner colours are reduced to one luminance per vertex (the mean of the vertex's corners that are
not on an emitter); vertices the truth sees below DARK_SHARE of the mean vertex are left out, so
that no vertex in shadow decides the ratio. The truth is the mean of N independent Cycles bakes;
its own noise is each vertex's spread between seeds / sqrt(N), relative to the vertex, as an RMS
over the judged vertices, and is taken out of a measured error in quadrature (independent errors
add as squares). Plain numpy: no Blender needed."""

import math

import numpy as np

# Rec. 709 luminance of linear RGB: Blender's scene-linear colour space.
LUMINANCE = np.array([0.2126, 0.7152, 0.0722])
DARK_SHARE = 0.01


class VertexLuminance:
    """Corner colours (corners, 3) -> one luminance per vertex that has a kept corner."""

    def __init__(self, corner_vertex, kept_corners):
        self.kept = np.asarray(kept_corners, dtype=bool)
        self.vertices, self.slot = np.unique(np.asarray(corner_vertex)[self.kept], return_inverse=True)
        self.count = np.bincount(self.slot)

    def __call__(self, corner_rgb):
        luminance = np.asarray(corner_rgb, dtype=np.float64)[self.kept] @ LUMINANCE
        return np.bincount(self.slot, weights=luminance) / self.count


class Truth:
    """The mean of per-seed vertex luminances (seeds, vertices) and what it can resolve."""

    def __init__(self, per_seed):
        self.per_seed = np.asarray(per_seed, dtype=np.float64)
        self.seeds = len(self.per_seed)
        self.mean = self.per_seed.mean(axis=0)
        self.judged = self.mean >= DARK_SHARE * self.mean.mean()

    def _spread(self):
        return self.per_seed.std(axis=0, ddof=1) / math.sqrt(self.seeds)

    def noise(self, subset=None):
        """Relative RMS noise of the mean over the judged vertices (of `subset`, a mask, if given;
        NaN with fewer than 2 seeds)."""
        if self.seeds < 2:
            return math.nan
        where = self._where(subset)
        return float(np.sqrt(np.mean((self._spread()[where] / self.mean[where]) ** 2)))

    def error(self, vertex_luminance, subset=None):
        """(measured, with the truth's noise taken out) relative RMS error of a bake's vertices."""
        where = self._where(subset)
        values = np.asarray(vertex_luminance, dtype=np.float64)[where]
        reference = self.mean[where]
        measured = float(np.sqrt(np.mean(((values - reference) / reference) ** 2)))
        return measured, math.sqrt(max(measured ** 2 - self.noise(subset) ** 2, 0.0))

    def scaled_error(self, vertex_luminance):
        """(measured, noise out) RMS difference over the RMS of the truth on the judged vertices:
        the measure of docs/charts/bake_vs_cycles.py and lab/final_gather (per corner there), in
        which bright vertices weigh more and dark ones less."""
        values = np.asarray(vertex_luminance, dtype=np.float64)[self.judged]
        reference = self.mean[self.judged]
        scale = math.sqrt(np.mean(reference ** 2))
        measured = math.sqrt(np.mean((values - reference) ** 2)) / scale
        noise = math.sqrt(np.mean(self._spread()[self.judged] ** 2)) / scale
        return measured, math.sqrt(max(measured ** 2 - noise ** 2, 0.0))

    def _where(self, subset):
        return self.judged if subset is None else self.judged & np.asarray(subset, dtype=bool)


def time_to_reach(points, level):
    """(seconds, extrapolated) at which Cycles' fastest-so-far error first falls to `level`, on the
    log-log line between the bakes around it; past the ladder's end along its last two bakes;
    None if `level` is above its first bake."""
    front, best = [], math.inf
    for seconds, error in sorted(points):
        if error < best:
            best = error
            front.append((seconds, error))
    if level >= front[0][1]:
        return None, False
    for (t0, e0), (t1, e1) in zip(front, front[1:]):
        if e1 <= level:
            fraction = math.log(level / e0) / math.log(e1 / e0)
            return math.exp(math.log(t0) + fraction * math.log(t1 / t0)), False
    (t0, e0), (t1, e1) = front[-2], front[-1]
    return math.exp(math.log(t1) + math.log(level / e1) / math.log(e1 / e0) * math.log(t1 / t0)), True
