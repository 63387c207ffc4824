#include "progress.h"

#include <pybind11/numpy.h>

namespace radiosity::python {

ProgressBridge::ProgressBridge(py::object callback) : callback_(std::move(callback)) {}

ProgressBridge::~ProgressBridge() {
    // The stored Python exception holds references: drop them with the GIL.
    py::gil_scoped_acquire gil;
    failure_.reset();
}

ProgressFn ProgressBridge::function() {
    if (callback_.is_none()) return {};
    return [this](const Progress& p) { return call(p); };
}

bool ProgressBridge::call(const Progress& p) {
    std::lock_guard<std::mutex> lock(mutex_);
    py::gil_scoped_acquire gil;
    if (failure_) return false;
    try {
        py::dict info;
        info["phase"] = p.phase;
        info["done"] = p.done;
        info["total"] = p.total;
        info["residual"] = p.residual;
        if (p.radiance != nullptr) {
            py::array_t<float> radiance({static_cast<py::ssize_t>(p.element_count), py::ssize_t{3}});
            float* out = radiance.mutable_data();
            for (std::size_t i = 0; i < p.element_count; ++i)
                for (int c = 0; c < 3; ++c) out[3 * i + c] = static_cast<float>(p.radiance[i][c]);
            info["radiance"] = radiance;
        } else {
            info["radiance"] = py::none();
        }
        const py::object answer = callback_(info);
        return answer.is_none() || answer.cast<bool>();
    } catch (py::error_already_set& e) {
        failure_ = std::make_unique<py::error_already_set>(std::move(e));
        return false;
    }
}

void ProgressBridge::rethrow_if_failed() {
    if (failure_) {
        auto failure = std::move(failure_);
        failure->restore();
        throw py::error_already_set();
    }
}

}  // namespace radiosity::python
