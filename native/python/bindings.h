/// @file bindings.h
/// @brief The parts of the `_core` module, each bound in its own file.
#pragma once

#include "media/volume.h"
#include "transport/lights.h"
#include "transport/world.h"

#include <pybind11/pybind11.h>

#include <vector>

namespace radiosity::python {

namespace py = pybind11;

void bind_bake(py::module_& m);
void bind_vdb(py::module_& m);
void bind_media(py::module_& m);

/// Lamps given as a list of dicts ({"type": "POINT" | "SPOT" | "SUN", ...}) to core lights.
Lights parse_lights(const py::list& lamps);

/// Media given as a list of dicts ({origin, voxel_size, extinction, albedo, emission}, grids of
/// shape (nz, ny, nx, 3)); ValueError naming the medium and the key.
std::vector<Medium> parse_media(const py::list& media);

/// The world's light from None (no world) or a float (height, width, 3) equirectangular map,
/// bottom row first (world.h); ValueError for another shape, a negative or non-finite value.
WorldLight parse_world(const py::object& map, int samples, int point_samples);

}  // namespace radiosity::python
