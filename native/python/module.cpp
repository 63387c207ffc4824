/// @file module.cpp
/// @brief The `_core` extension module: a thin layer over the core, arrays in and arrays out.
#include "bindings.h"
#include "progress_monitor.h"

#include "radiosity/types.h"

namespace py = pybind11;

PYBIND11_MODULE(_core, m) {
    m.doc() = "Bake Radiosity's native core: hemi-cube form factors and radiosity solvers.";
    py::register_exception<radiosity::Cancelled>(m, "Cancelled");
    radiosity::python::bind_bake(m);
    radiosity::python::bind_hierarchy(m);
    radiosity::python::bind_progress_monitor(m);
    radiosity::python::bind_vdb(m);
    radiosity::python::bind_zonal(m);
}
