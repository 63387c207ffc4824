/// @file zonal_voxel_radiance.cpp
/// @brief voxel_radiance(): zone radiances back onto a medium's voxels, a linear field inside each
/// merged block, each zone's power kept.
#include "media/zonal_grids.h"

#include <glm/common.hpp>

namespace radiosity {
namespace {

/// Mean radiance and mean centre of the zones just across one face of a block.
struct Side {
    Rgb L{0.0};
    glm::dvec3 centre{0.0};
    double count = 0.0;
};

class BlockField {
public:
    BlockField(const Medium& m, const Zones& zones, const std::vector<Rgb>& L, const std::vector<int32_t>& zone_of)
        : m_(m), zones_(zones), L_(L), zone_of_(zone_of) {}

    /// Writes zone k's voxels into `out`.
    void write(std::size_t k, std::vector<Rgb>& out) const {
        const int32_t v = zones_.voxel[k], b = zones_.block[k];
        const std::array<int32_t, 3> c{v % m_.dims[0], (v / m_.dims[0]) % m_.dims[1], v / (m_.dims[0] * m_.dims[1])};
        const Rgb Lk = L_[k];
        const glm::dvec3 ck(zones_.centre[k]);
        Rgb g[3];
        for (int a = 0; a < 3; ++a) g[a] = gradient(c, b, a, Lk, ck);
        Rgb sum(0.0);
        for_each_voxel(c, b, [&](const std::array<int32_t, 3>& p, std::size_t voxel) {
            Rgb value = Lk;
            for (int a = 0; a < 3; ++a) value += g[a] * (centre_of(p)[a] - ck[a]);
            out[voxel] = glm::max(value, Rgb(0.0));
            sum += out[voxel];
        });
        // Keep the zone's power: the mean over its voxels is L_k (held where all clamped).
        const Rgb mean = sum / (double(b) * b * b);
        for_each_voxel(c, b, [&](const std::array<int32_t, 3>&, std::size_t voxel) {
            for (int ch = 0; ch < 3; ++ch)
                out[voxel][ch] = mean[ch] > 0.0 ? out[voxel][ch] * (Lk[ch] / mean[ch]) : Lk[ch];
        });
    }

private:
    template <typename Visit>
    void for_each_voxel(const std::array<int32_t, 3>& c, int32_t b, Visit visit) const {
        for (int32_t z = c[2]; z < c[2] + b; ++z)
            for (int32_t y = c[1]; y < c[1] + b; ++y)
                for (int32_t x = c[0]; x < c[0] + b; ++x) visit({x, y, z}, m_.index(x, y, z));
    }

    glm::dvec3 centre_of(const std::array<int32_t, 3>& p) const {
        return glm::dvec3(m_.origin) + double(m_.voxel_size) * (glm::dvec3(p[0], p[1], p[2]) + 0.5);
    }

    /// The zones across the face of the block at `c` (edge b) on `side` of axis a.
    Side across(const std::array<int32_t, 3>& c, int32_t b, int a, int side) const {
        Side s;
        const int32_t layer = side > 0 ? c[a] + b : c[a] - 1;
        if (layer < 0 || layer >= m_.dims[a]) return s;
        std::array<int32_t, 3> lo = c, hi{c[0] + b, c[1] + b, c[2] + b};
        lo[a] = layer;
        hi[a] = layer + 1;
        for (int32_t z = lo[2]; z < hi[2]; ++z)
            for (int32_t y = lo[1]; y < hi[1]; ++y)
                for (int32_t x = lo[0]; x < hi[0]; ++x) {
                    const int32_t n = zone_of_[m_.index(x, y, z)];
                    if (n < 0) continue;
                    s.L += L_[n];
                    s.centre += glm::dvec3(zones_.centre[n]);
                    s.count += 1.0;
                }
        if (s.count > 0.0) {
            s.L /= s.count;
            s.centre /= s.count;
        }
        return s;
    }

    /// dL/dx_a: central difference between the mean zones across both faces, one-sided with the
    /// block's own value where only one face has zones, 0 where neither does.
    Rgb gradient(const std::array<int32_t, 3>& c, int32_t b, int a, const Rgb& Lk, const glm::dvec3& ck) const {
        const Side minus = across(c, b, a, -1), plus = across(c, b, a, +1);
        if (minus.count > 0.0 && plus.count > 0.0) return (plus.L - minus.L) / (plus.centre[a] - minus.centre[a]);
        if (plus.count > 0.0) return (plus.L - Lk) / (plus.centre[a] - ck[a]);
        if (minus.count > 0.0) return (Lk - minus.L) / (ck[a] - minus.centre[a]);
        return Rgb(0.0);
    }

    const Medium& m_;
    const Zones& zones_;
    const std::vector<Rgb>& L_;
    const std::vector<int32_t>& zone_of_;
};

}  // namespace

std::vector<Rgb> voxel_radiance(const Medium& medium, std::size_t medium_index, const Zones& zones,
                                const std::vector<Rgb>& zone_radiance) {
    if (zone_radiance.size() != zones.size()) throw InputError("voxel_radiance: one radiance per zone");
    const std::vector<int32_t> zone_of = voxel_zones(medium, medium_index, zones);
    std::vector<Rgb> out(medium.voxel_count(), Rgb(0.0));
    const BlockField field(medium, zones, zone_radiance, zone_of);
    for (std::size_t k = 0; k < zones.size(); ++k) {
        if (zones.medium[k] != static_cast<int32_t>(medium_index)) continue;
        if (zones.block[k] == 1)
            out[zones.voxel[k]] = zone_radiance[k];  // a voxel: its zone's value, as before merging
        else
            field.write(k, out);
    }
    return out;
}

}  // namespace radiosity
