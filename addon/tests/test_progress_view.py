"""The bake operator's timer tick (bake_radiosity.engine.progress_view) does only the work a new
report needs: what it asks of the core's monitor and what it gives the interface to redraw, tick by
tick, against a monitor and a clock played by the test."""
import unittest

import numpy as np

from bake_radiosity.engine.progress_view import PREVIEW_INTERVAL, ProgressView

TOLERANCE = 1e-4


class Monitor:
    """A _core.ProgressMonitor's interface, counting the snapshots taken and the radiance copied."""

    def __init__(self):
        self.reports = 0
        self.info = None
        self.snapshots = 0
        self.radiance_copies = 0

    def report(self, phase, done, total, residual=1.0, radiance=None):
        self.reports += 1
        self.info = {"phase": phase, "done": done, "total": total, "residual": residual, "radiance": radiance}

    def snapshot(self, radiance=True):
        self.snapshots += 1
        if self.info is None:
            return None
        if radiance and self.info["radiance"] is not None:
            self.radiance_copies += 1
            return dict(self.info, radiance=self.info["radiance"].copy())
        return dict(self.info, radiance=None)


class Clock:
    def __init__(self):
        self.now = 100.0

    def __call__(self):
        return self.now


class ProgressViewTest(unittest.TestCase):
    def setUp(self):
        self.monitor, self.clock = Monitor(), Clock()
        self.view = ProgressView(TOLERANCE, clock=self.clock)

    def tick(self, preview=False, seconds=0.2):
        self.clock.now += seconds
        return self.view.tick(self.monitor, preview)

    def test_a_tick_without_a_new_report_does_nothing(self):
        self.assertEqual(self.tick(), (None, None))
        self.monitor.report("form_factors", 1, 10)
        text, radiance = self.tick()
        self.assertEqual(text, "Bake Radiosity: form factors 1/10")
        self.assertIsNone(radiance)
        for _ in range(20):
            self.assertEqual(self.tick(), (None, None))
        self.assertEqual(self.monitor.snapshots, 1)  # for the one report

    def test_the_status_text_is_set_only_when_it_changes(self):
        self.monitor.report("solve", 0, 0, residual=1e-2)
        self.assertIsNotNone(self.tick()[0])
        self.monitor.report("solve", 0, 0, residual=0.9999e-2)  # the same line: "50%, residual 1.0e-02"
        self.assertEqual(self.tick(), (None, None))
        self.monitor.report("solve", 0, 0, residual=1e-3)
        self.assertIn("residual 1.0e-03", self.tick()[0])

    def test_the_preview_is_updated_at_most_once_an_interval_and_never_left_stale(self):
        radiance = np.zeros((1000, 3), np.float32)
        shown = []
        ticks = int(5 * PREVIEW_INTERVAL / 0.1)
        for k in range(ticks):
            radiance[:] = k
            self.monitor.report("solve", 0, 0, residual=1.0 / (k + 1), radiance=radiance)
            shown.append(self.tick(preview=True, seconds=0.1)[1])
        updates = [k for k, r in enumerate(shown) if r is not None]
        self.assertEqual(self.monitor.radiance_copies, len(updates))
        self.assertLessEqual(len(updates), 5 + 1)
        self.assertTrue(all(b - a >= round(PREVIEW_INTERVAL / 0.1) for a, b in zip(updates, updates[1:])), updates)
        np.testing.assert_array_equal(shown[updates[0]], updates[0])  # the radiance of that tick's report
        # The core stops reporting: the last report still reaches the preview, once.
        later = [self.tick(preview=True, seconds=0.1)[1] for _ in range(2 * round(PREVIEW_INTERVAL / 0.1))]
        last = [r for r in later if r is not None]
        self.assertEqual(len(last), 1)
        np.testing.assert_array_equal(last[0], ticks - 1)

    def test_no_radiance_is_copied_without_a_preview(self):
        for k in range(30):
            self.monitor.report("solve", 0, 0, residual=1.0 / (k + 1), radiance=np.ones((10, 3)))
            self.assertIsNone(self.tick()[1])
        self.assertEqual(self.monitor.radiance_copies, 0)


if __name__ == "__main__":
    unittest.main()
