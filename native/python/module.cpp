/// @file module.cpp
/// @brief The `_core` extension module: a thin layer over the core, arrays in and arrays out.
#include "bindings.h"
#include "progress_monitor.h"

#include "common/types.h"

namespace py = pybind11;

PYBIND11_MODULE(_core, m) {
    m.doc() = "Bake Radiosity's native core: hemi-cube form factors and radiosity solvers.";
    // The core's error vocabulary (common/types.h). Every failure is also a `_core.Error`, so a
    // caller reports any bake that cannot run in one place, and keeps the built-in base its
    // meaning has. Translators are tried newest first: BudgetError before InputError.
    auto error = py::reinterpret_steal<py::object>(PyErr_NewException("_core.Error", PyExc_Exception, nullptr));
    m.attr("Error") = error;
    auto bases = [&](PyObject* builtin) { return py::make_tuple(py::handle(builtin), error); };
    py::handle input = py::register_exception<radiosity::InputError>(m, "InputError", bases(PyExc_ValueError));
    py::register_exception<radiosity::BudgetError>(m, "BudgetError", input);
    py::register_exception<radiosity::NotConverged>(m, "NotConverged", bases(PyExc_RuntimeError));
    py::register_exception<radiosity::FileError>(m, "FileError", bases(PyExc_OSError));
    py::register_exception<radiosity::Cancelled>(m, "Cancelled");
    // Also says in which phase light stopped being a number, and on which input polygon (.phase,
    // .polygon; -1: none to blame), so that the add-on can name the object.
    static py::exception<radiosity::NumericalError> numerical(m, "NumericalError", bases(PyExc_RuntimeError));
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
    radiosity::python::bind_progress_monitor(m);
    radiosity::python::bind_vdb(m);
    radiosity::python::bind_media(m);
}
