/// @file transmittance.cpp
/// @brief The 3D-DDA through each medium's occupied box, media in ray order.
#include "media/transmittance.h"

#include "media/volume_bounds.h"

#include <algorithm>
#include <cmath>

namespace radiosity {
namespace {

constexpr float kOpaque = 1e-7f;  ///< below this in every channel the rest of the walk is negligible

/// [t0, t1] of the ray inside the box, clipped to [0, t_max]; t0 >= t1 when it misses.
void clip(const Vec3& lo, const Vec3& hi, const Vec3& o, const Vec3& d, float t_max, float& t0, float& t1) {
    t0 = 0.0f;
    t1 = t_max;
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0.0f) {
            if (o[a] < lo[a] || o[a] > hi[a]) t1 = -1.0f;
            continue;
        }
        const float inv = 1.0f / d[a];
        float near = (lo[a] - o[a]) * inv, far = (hi[a] - o[a]) * inv;
        if (near > far) std::swap(near, far);
        t0 = std::max(t0, near);
        t1 = std::min(t1, far);
    }
}

}  // namespace

MediumTracer::MediumTracer(const std::vector<Medium>& media, const Zones& zones) {
    extinction_.resize(zones.size());
    for (std::size_t k = 0; k < zones.size(); ++k) extinction_[k] = Channels(zones.extinction[k]);
    const std::vector<OccupiedBox> boxes = occupied_boxes(media);
    for (std::size_t i = 0; i < media.size(); ++i) {
        if (boxes[i].empty) continue;
        Grid g;
        g.origin = media[i].origin;
        g.h = media[i].voxel_size;
        g.dims = media[i].dims;
        g.lo = boxes[i].lo;
        g.hi = boxes[i].hi;
        g.world_lo = boxes[i].world_lo;
        g.world_hi = boxes[i].world_hi;
        g.zone = voxel_zones(media[i], i, zones);
        grids_.push_back(std::move(g));
    }
}

Channels MediumTracer::trace(const Vec3& origin, const Vec3& direction, float t_max,
                             std::vector<ZoneCredit>& credits) const {
    credits.clear();
    Channels tau(1.0f);
    // Occupied boxes do not overlap, so their intervals along the ray are disjoint: walk them in order.
    struct Span {
        float t0, t1;
        const Grid* grid;
    };
    thread_local std::vector<Span> spans;  // reused: no allocation per ray
    spans.clear();
    for (const Grid& g : grids_) {
        float t0, t1;
        clip(g.world_lo, g.world_hi, origin, direction, t_max, t0, t1);
        if (t0 < t1) spans.push_back({t0, t1, &g});
    }
    std::sort(spans.begin(), spans.end(), [](const Span& a, const Span& b) { return a.t0 < b.t0; });
    for (const Span& span : spans) {
        walk(*span.grid, origin, direction, span.t0, span.t1, tau, credits);
        if (tau.r < kOpaque && tau.g < kOpaque && tau.b < kOpaque) break;
    }
    return tau;
}

void MediumTracer::walk(const Grid& g, const Vec3& origin, const Vec3& d, float t0, float t1, Channels& tau,
                        std::vector<ZoneCredit>& credits) const {
    // Voxel coordinates q(t) = (origin + t d - grid origin) / h; the walk starts at t0's voxel.
    const Vec3 p = (origin - g.origin) / g.h;
    std::array<int32_t, 3> v{}, step{};
    std::array<float, 3> t_next{}, t_delta{};
    for (int a = 0; a < 3; ++a) {
        const float q = p[a] + t0 * d[a] / g.h;
        v[a] = std::min(std::max(static_cast<int32_t>(std::floor(q)), g.lo[a]), g.hi[a] - 1);
        if (d[a] > 0.0f) {
            step[a] = 1;
            t_delta[a] = g.h / d[a];
            t_next[a] = (float(v[a] + 1) - p[a]) * g.h / d[a];
        } else if (d[a] < 0.0f) {
            step[a] = -1;
            t_delta[a] = -g.h / d[a];
            t_next[a] = (float(v[a]) - p[a]) * g.h / d[a];
        } else {
            step[a] = 0;
            t_delta[a] = INFINITY;
            t_next[a] = INFINITY;
        }
    }
    float t = t0;
    while (true) {
        const int a = t_next[0] < t_next[1] ? (t_next[0] < t_next[2] ? 0 : 2) : (t_next[1] < t_next[2] ? 1 : 2);
        const float t_exit = std::min(t_next[a], t1);
        const float length = t_exit - t;
        const int32_t k = g.zone[v[0] + std::size_t(g.dims[0]) * (v[1] + std::size_t(g.dims[1]) * v[2])];
        if (k >= 0 && length > 0.0f) {
            const Channels& K = extinction_[k];
            const Channels after(tau.r * std::exp(-K.r * length), tau.g * std::exp(-K.g * length),
                                 tau.b * std::exp(-K.b * length));
            // A merged zone spans several voxels: one credit per zone crossed, not per voxel.
            if (!credits.empty() && credits.back().zone == k)
                credits.back().fraction += tau - after;
            else
                credits.push_back({k, tau - after});
            tau = after;
            if (tau.r < kOpaque && tau.g < kOpaque && tau.b < kOpaque) return;
        }
        if (t_next[a] >= t1) return;
        t = std::max(t, t_exit);
        v[a] += step[a];
        if (v[a] < g.lo[a] || v[a] >= g.hi[a]) return;
        t_next[a] += t_delta[a];
    }
}

}  // namespace radiosity
