/// @file zonal_grids.cpp
/// @brief medium_grids(): zone radiances trilinearly onto a finer grid, extrapolated at the
/// medium's border, each zone's power kept.
#include "media/zonal_grids.h"

#include <glm/common.hpp>

namespace radiosity {
namespace {

bool is_zone(const Rgb& K) { return K.r > 0.0 || K.g > 0.0 || K.b > 0.0; }

/// The zones' radiance with the border rule of zonal_grids.h, around one home zone.
class Stencil {
public:
    Stencil(const Medium& m, const std::vector<Rgb>& radiance) : m_(m), radiance_(radiance) {}

    /// Home zone (x, y, z); its steps to either side along each axis.
    void set_home(const std::array<int32_t, 3>& h) {
        home_ = h;
        const Rgb L = radiance_[m_.index(h[0], h[1], h[2])];
        for (int a = 0; a < 3; ++a)
            for (int side = 0; side < 2; ++side) {
                const int d = side ? 1 : -1;
                std::array<int32_t, 3> n = h, o = h;
                n[a] += d;
                o[a] -= d;
                step_[a][side] = zone(n) ? value(n) - L : zone(o) ? L - value(o) : Rgb(0.0);
            }
    }

    /// J at the zone centre home + offset (offsets in {-1, 0, 1}).
    Rgb at(const std::array<int, 3>& offset) const {
        std::array<int32_t, 3> c = home_;
        for (int a = 0; a < 3; ++a) c[a] += offset[a];
        if (zone(c)) return value(c);
        Rgb v = value(home_);
        for (int a = 0; a < 3; ++a)
            if (offset[a] != 0) v += step_[a][offset[a] > 0];
        return v;
    }

private:
    bool zone(const std::array<int32_t, 3>& c) const {
        for (int a = 0; a < 3; ++a)
            if (c[a] < 0 || c[a] >= m_.dims[a]) return false;
        return is_zone(m_.extinction[m_.index(c[0], c[1], c[2])]);
    }
    Rgb value(const std::array<int32_t, 3>& c) const { return radiance_[m_.index(c[0], c[1], c[2])]; }

    const Medium& m_;
    const std::vector<Rgb>& radiance_;
    std::array<int32_t, 3> home_{};
    Rgb step_[3][2];
};

}  // namespace

MediumGrids medium_grids(const Medium& medium, const std::vector<Rgb>& radiance, int subdivision) {
    if (subdivision < 1) throw InputError("grid subdivision must be at least 1");
    if (radiance.size() != medium.voxel_count() || medium.extinction.size() != medium.voxel_count())
        throw InputError("medium_grids: one radiance and one extinction per voxel of the medium");
    const int s = subdivision;
    MediumGrids g;
    g.origin = medium.origin;
    g.voxel_size = medium.voxel_size / float(s);
    g.dims = {medium.dims[0] * s, medium.dims[1] * s, medium.dims[2] * s};
    const std::size_t fine_count = std::size_t(g.dims[0]) * g.dims[1] * g.dims[2];
    g.density.assign(fine_count, Rgb(0.0));
    g.emission.assign(fine_count, Rgb(0.0));

    Stencil stencil(medium, radiance);
    std::vector<Rgb> J(std::size_t(s) * s * s);
    std::vector<std::size_t> fine(J.size());
    for (int32_t z = 0; z < medium.dims[2]; ++z)
        for (int32_t y = 0; y < medium.dims[1]; ++y)
            for (int32_t x = 0; x < medium.dims[0]; ++x) {
                const std::size_t v = medium.index(x, y, z);
                const Rgb K = medium.extinction[v];
                if (!is_zone(K)) continue;
                stencil.set_home({x, y, z});
                Rgb sum(0.0);
                for (int k = 0, f = 0; k < s; ++k)
                    for (int j = 0; j < s; ++j)
                        for (int i = 0; i < s; ++i, ++f) {
                            // Fine centre relative to the home zone's centre, in zones: the
                            // stencil's lower corner and the weight of its upper one per axis.
                            const int local[3] = {i, j, k};
                            int lower[3];
                            double w[3];
                            for (int a = 0; a < 3; ++a) {
                                const double t = (local[a] + 0.5) / s - 0.5;
                                lower[a] = t < 0.0 ? -1 : 0;
                                w[a] = t - lower[a];
                            }
                            Rgb value(0.0);
                            for (int c = 0; c < 8; ++c) {
                                double weight = 1.0;
                                std::array<int, 3> offset{};
                                for (int a = 0; a < 3; ++a) {
                                    const int up = (c >> a) & 1;
                                    offset[a] = lower[a] + up;
                                    weight *= up ? w[a] : 1.0 - w[a];
                                }
                                if (weight != 0.0) value += weight * stencil.at(offset);
                            }
                            J[f] = glm::max(value, Rgb(0.0));
                            sum += J[f];
                            fine[f] = std::size_t(x * s + i) +
                                      std::size_t(g.dims[0]) *
                                          (std::size_t(y * s + j) + std::size_t(g.dims[1]) * (z * s + k));
                        }
                // Keep the zone's power: the mean of J over its cells is L_k (held where all clamped).
                const Rgb L = radiance[v], mean = sum / double(J.size());
                for (std::size_t f = 0; f < J.size(); ++f) {
                    Rgb kept;
                    for (int ch = 0; ch < 3; ++ch) kept[ch] = mean[ch] > 0.0 ? J[f][ch] * (L[ch] / mean[ch]) : L[ch];
                    g.density[fine[f]] = K;
                    g.emission[fine[f]] = K * kept;
                }
            }
    return g;
}

}  // namespace radiosity
