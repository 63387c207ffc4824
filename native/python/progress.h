/// @file progress.h
/// @brief Calls a Python progress callback from the core, which runs without the GIL.
#pragma once

#include "common/types.h"

#include <pybind11/pybind11.h>

#include <memory>
#include <mutex>

namespace radiosity::python {

namespace py = pybind11;

/// Wraps `callback(info: dict) -> bool | None` as a ProgressFn. Returning False cancels the core.
/// An exception raised by the callback also cancels the core; `rethrow_if_failed` then raises it
/// in the calling Python thread instead of Cancelled.
class ProgressBridge {
public:
    explicit ProgressBridge(py::object callback);
    ~ProgressBridge();
    ProgressFn function();
    /// Re-raises the callback's exception, if it raised one. Call with the GIL held.
    void rethrow_if_failed();

private:
    bool call(const Progress& progress);

    py::object callback_;
    std::unique_ptr<py::error_already_set> failure_;
    std::mutex mutex_;
};

}  // namespace radiosity::python
