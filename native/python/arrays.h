/// @file arrays.h
/// @brief Checked views of numpy arrays and conversions of core results to numpy.
#pragma once

#include "common/types.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstring>
#include <string>
#include <vector>

namespace radiosity::python {

namespace py = pybind11;

template <typename T>
using Array = py::array_t<T, py::array::c_style | py::array::forcecast>;

/// Throws ValueError unless `a` has shape (rows, columns) (columns 0 = one-dimensional).
template <typename T>
void require_shape(const Array<T>& a, const char* name, py::ssize_t rows, py::ssize_t columns) {
    const bool ok = columns == 0 ? (a.ndim() == 1 && (rows < 0 || a.shape(0) == rows))
                                 : (a.ndim() == 2 && a.shape(1) == columns && (rows < 0 || a.shape(0) == rows));
    if (!ok) {
        std::string want = "(" + (rows < 0 ? std::string("n") : std::to_string(rows)) +
                           (columns == 0 ? ",)" : ", " + std::to_string(columns) + ")");
        std::string got = "(";
        for (py::ssize_t d = 0; d < a.ndim(); ++d) got += std::to_string(a.shape(d)) + (d + 1 < a.ndim() ? ", " : "");
        throw InputError(std::string(name) + " must have shape " + want + ", got " + got + ")");
    }
}

/// An (n, 3) float32 array of colours.
inline py::array_t<float> to_numpy(const std::vector<Rgb>& colours) {
    py::array_t<float> out({static_cast<py::ssize_t>(colours.size()), py::ssize_t{3}});
    auto o = out.mutable_unchecked<2>();
    for (std::size_t i = 0; i < colours.size(); ++i)
        for (int c = 0; c < 3; ++c) o(i, c) = static_cast<float>(colours[i][c]);
    return out;
}

/// An (n, 3) float32 array of positions or directions.
inline py::array_t<float> to_numpy(const std::vector<Vec3>& points) {
    static_assert(sizeof(Vec3) == 3 * sizeof(float), "Vec3 must be three packed floats");
    py::array_t<float> out({static_cast<py::ssize_t>(points.size()), py::ssize_t{3}});
    std::memcpy(out.mutable_data(), points.data(), points.size() * sizeof(Vec3));
    return out;
}

template <typename T>
py::array_t<T> to_numpy(const std::vector<T>& values) {
    return py::array_t<T>(static_cast<py::ssize_t>(values.size()), values.data());
}

}  // namespace radiosity::python
