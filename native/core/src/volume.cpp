/// @file volume.cpp
/// @brief Principled Volume coefficients, voxel grids and their zones.
#include "radiosity/volume.h"

#include "volume_bounds.h"

#include <glm/common.hpp>
#include <glm/exponential.hpp>

#include <cmath>
#include <string>

namespace radiosity {

VolumeCoefficients principled_volume(const Rgb& color, double density, const Rgb& absorption_color,
                                     double emission_strength, const Rgb& emission_color) {
    const double d = std::max(density, 0.0);
    const Rgb sqrt_absorption = glm::sqrt(glm::max(absorption_color, Rgb(0.0)));
    VolumeCoefficients c;
    c.scattering = d * color;
    c.absorption = d * glm::max(1.0 - color, Rgb(0.0)) * glm::max(1.0 - sqrt_absorption, Rgb(0.0));
    c.emission = emission_strength * emission_color;
    return c;
}

Medium::Medium(const Vec3& origin_, float voxel_size_, const std::array<int32_t, 3>& dims_)
    : origin(origin_), voxel_size(voxel_size_), dims(dims_) {
    const std::size_t n = voxel_count();
    extinction.assign(n, Rgb(0.0));
    albedo.assign(n, Rgb(0.0));
    emission.assign(n, Rgb(0.0));
}

void Medium::set(std::size_t voxel, const VolumeCoefficients& c) {
    const Rgb K_t = c.extinction();
    extinction[voxel] = K_t;
    for (int ch = 0; ch < 3; ++ch) albedo[voxel][ch] = K_t[ch] > 0.0 ? c.scattering[ch] / K_t[ch] : 0.0;
    emission[voxel] = c.emission;
}

namespace {

bool finite(const Rgb& v) { return std::isfinite(v.r) && std::isfinite(v.g) && std::isfinite(v.b); }

void check_medium(const Medium& m, std::size_t index) {
    const std::string name = "medium " + std::to_string(index);
    if (!(m.voxel_size > 0.0f) || !std::isfinite(m.voxel_size)) throw InputError(name + ": voxel_size must be positive");
    if (m.dims[0] < 0 || m.dims[1] < 0 || m.dims[2] < 0) throw InputError(name + ": negative dims");
    const std::size_t n = m.voxel_count();
    if (m.extinction.size() != n || m.albedo.size() != n || m.emission.size() != n)
        throw InputError(name + ": extinction, albedo and emission need dims[0] * dims[1] * dims[2] values each");
}

void check_voxel(const Medium& m, std::size_t index, std::size_t v) {
    const Rgb &K = m.extinction[v], &a = m.albedo[v], &e = m.emission[v];
    const std::string where = "medium " + std::to_string(index) + " voxel " + std::to_string(v);
    if (!finite(K) || !finite(a) || !finite(e)) throw InputError(where + ": non-finite value");
    for (int ch = 0; ch < 3; ++ch) {
        if (K[ch] < 0.0 || e[ch] < 0.0) throw InputError(where + ": negative extinction or emission");
        if (a[ch] < 0.0 || a[ch] > 1.0) throw InputError(where + ": albedo outside [0, 1]");
        if (K[ch] == 0.0 && e[ch] > 0.0)
            throw InputError(where + ": emission without extinction (the zonal method needs K_t > 0 where a medium emits)");
    }
}

}  // namespace

Zones build_zones(const std::vector<Medium>& media) {
    Zones zones;
    for (std::size_t i = 0; i < media.size(); ++i) {
        const Medium& m = media[i];
        check_medium(m, i);
        for (int32_t z = 0; z < m.dims[2]; ++z)
            for (int32_t y = 0; y < m.dims[1]; ++y)
                for (int32_t x = 0; x < m.dims[0]; ++x) {
                    const std::size_t v = m.index(x, y, z);
                    check_voxel(m, i, v);
                    const Rgb& K = m.extinction[v];
                    if (!(K.r > 0.0 || K.g > 0.0 || K.b > 0.0)) continue;
                    zones.medium.push_back(static_cast<int32_t>(i));
                    zones.voxel.push_back(static_cast<int32_t>(v));
                    zones.centre.push_back(m.origin + m.voxel_size * Vec3(x + 0.5f, y + 0.5f, z + 0.5f));
                    zones.edge.push_back(m.voxel_size);
                    zones.extinction.push_back(K);
                    zones.albedo.push_back(m.albedo[v]);
                    Rgb emitted(0.0);
                    for (int ch = 0; ch < 3; ++ch) emitted[ch] = K[ch] > 0.0 ? m.emission[v][ch] / K[ch] : 0.0;
                    zones.emitted.push_back(emitted);
                }
    }
    const std::vector<OccupiedBox> boxes = occupied_boxes(media);
    for (std::size_t a = 0; a < boxes.size(); ++a)
        for (std::size_t b = a + 1; b < boxes.size(); ++b)
            if (boxes[a].overlaps(boxes[b]))
                throw InputError("media " + std::to_string(a) + " and " + std::to_string(b) +
                                 " overlap; merge them into one grid");
    return zones;
}

}  // namespace radiosity
