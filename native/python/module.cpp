/// @file module.cpp
/// @brief The `_core` extension module: a thin layer over the core, arrays in and arrays out.
#include "bindings.h"
#include "progress_monitor.h"

#include "radiosity/types.h"

namespace py = pybind11;

PYBIND11_MODULE(_core, m) {
    m.doc() = "Bake Radiosity's native core: hemi-cube form factors and radiosity solvers.";
    py::register_exception<radiosity::Cancelled>(m, "Cancelled");
    // A RuntimeError that says in which phase light stopped being a number, and on which input
    // polygon (.phase, .polygon; -1: none to blame), so that the add-on can name the object.
    static py::exception<radiosity::NumericalError> numerical(m, "NumericalError", PyExc_RuntimeError);
    py::register_exception_translator([](std::exception_ptr thrown) {
        try {
            if (thrown) std::rethrow_exception(thrown);
        } catch (const radiosity::NumericalError& e) {
            py::object error = py::handle(numerical.ptr())(e.what());  // an instance (numerical() would raise)
            error.attr("phase") = e.phase;
            error.attr("polygon") = e.polygon;
            PyErr_SetObject(numerical.ptr(), error.ptr());
        }
    });
    radiosity::python::bind_bake(m);
    radiosity::python::bind_hierarchy(m);
    radiosity::python::bind_progress_monitor(m);
    radiosity::python::bind_vdb(m);
    radiosity::python::bind_zonal(m);
}
