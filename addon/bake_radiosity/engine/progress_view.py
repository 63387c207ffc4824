"""What the bake operator's modal timer shows of the core's progress, each tick doing as little as
it can, so the interface stays responsive while a bake runs: nothing when the core has not
reported since the last tick (one counter read), a new status text only when it differs from the
shown one, and the progressive preview's element colours (a copy of every element's radiance,
then a new GPU batch and a redraw of each 3D View) at most once every PREVIEW_INTERVAL seconds."""

import math
import time

from .summary import progress_text

PREVIEW_INTERVAL = 1.0  # seconds between updates of the progressive preview


class ProgressView:
    """`tick(monitor, preview)` reads a `_core.ProgressMonitor` (its `reports` count and
    `snapshot(radiance=...)`) and returns (status text to show or None, element radiance to show
    or None); `preview`: whether the element radiance is wanted at all."""

    def __init__(self, tolerance, clock=time.monotonic):
        self.tolerance = tolerance
        self.clock = clock
        self.seen_reports = 0
        self.text = None
        self.preview_stale = False  # the core reported since the preview was last updated
        self.previewed_at = -math.inf

    def tick(self, monitor, preview):
        reports = monitor.reports
        new = reports != self.seen_reports
        self.seen_reports = reports
        self.preview_stale = preview and (self.preview_stale or new)
        preview_due = self.preview_stale and self.clock() - self.previewed_at >= PREVIEW_INTERVAL
        if not new and not preview_due:
            return None, None
        info = monitor.snapshot(radiance=preview_due)
        if info is None:
            return None, None
        radiance = None
        if preview_due:
            self.preview_stale, self.previewed_at = False, self.clock()
            radiance = info["radiance"]
        text = progress_text(info, self.tolerance)
        if text == self.text:
            return None, radiance
        self.text = text
        return text, radiance
