/// @file volume.cpp
/// @brief Principled Volume coefficients, voxel grids and their zones.
#include "media/volume.h"

#include "media/volume_bounds.h"

#include <glm/common.hpp>
#include <glm/exponential.hpp>

#include <algorithm>
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
    if (!(m.voxel_size > 0.0f) || !std::isfinite(m.voxel_size))
        throw InputError(name + ": voxel_size must be positive");
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
            throw InputError(where +
                             ": emission without extinction (the zonal method needs K_t > 0 where a medium emits)");
    }
}

bool occupied(const Rgb& K) { return K.r > 0.0 || K.g > 0.0 || K.b > 0.0; }

bool agree(const Rgb& a, const Rgb& b) {
    for (int ch = 0; ch < 3; ++ch)
        if (std::abs(a[ch] - b[ch]) > kUniformTolerance * std::max(std::abs(a[ch]), std::abs(b[ch]))) return false;
    return true;
}

/// Adds the zones of one medium's octree blocks to `zones`.
class BlockZones {
public:
    BlockZones(const Medium& m, std::size_t medium_index, Zones& zones)
        : m_(m), medium_(static_cast<int32_t>(medium_index)), zones_(zones) {}

    /// The block of `size` voxels per edge at `corner`: one zone when uniform (or a single occupied
    /// voxel), else its eight children of half the size, x fastest.
    void add(const std::array<int32_t, 3>& corner, int32_t size) {
        if (size == 1 || uniform(corner, size)) {
            if (occupied(m_.extinction[m_.index(corner[0], corner[1], corner[2])])) add_zone(corner, size);
            return;
        }
        const int32_t half = size / 2;
        for (int32_t k = 0; k < 2; ++k)
            for (int32_t j = 0; j < 2; ++j)
                for (int32_t i = 0; i < 2; ++i) {
                    const std::array<int32_t, 3> child{corner[0] + i * half, corner[1] + j * half,
                                                       corner[2] + k * half};
                    if (child[0] < m_.dims[0] && child[1] < m_.dims[1] && child[2] < m_.dims[2]) add(child, half);
                }
    }

private:
    template <typename Visit>
    void for_each_voxel(const std::array<int32_t, 3>& c, int32_t size, Visit visit) const {
        for (int32_t z = c[2]; z < c[2] + size; ++z)
            for (int32_t y = c[1]; y < c[1] + size; ++y)
                for (int32_t x = c[0]; x < c[0] + size; ++x) visit(m_.index(x, y, z));
    }

    /// Inside the grid, every voxel a zone, all coefficients agreeing with the first voxel's.
    bool uniform(const std::array<int32_t, 3>& c, int32_t size) const {
        for (int a = 0; a < 3; ++a)
            if (c[a] + size > m_.dims[a]) return false;
        const std::size_t first = m_.index(c[0], c[1], c[2]);
        bool same = true;
        for_each_voxel(c, size, [&](std::size_t v) {
            same = same && occupied(m_.extinction[v]) && agree(m_.extinction[v], m_.extinction[first]) &&
                   agree(m_.albedo[v], m_.albedo[first]) && agree(m_.emission[v], m_.emission[first]);
        });
        return same;
    }

    void add_zone(const std::array<int32_t, 3>& c, int32_t size) {
        const std::size_t first = m_.index(c[0], c[1], c[2]);
        Rgb K = m_.extinction[first], albedo = m_.albedo[first], emission = m_.emission[first];
        if (size > 1) {  // the block's means: total extinction, scattering and emission kept
            Rgb K_sum(0.0), scattering_sum(0.0), emission_sum(0.0);
            for_each_voxel(c, size, [&](std::size_t v) {
                K_sum += m_.extinction[v];
                scattering_sum += m_.albedo[v] * m_.extinction[v];
                emission_sum += m_.emission[v];
            });
            const double n = double(size) * size * size;
            K = K_sum / n;
            emission = emission_sum / n;
            for (int ch = 0; ch < 3; ++ch) albedo[ch] = K_sum[ch] > 0.0 ? scattering_sum[ch] / K_sum[ch] : 0.0;
        }
        zones_.medium.push_back(medium_);
        zones_.voxel.push_back(static_cast<int32_t>(first));
        zones_.block.push_back(size);
        const float half = 0.5f * float(size);
        zones_.centre.push_back(m_.origin + m_.voxel_size * Vec3(c[0] + half, c[1] + half, c[2] + half));
        zones_.edge.push_back(m_.voxel_size * float(size));
        zones_.extinction.push_back(K);
        zones_.albedo.push_back(albedo);
        Rgb emitted(0.0);
        for (int ch = 0; ch < 3; ++ch) emitted[ch] = K[ch] > 0.0 ? emission[ch] / K[ch] : 0.0;
        zones_.emitted.push_back(emitted);
    }

    const Medium& m_;
    int32_t medium_;
    Zones& zones_;
};

}  // namespace

Zones build_zones(const std::vector<Medium>& media, int max_block_level) {
    if (max_block_level < 0 || max_block_level > 10) throw InputError("max_block_level must be in [0, 10]");
    const int32_t top = int32_t(1) << max_block_level;
    Zones zones;
    for (std::size_t i = 0; i < media.size(); ++i) {
        const Medium& m = media[i];
        check_medium(m, i);
        for (std::size_t v = 0; v < m.voxel_count(); ++v) check_voxel(m, i, v);
        BlockZones blocks(m, i, zones);
        for (int32_t z = 0; z < m.dims[2]; z += top)
            for (int32_t y = 0; y < m.dims[1]; y += top)
                for (int32_t x = 0; x < m.dims[0]; x += top) blocks.add({x, y, z}, top);
    }
    const std::vector<OccupiedBox> boxes = occupied_boxes(media);
    for (std::size_t a = 0; a < boxes.size(); ++a)
        for (std::size_t b = a + 1; b < boxes.size(); ++b)
            if (boxes[a].overlaps(boxes[b]))
                throw InputError("media " + std::to_string(a) + " and " + std::to_string(b) +
                                 " overlap; merge them into one grid");
    return zones;
}

std::vector<int32_t> voxel_zones(const Medium& medium, std::size_t medium_index, const Zones& zones) {
    std::vector<int32_t> zone(medium.voxel_count(), -1);
    const std::array<int32_t, 3> d = medium.dims;
    for (std::size_t k = 0; k < zones.size(); ++k) {
        if (zones.medium[k] != static_cast<int32_t>(medium_index)) continue;
        const int32_t v = zones.voxel[k], b = zones.block[k];
        const int32_t x0 = v % d[0], y0 = (v / d[0]) % d[1], z0 = v / (d[0] * d[1]);
        for (int32_t z = z0; z < z0 + b; ++z)
            for (int32_t y = y0; y < y0 + b; ++y)
                for (int32_t x = x0; x < x0 + b; ++x) zone[medium.index(x, y, z)] = static_cast<int32_t>(k);
    }
    return zone;
}

}  // namespace radiosity
