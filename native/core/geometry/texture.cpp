/// @file texture.cpp
/// @brief Texel lookup as Cycles' Image Texture node does it (kernel/device/cpu/image.h), texel
/// means and the checks of the texture arrays.
#include "geometry/texture.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace radiosity {
namespace {

int64_t wrap_periodic(int64_t x, int64_t size) {
    x %= size;
    return x < 0 ? x + size : x;
}

int64_t wrap_mirror(int64_t x, int64_t size) {
    const int64_t period = 2 * size;
    x = wrap_periodic(x, period);
    return x < size ? x : period - 1 - x;
}

/// Texel index x after the extension; -1 for Clip outside the image.
int64_t wrap(int64_t x, int64_t size, TextureExtension extension) {
    switch (extension) {
        case TextureExtension::Repeat:
            return wrap_periodic(x, size);
        case TextureExtension::Extend:
            return std::clamp<int64_t>(x, 0, size - 1);
        case TextureExtension::Mirror:
            return wrap_mirror(x, size);
        case TextureExtension::Clip:
            return x >= 0 && x < size ? x : -1;
    }
    return -1;
}

Rgb fetch(const Texture& t, int64_t x, int64_t y) {
    if (x < 0 || y < 0) return Rgb(0.0);
    const float* p = t.rgb + 3 * (std::size_t(y) * std::size_t(t.width) + std::size_t(x));
    return Rgb(p[0], p[1], p[2]);
}

/// sRGB's transfer function to linear, as Cycles' color_srgb_to_linear.
double srgb_to_linear(double c) {
    if (c < 0.04045) return c < 0.0 ? 0.0 : c * (1.0 / 12.92);
    return std::pow((c + 0.055) * (1.0 / 1.055), 2.4);
}

Rgb decoded(const Texture& t, const Rgb& c) {
    return t.srgb ? Rgb(srgb_to_linear(c.r), srgb_to_linear(c.g), srgb_to_linear(c.b)) : c;
}

Rgb stored_at(const Texture& t, int64_t x, int64_t y) {
    return fetch(t, wrap(x, t.width, t.extension), wrap(y, t.height, t.extension));
}

}  // namespace

Rgb texel_at(const Texture& t, int64_t x, int64_t y) { return decoded(t, stored_at(t, x, y)); }

Rgb texel(const Texture& t, float u, float v) {
    if (t.width <= 0 || t.height <= 0 || !t.rgb) return Rgb(0.0);
    if (!std::isfinite(u) || !std::isfinite(v)) return Rgb(0.0);
    if (t.filter == TextureFilter::Closest) {
        if (t.extension == TextureExtension::Clip && (u < 0.0f || v < 0.0f || u > 1.0f || v > 1.0f)) return Rgb(0.0);
        const auto x = int64_t(std::floor(double(u) * t.width)), y = int64_t(std::floor(double(v) * t.height));
        // Clip inside [0, 1] reads the edge texel at u = 1 exactly, as Cycles clamps there.
        const TextureExtension inside = t.extension == TextureExtension::Clip ? TextureExtension::Extend : t.extension;
        return decoded(t, fetch(t, wrap(x, t.width, inside), wrap(y, t.height, inside)));
    }
    // Texel centres at (i + 0.5) / size: the point blends the four centres around it.
    const float fx = u * float(t.width) - 0.5f, fy = v * float(t.height) - 0.5f;
    const float x0 = std::floor(fx), y0 = std::floor(fy);
    const double tx = double(fx - x0), ty = double(fy - y0);
    const auto ix = int64_t(x0), iy = int64_t(y0);
    return decoded(t, (1.0 - ty) * ((1.0 - tx) * stored_at(t, ix, iy) + tx * stored_at(t, ix + 1, iy)) +
                          ty * ((1.0 - tx) * stored_at(t, ix, iy + 1) + tx * stored_at(t, ix + 1, iy + 1)));
}

Rgb texel_mean(const Texture& t) {
    const std::size_t count = std::size_t(std::max(t.width, 0)) * std::size_t(std::max(t.height, 0));
    if (count == 0 || !t.rgb) return Rgb(0.0);
    Rgb sum(0.0);
    for (std::size_t i = 0; i < count; ++i) sum += decoded(t, Rgb(t.rgb[3 * i], t.rgb[3 * i + 1], t.rgb[3 * i + 2]));
    return sum / double(count);
}

void validate_textures(const SurfaceTextures& in, std::size_t face_count, std::size_t corner_count) {
    for (std::size_t k = 0; k < in.textures.size(); ++k) {
        const Texture& t = in.textures[k];
        if (t.width <= 0 || t.height <= 0 || !t.rgb)
            throw InputError("texture " + std::to_string(k) + " has no texels");
        const std::size_t values = 3 * std::size_t(t.width) * std::size_t(t.height);
        for (std::size_t i = 0; i < values; ++i)
            if (!std::isfinite(t.rgb[i]))
                throw InputError("texture " + std::to_string(k) + ": texel " + std::to_string(i / 3) +
                                 " is not finite");
    }
    const bool textured = in.reflectance_texture || in.emission_texture;
    if (textured && !in.corner_uv && corner_count > 0) throw InputError("textured faces need corner UVs");
    if (in.corner_uv)
        for (std::size_t c = 0; c < 2 * corner_count; ++c)
            if (!std::isfinite(in.corner_uv[c]))
                throw InputError("corner " + std::to_string(c / 2) + ": UV is not finite");
    auto check = [&](const int32_t* index, const float* scale, const char* what) {
        if (!index) return;
        if (!scale) throw InputError(std::string(what) + " textures need their scale");
        for (std::size_t f = 0; f < face_count; ++f) {
            if (index[f] < -1 || index[f] >= int32_t(in.textures.size()))
                throw InputError("polygon " + std::to_string(f) + ": " + what + " texture " + std::to_string(index[f]) +
                                 " does not exist");
            for (int c = 0; c < 3; ++c)
                if (!(scale[3 * f + c] >= 0.0f && std::isfinite(scale[3 * f + c])))
                    throw InputError("polygon " + std::to_string(f) + ": " + what +
                                     " texture scale negative or not finite");
        }
    };
    check(in.reflectance_texture, in.reflectance_scale, "reflectance");
    check(in.emission_texture, in.emission_scale, "emission");
}

}  // namespace radiosity
