/// @file irradiance_cache.cpp
/// @brief Records, their gradients and the points read from them (irradiance_cache.h).
#include "output/irradiance_cache.h"

#include "common/stratified.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

namespace radiosity::detail {

GradientWeights gradient_weights(int grid, const std::vector<double>& inverse_distance) {
    const int m = grid, n = grid;
    const double pi = M_PI;
    // Per polar stratum j (the same at every azimuth): the factors its samples' terms take.
    struct Stratum {
        double rotation;      ///< tan theta_j
        double towards_pole;  ///< across theta_{j-}: (2 pi / n) sin theta_{j-} cos^2 theta_{j-}
        double across_phi;    ///< across phi_k: cos theta_j (cos theta_{j-} - cos theta_{j+}) / sin theta_j
    };
    std::vector<Stratum> strata(static_cast<std::size_t>(m));
    for (int j = 0; j < m; ++j) {
        const double sin2 = (j + 0.5) / m, sin_j = std::sqrt(sin2), cos_j = std::sqrt(1.0 - sin2);
        const double sin_low = std::sqrt(double(j) / m), cos2_low = 1.0 - double(j) / m;
        const double cos_low = std::sqrt(1.0 - double(j) / m), cos_high = std::sqrt(1.0 - double(j + 1) / m);
        strata[std::size_t(j)] = {sin_j / cos_j, (2.0 * pi / n) * sin_low * cos2_low,
                                  cos_j * (cos_low - cos_high) / sin_j};
    }
    const std::size_t rays = std::size_t(m) * std::size_t(n);
    GradientWeights w{std::vector<glm::dvec2>(rays, glm::dvec2(0.0)), std::vector<glm::dvec2>(rays, glm::dvec2(0.0))};
    auto at = [&](int j, int k) { return std::size_t(k) * std::size_t(m) + std::size_t(j); };
    auto in_plane = [](double phi) { return glm::dvec2(std::cos(phi), std::sin(phi)); };
    // A difference of two samples across a boundary, by the nearer of the two hits: + to one, - to the other.
    auto across = [&](std::size_t here, std::size_t there, double factor, const glm::dvec2& direction) {
        const glm::dvec2 weight = factor * std::max(inverse_distance[here], inverse_distance[there]) / pi * direction;
        w.translation[here] += weight;
        w.translation[there] -= weight;
    };
    for (int k = 0; k < n; ++k) {
        const double phi = 2.0 * pi * (k + 0.5) / n, phi_low = 2.0 * pi * k / n;
        const glm::dvec2 u = in_plane(phi), v = in_plane(phi + 0.5 * pi), v_low = in_plane(phi_low + 0.5 * pi);
        const int previous = (k + n - 1) % n;
        for (int j = 0; j < m; ++j) {
            const Stratum& s = strata[std::size_t(j)];
            // Rotation: each sample's cosine turns by (n x omega) / cos theta = tan theta v_k; the mean's: / (m n).
            w.rotation[at(j, k)] += s.rotation / double(m * n) * v;
            // Translation across the stratum's boundary towards the pole (theta_{j-}), then across
            // the one at phi_k (Ward & Heckbert 1992), each by the nearer of the two hits.
            if (j > 0) across(at(j, k), at(j - 1, k), s.towards_pole, u);
            across(at(j, k), at(j, previous), s.across_phi, v_low);
        }
    }
    return w;
}

LightGradients PlaneGradients::in_space(const glm::dvec3& t, const glm::dvec3& b) const {
    LightGradients out;
    for (std::size_t c = 0; c < 3; ++c) {
        out.rotation[c] = rotation[c].x * t + rotation[c].y * b;
        out.translation[c] = translation[c].x * t + translation[c].y * b;
    }
    return out;
}

std::size_t CachePlan::records() const { return std::size_t(std::count(record.begin(), record.end(), uint8_t(1))); }

double cache_error(const CachePoint& r, const CachePoint& p) {
    const glm::dvec3 offset = p.position - r.position;
    const double distance = glm::length(offset);
    const double cosine = glm::dot(r.normal, p.normal);
    if (!(r.harmonic_distance > 0.0) || !(cosine > 0.0)) return -1.0;
    // Neither in front of the point nor behind it (a step, the far side of a thin wall).
    if (std::abs(glm::dot(offset, 0.5 * (r.normal + p.normal))) > 0.05 * distance) return -1.0;
    // Neighbour clamping (Krivanek, Bouatouch, Pattanaik & Zara 2006): a record reaches no farther than
    // the point's own distance to what it sees plus their separation. A wall's record half a metre
    // under a ledge, seeing the room, would otherwise reach a point just under the ledge, whose rays
    // meet the ledge a few centimetres off (+4.5% there).
    const double radius = std::min(r.harmonic_distance, p.harmonic_distance + distance);
    return distance / radius + std::sqrt(std::max(0.0, 1.0 - cosine));
}

Rgb read_record(const CachePoint& record, const Rgb& indirect, const LightGradients& gradients, const CachePoint& p) {
    return indirect + gradients.change(p.position - record.position, glm::cross(record.normal, p.normal));
}

namespace {

/// Records by the cells of a uniform grid their validity spheres (radius a R_i) overlap.
class RecordGrid {
public:
    RecordGrid(double cell) : cell_(cell) {}
    void insert(int32_t record, const glm::dvec3& centre, double radius) {
        const glm::ivec3 low = cell_of(centre - glm::dvec3(radius)), high = cell_of(centre + glm::dvec3(radius));
        for (int x = low.x; x <= high.x; ++x)
            for (int y = low.y; y <= high.y; ++y)
                for (int z = low.z; z <= high.z; ++z) cells_[key(glm::ivec3(x, y, z))].push_back(record);
    }
    const std::vector<int32_t>& near(const glm::dvec3& point) const {
        static const std::vector<int32_t> none;
        const auto found = cells_.find(key(cell_of(point)));
        return found == cells_.end() ? none : found->second;
    }

private:
    glm::ivec3 cell_of(const glm::dvec3& p) const { return glm::ivec3(glm::floor(p / cell_)); }
    static int64_t key(const glm::ivec3& c) {
        return (int64_t(c.x) & 0x1FFFFF) | ((int64_t(c.y) & 0x1FFFFF) << 21) | ((int64_t(c.z) & 0x1FFFFF) << 42);
    }
    double cell_;
    std::unordered_map<int64_t, std::vector<int32_t>> cells_;
};

/// The grid's cell: the median validity radius, or an eighth of the largest (a record then
/// overlaps at most 17^3 cells).
double cell_size(const std::vector<CachePoint>& points, double accuracy) {
    std::vector<double> radius;
    for (const CachePoint& p : points)
        if (p.harmonic_distance > 0.0) radius.push_back(accuracy * p.harmonic_distance);
    if (radius.empty()) return 1.0;
    std::nth_element(radius.begin(), radius.begin() + long(radius.size() / 2), radius.end());
    const double median = radius[radius.size() / 2];
    return std::max({median, *std::max_element(radius.begin(), radius.end()) / 8.0, 1e-9});
}

/// The kept points by index, then the others in a pseudo-random order fixed by their index.
std::vector<int32_t> visiting_order(const std::vector<CachePoint>& points) {
    std::vector<int32_t> order(points.size());
    std::iota(order.begin(), order.end(), 0);
    auto rank = [&](int32_t i) {
        return std::make_pair(!points[std::size_t(i)].keep, mix_seed(uint32_t(i), 0xCAC4EU));
    };
    std::stable_sort(order.begin(), order.end(), [&](int32_t a, int32_t b) { return rank(a) < rank(b); });
    return order;
}

}  // namespace

CachePlan plan_cache(const std::vector<CachePoint>& points, double accuracy) {
    CachePlan plan{std::vector<uint8_t>(points.size(), 1),
                   std::vector<std::vector<std::pair<int32_t, double>>>(points.size())};
    if (!(accuracy > 0.0)) return plan;
    RecordGrid grid(cell_size(points, accuracy));
    // The weight 1 / eps - 1 / a of a record at p, 0 where it may not be read (not even at eps just below a,
    // where the weight would be lost to round-off).
    auto weight = [&](int32_t r, const CachePoint& p) {
        const double error = cache_error(points[std::size_t(r)], p);
        return error >= 0.0 && error < (1.0 - 1e-6) * accuracy ? 1.0 / std::max(error, 1e-12) - 1.0 / accuracy : 0.0;
    };
    auto covered = [&](const CachePoint& p) {
        const std::vector<int32_t>& near = grid.near(p.position);
        return std::any_of(near.begin(), near.end(), [&](int32_t r) { return weight(r, p) > 0.0; });
    };
    for (const int32_t i : visiting_order(points)) {
        const CachePoint& p = points[std::size_t(i)];
        plan.record[std::size_t(i)] = p.keep || !(p.harmonic_distance > 0.0) || !covered(p);
        if (plan.record[std::size_t(i)] && p.harmonic_distance > 0.0)
            grid.insert(i, p.position, accuracy * p.harmonic_distance);
    }
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (plan.record[i]) continue;
        auto& from = plan.from[i];
        double total = 0.0;
        for (const int32_t r : grid.near(points[i].position)) {
            const double w = weight(r, points[i]);
            if (!(w > 0.0)) continue;
            from.emplace_back(r, w);
            total += w;
        }
        std::sort(from.begin(), from.end());
        for (auto& entry : from) entry.second /= total;
    }
    return plan;
}

}  // namespace radiosity::detail
