/// @file bake_keywords.h
/// @brief What `_core.plan` and `_core.bake` share: their keyword settings checked into
/// BakeSettings, the progress reporter, and the result as a dict.
#pragma once

#include "arrays.h"
#include "progress.h"
#include "progress_monitor.h"

#include "bake/bake.h"

namespace radiosity::python {

/// BakeSettings from the keyword settings (see `_core.bake`'s docstring for each); TypeError for
/// a keyword that is not a setting, ValueError naming one out of range or of the wrong type.
BakeSettings bake_settings(const py::kwargs& keywords);

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

/// Element corner colours as (E, 4, 3); the 4th corner of a triangle repeats zero.
py::array_t<float> element_corner_array(const std::vector<Rgb>& element_corner);

/// bake()'s result as the dict `_core.bake` returns: elements, corner colours, solve statistics,
/// seconds per phase, and the hierarchy's counts and the media's zones and grids where they apply.
py::dict bake_result(const BakeResult& result);

}  // namespace radiosity::python
