/// @file progress_monitor.h
/// @brief `_core.ProgressMonitor`: progress the core writes without the GIL and Python polls.
///
/// A Python callback needs the GIL on the core's thread, and Blender's main thread holds the GIL
/// most of the time: a bake in a worker thread would stall at every report. A monitor instead
/// keeps the latest report in C++ under a mutex; Blender's modal timer reads it and may cancel.
#pragma once

#include "common/types.h"

#include <pybind11/pybind11.h>

#include <atomic>
#include <mutex>
#include <string>
#include <vector>

namespace radiosity::python {

namespace py = pybind11;

class ProgressMonitor {
public:
    /// The core's side: stores the report, answers whether to go on. Never touches Python.
    ProgressFn function();
    /// The latest report as the dict a progress callback receives, or None before the first;
    /// without its radiance (None) unless `with_radiance`.
    py::object snapshot(bool with_radiance) const;
    /// How many reports the core has made: a poller sees whether anything changed without a snapshot.
    std::size_t reports() const { return reports_; }
    void cancel() { cancelled_ = true; }
    bool cancelled() const { return cancelled_; }

private:
    mutable std::mutex mutex_;
    bool reported_ = false;
    std::string phase_;
    std::size_t done_ = 0, total_ = 0;
    double residual_ = 0.0;
    std::vector<float> radiance_;  ///< element_count x 3, empty when the phase has none
    std::atomic<std::size_t> reports_{0};
    std::atomic<bool> cancelled_{false};
};

void bind_progress_monitor(py::module_& m);

}  // namespace radiosity::python
