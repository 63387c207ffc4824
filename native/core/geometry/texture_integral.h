/// @file texture_integral.h
/// @brief The exact mean of a texture over a polygon of UV space (internal; surface_textures.h).
#pragma once

#include "geometry/texture.h"

#include <glm/vec2.hpp>

#include <vector>

namespace radiosity::detail {

/// The mean over the polygon `uv` (UV space, either winding) of the texture as `texel` reads it:
/// exact, cell by cell of the texel grid (Closest: one value per texel; Linear: one bilinear patch
/// between four texel centres), from the area moments of the polygon clipped to each cell. A
/// polygon of no area takes the texel at its first corner. An sRGB image's patches blend its
/// decoded texels (a lookup blends encoded ones: the two differ by the curve's bend between
/// neighbouring texels). Cost: the cells the polygon's bounding box covers.
Rgb footprint_mean(const Texture& texture, const std::vector<glm::dvec2>& uv);

}  // namespace radiosity::detail
