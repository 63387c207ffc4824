/// @file surface_textures.h
/// @brief Textured faces in the bake (internal; texture.h): each element's mean colour over its
/// UV footprint for the solve, the texel at each output corner for the colours written.
#pragma once

#include "geometry/scene.h"
#include "geometry/texture.h"

namespace radiosity::detail {

/// Sets the reflectance and emission of the elements of textured faces to their mean over the
/// element: the exact mean of the texture over the element's UV footprint (texture_integral.h). A
/// footprint more than 64 texels across reads a box-filtered copy of the image, halved until it
/// is at most that (the solve's light needs no finer detail; the output corners read the image
/// itself). A back side takes its front's values. Progress phase "textures".
void texture_elements(const SceneInput& input, Elements& elements, const ProgressFn& progress);

/// The corner colours of textured faces with their colour at the corner itself: emission(uv) +
/// reflectance(uv) x the light arriving there (`light`, irradiance / pi at the same corners).
/// Input corners read their own UV; element corners the UV their polygon gives the vertex.
void texture_corners(const SceneInput& input, const Elements& elements, const CornerColors& light,
                     CornerColors& colors);

}  // namespace radiosity::detail
