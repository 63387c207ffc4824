/// @file layer_arrays.h
/// @brief The `layers` keyword of `_core.bake` (which light group each source lights) and the
/// layered result as a dict.
#pragma once

#include "arrays.h"

#include "bake/layers.h"

namespace radiosity::python {

/// LayerSources from `layers` = {"count": int, "polygon": (face_count,) int32, "lamp": (lamps,)
/// int32 in the order of the `lights` keyword, "world": int}; ValueError naming what is missing or
/// of the wrong shape. `lights`: the `lights` keyword (its SUN entries are the suns).
LayerSources parse_layers(const py::dict& layers, std::size_t face_count, const py::list& lights);

/// bake_result(total) with "layers": per layer corner_radiance, element_corner_radiance,
/// corner_light, element_corner_light, element_radiance, element_emission, iterations, residual,
/// converged, seconds (solve, gather).
py::dict layered_result(const LayeredBake& layered);

}  // namespace radiosity::python
