/// @file texture.h
/// @brief Image textures on the input polygons: what colour a face has where the light lands.
///
/// A textured face's reflectance (or emission) at a point x is
///     reflectance[f] + scale[f] * (texel(uv(x)) - mean texel)
/// clamped to [0, kMaxTexturedReflectance] (emission to >= 0; an element's mean is clamped after
/// averaging the texels over it): SceneInput's reflectance stays the
/// face's mean colour, which every method that does not read textures uses as is, and the texture
/// adds its variation about that mean. With Base Color fed by the texture alone, scale is 1 and the
/// reflectance is the texel. uv(x) interpolates the polygon's corner UVs over its triangles (a
/// quad split along its corner 0 - corner 2 diagonal, as Blender splits quads).
#pragma once

#include "common/types.h"

#include <cstdint>
#include <vector>

namespace radiosity {

/// Texel lookup of Cycles' Image Texture node. Cubic and Smart are looked up as Linear.
enum class TextureFilter : int32_t { Closest = 0, Linear = 1 };
/// What lies outside [0, 1]: the image repeated, its edge texels extended, black, or mirrored.
enum class TextureExtension : int32_t { Repeat = 0, Extend = 1, Clip = 2, Mirror = 3 };

/// One image (a view; the caller owns the texels): RGB, `height` rows of `width` texels, row 0 at
/// v = 0 (the bottom, as Blender stores images).
struct Texture {
    const float* rgb = nullptr;
    int width = 0, height = 0;
    TextureFilter filter = TextureFilter::Linear;
    TextureExtension extension = TextureExtension::Repeat;
    /// The texels are sRGB-encoded (an 8-bit sRGB image): as Cycles does, a lookup blends the
    /// encoded values and decodes the blend to linear; means are taken of decoded texels.
    /// Otherwise the texels are linear.
    bool srgb = false;
};

/// The textures of a scene and which faces they vary (views, like SceneInput).
struct SurfaceTextures {
    std::vector<Texture> textures;
    const float* corner_uv = nullptr;              ///< corner_count x 2: each input corner's UV
    const int32_t* reflectance_texture = nullptr;  ///< face_count: texture index, -1 none. May be null.
    const float* reflectance_scale = nullptr;      ///< face_count x 3 (with reflectance_texture)
    const int32_t* emission_texture = nullptr;     ///< face_count: texture index, -1 none. May be null.
    const float* emission_scale = nullptr;         ///< face_count x 3 (with emission_texture)
};

/// Textured reflectance stays below 1, as the solve needs (the add-on's cap for plain colours too).
constexpr double kMaxTexturedReflectance = 0.999;

/// The texel at (u, v) as Cycles looks it up: Linear blends the four texels around the point
/// (texel centres at (i + 0.5) / width), Closest takes the texel the point is in; Clip is black
/// where no texel contributes.
Rgb texel(const Texture& texture, float u, float v);

/// Texel (x, y) after the texture's extension (black outside a Clip image), linear.
Rgb texel_at(const Texture& texture, int64_t x, int64_t y);

/// The mean of all texels, linear.
Rgb texel_mean(const Texture& texture);

/// Checks the textures and the per-face arrays against the scene's sizes (InputError naming the
/// texture or face).
void validate_textures(const SurfaceTextures& textures, std::size_t face_count, std::size_t corner_count);

}  // namespace radiosity
