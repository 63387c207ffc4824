/// @file bindings.h
/// @brief The parts of the `_core` module, each bound in its own file.
#pragma once

#include <pybind11/pybind11.h>

namespace radiosity::python {

namespace py = pybind11;

void bind_bake(py::module_& m);

}  // namespace radiosity::python
