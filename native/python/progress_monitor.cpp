#include "progress_monitor.h"

#include <pybind11/numpy.h>

namespace radiosity::python {

ProgressFn ProgressMonitor::function() {
    return [this](const Progress& p) {
        std::lock_guard<std::mutex> lock(mutex_);
        reported_ = true;
        phase_ = p.phase;
        done_ = p.done;
        total_ = p.total;
        residual_ = p.residual;
        radiance_.resize(p.radiance ? 3 * p.element_count : 0);
        for (std::size_t k = 0; k < radiance_.size(); ++k) radiance_[k] = static_cast<float>(p.radiance[k / 3][k % 3]);
        ++reports_;
        return !cancelled_;
    };
}

py::object ProgressMonitor::snapshot(bool with_radiance) const {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!reported_) return py::none();
    py::dict info;
    info["phase"] = phase_;
    info["done"] = done_;
    info["total"] = total_;
    info["residual"] = residual_;
    if (!with_radiance || radiance_.empty()) {
        info["radiance"] = py::none();
    } else {
        py::array_t<float> radiance({static_cast<py::ssize_t>(radiance_.size() / 3), py::ssize_t{3}});
        std::copy(radiance_.begin(), radiance_.end(), radiance.mutable_data());
        info["radiance"] = radiance;
    }
    return std::move(info);
}

void bind_progress_monitor(py::module_& m) {
    py::class_<ProgressMonitor>(m, "ProgressMonitor",
                                "Pass as bake(progress=...) from a worker thread; poll snapshot() and call "
                                "cancel() from another thread. The core never waits for the GIL to report.")
        .def(py::init<>())
        .def("snapshot", &ProgressMonitor::snapshot, py::arg("radiance") = true,
             "The latest report {phase, done, total, residual, radiance} or None before the first; its "
             "radiance None unless `radiance` (a copy of every element's).")
        .def_property_readonly("reports", &ProgressMonitor::reports,
                               "How many reports the core has made so far (0: snapshot() is None).")
        .def("cancel", &ProgressMonitor::cancel, "Ask the core to stop; bake() then raises Cancelled.")
        .def_property_readonly("cancelled", &ProgressMonitor::cancelled);
}

}  // namespace radiosity::python
