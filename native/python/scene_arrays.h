/// @file scene_arrays.h
/// @brief The scene arrays every entry point takes, checked once, and elements back to numpy.
#pragma once

#include "arrays.h"

#include "geometry/scene.h"

#include <optional>

namespace radiosity::python {

/// Checks shapes (ValueError naming the array) and views the arrays as a SceneInput. The arrays
/// must outlive the returned view. `front_only`: one flag per face, emitting from the front only.
SceneInput scene_input(const Array<float>& positions, const Array<int32_t>& face_offsets,
                       const Array<int32_t>& corner_vertices, const Array<float>& reflectance,
                       const Array<float>& emission, const std::optional<Array<int32_t>>& material,
                       const std::optional<Array<uint8_t>>& front_only = std::nullopt);

/// Adds element_vertices, element_corners, element_polygon, element_area, elements and skipped
/// (list of (polygon, reason)) to `out`.
void add_elements(const BuildResult& build, py::dict& out);

}  // namespace radiosity::python
