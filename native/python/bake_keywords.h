/// @file bake_keywords.h
/// @brief The keyword settings `_core.bake` and `_core.bake_with_media` share: checked into
/// BakeSettings, the progress reporter they both use, and the surface result as a dict.
#pragma once

#include "progress.h"
#include "progress_monitor.h"

#include "bake/bake.h"

#include <string>

namespace radiosity::python {

/// BakeSettings from the keyword values; ValueError naming the keyword that is out of range.
BakeSettings bake_settings(float element_size, int resolution, const std::string& method, double tolerance,
                           int max_iterations, float hard_edge_angle, bool ambient, const py::list& lights,
                           std::size_t matrix_budget_bytes);

/// The `progress` keyword as the core's ProgressFn: a ProgressMonitor reports without the GIL,
/// anything else is called as a Python callback (None: no reports).
class ProgressReporter {
public:
    explicit ProgressReporter(const py::object& progress);
    const ProgressFn& function() const { return function_; }
    /// After Cancelled: re-raises the callback's own exception, if it raised one (GIL held).
    void rethrow_if_failed() { bridge_.rethrow_if_failed(); }

private:
    ProgressMonitor* monitor_;
    ProgressBridge bridge_;
    ProgressFn function_;
};

/// bake()'s result keys (elements, corner colours, solve statistics, seconds) added to `out`.
void add_bake_result(const BakeResult& result, py::dict& out);

/// The per-element solution keys both surface bakes return: corner colours (input and element
/// corners), element radiance, and the emission and reflectance the solve used.
void add_surface_solution(const Elements& elements, const std::vector<Rgb>& radiance, const CornerColors& colors,
                          py::dict& out);

}  // namespace radiosity::python
