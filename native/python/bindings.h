/// @file bindings.h
/// @brief The parts of the `_core` module, each bound in its own file.
#pragma once

#include "radiosity/lights.h"

#include <pybind11/pybind11.h>

namespace radiosity::python {

namespace py = pybind11;

void bind_bake(py::module_& m);
void bind_hierarchy(py::module_& m);
void bind_vdb(py::module_& m);
void bind_zonal(py::module_& m);

/// Lamps given as a list of dicts ({"type": "POINT" | "SPOT" | "SUN", ...}) to core lights.
Lights parse_lights(const py::list& lamps);

}  // namespace radiosity::python
