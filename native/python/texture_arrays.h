/// @file texture_arrays.h
/// @brief The `textures` keyword of `_core.bake`: images and per-face texture arrays, checked and
/// viewed as the core's SurfaceTextures.
#pragma once

#include "arrays.h"

#include "geometry/texture.h"

#include <optional>
#include <vector>

namespace radiosity::python {

/// The numpy arrays behind a SurfaceTextures (kept alive here) and the view of them.
struct TextureArrays {
    std::vector<Array<float>> images;
    Array<float> corner_uv;
    std::optional<Array<int32_t>> reflectance_texture, emission_texture;
    std::optional<Array<float>> reflectance_scale, emission_scale;
    SurfaceTextures view;
};

/// Parses `textures` (None, or a dict: images, a list of dicts with rgb (height, width, 3) float32,
/// bottom row first, linear or with srgb True sRGB-encoded, filter "closest" or "linear",
/// extension "repeat", "extend", "clip" or "mirror"; corner_uv (corners, 2); reflectance_texture and emission_texture
/// (faces,) int32, -1 for none, each with its scale (faces, 3)). ValueError naming the key that does not fit.
std::optional<TextureArrays> parse_textures(const py::object& textures, py::ssize_t faces, py::ssize_t corners);

}  // namespace radiosity::python
