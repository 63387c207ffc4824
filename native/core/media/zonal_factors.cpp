/// @file zonal_factors.cpp
/// @brief Exchange-factor rows: item buffers for the surfaces, a transmittance walk per cell.
#include "media/zonal.h"

#include "common/parallel_rows.h"
#include "common/stratified.h"

#include <tbb/enumerable_thread_specific.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>

namespace radiosity {
namespace {

/// Distance from x along d to the plane of element j; 0 when x is not in front of it.
float distance_to_plane(const Elements& e, int32_t j, const Vec3& x, const Vec3& d) {
    const float approach = glm::dot(e.normal[j], d);
    if (!(approach < 0.0f)) return 0.0f;
    return std::max(0.0f, glm::dot(e.normal[j], e.centre[j] - x) / approach);
}

}  // namespace

ZonalRowRenderer::ZonalRowRenderer(const Elements& elements, const Zones& zones, const MediumTracer& tracer,
                                   const ZonalFactorSettings& settings)
    : elements_(elements),
      zones_(zones),
      tracer_(tracer),
      surface_cube_(CubeWeights::make(settings.surface_resolution)),
      zone_cube_(CubeWeights::make(settings.zone_resolution)),
      sum_(elements.size() + zones.size(), glm::dvec3(0.0)) {}

void ZonalRowRenderer::add_cell(int32_t item, double weight, const Channels& tau) {
    const auto n = static_cast<int32_t>(elements_.size());
    auto add = [&](int32_t y, const Channels& fraction) {
        glm::dvec3& s = sum_[y];
        if (s == glm::dvec3(0.0)) touched_.push_back(y);
        s += weight * glm::dvec3(fraction);
    };
    if (item >= 0) add(item, tau);
    for (const ZoneCredit& c : credits_) add(n + c.zone, c.fraction);
}

void ZonalRowRenderer::row(int32_t x, ZonalRow& out) {
    const auto n = static_cast<int32_t>(elements_.size());
    touched_.clear();
    if (x < n) {
        surface_cube_.render_hemisphere(elements_, elements_.centre[x], elements_.normal[x], x);
        const std::vector<float>& dF = surface_cube_.weights().form_factor;
        const std::vector<int32_t>& item = surface_cube_.item_buffer();
        for (std::size_t p = 0; p < item.size(); ++p) {
            const Channels tau = tracer_.trace(elements_.centre[x], surface_cube_.cell_direction(p),
                                               surface_cube_.cell_distance(p), credits_);
            add_cell(item[p], dF[p], tau);
        }
    } else {
        const int32_t k = x - n;
        const Vec3 corner = zones_.centre[k] - 0.5f * zones_.edge[k];
        zone_cube_.render_sphere(elements_, zones_.centre[k], -1);
        const std::vector<float>& solid_angle = zone_cube_.weights().solid_angle;
        const std::vector<int32_t>& item = zone_cube_.item_buffer();
        for (std::size_t p = 0; p < item.size(); ++p) {
            const Vec3 d = zone_cube_.cell_direction(p);
            const Vec3 start = corner + zones_.edge[k] * detail::r3_point(p);
            const int32_t j = item[p];
            const float t_max = j >= 0 ? distance_to_plane(elements_, j, start, d) : zone_cube_.cell_distance(p);
            const Channels tau = tracer_.trace(start, d, t_max, credits_);
            add_cell(j, solid_angle[p] / (4.0 * M_PI), tau);
        }
    }
    std::sort(touched_.begin(), touched_.end());
    out.clear();
    out.col.reserve(touched_.size());
    out.val.reserve(touched_.size());
    for (int32_t y : touched_) {
        out.col.push_back(y);
        out.val.push_back(Channels(sum_[y]));
        sum_[y] = glm::dvec3(0.0);
    }
}

ZonalMatrix compute_exchange_factors(const Elements& elements, const std::vector<Medium>& media, const Zones& zones,
                                     const ZonalFactorSettings& settings, const ProgressFn& progress) {
    const std::size_t unknowns = elements.size() + zones.size();
    const MediumTracer tracer(media, zones);
    bool grey = true;
    for (const Rgb& K : zones.extinction) grey = grey && K.r == K.g && K.g == K.b;
    ZonalMatrix matrix;
    matrix.channels = grey ? 1 : 3;
    const std::size_t bytes_per_nonzero = sizeof(int32_t) + matrix.channels * sizeof(float);

    tbb::enumerable_thread_specific<ZonalRowRenderer> renderers(
        [&] { return ZonalRowRenderer(elements, zones, tracer, settings); });
    std::vector<ZonalRow> rows(unknowns);
    std::atomic<std::size_t> bytes{unknowns * sizeof(int64_t)};
    const bool within_budget =
        detail::parallel_rows("form_factors", unknowns, 4, elements.size(), progress, [&](std::size_t x) {
            renderers.local().row(static_cast<int32_t>(x), rows[x]);
            return (bytes += rows[x].col.size() * bytes_per_nonzero) <= settings.budget_bytes;
        });
    if (!within_budget)
        throw BudgetError("exchange factors of " + std::to_string(elements.size()) + " elements and " +
                          std::to_string(zones.size()) + " zones exceed the memory budget of " +
                          std::to_string(settings.budget_bytes >> 20) +
                          " MiB (they grow as zones squared): use larger voxels or raise the budget");

    matrix.row_start.resize(unknowns + 1);
    matrix.row_start[0] = 0;
    for (std::size_t x = 0; x < unknowns; ++x)
        matrix.row_start[x + 1] = matrix.row_start[x] + int64_t(rows[x].col.size());
    matrix.col.reserve(matrix.row_start[unknowns]);
    matrix.val.reserve(matrix.row_start[unknowns] * matrix.channels);
    for (ZonalRow& row : rows) {
        matrix.col.insert(matrix.col.end(), row.col.begin(), row.col.end());
        for (const Channels& v : row.val) {
            if (grey)
                matrix.val.push_back(v.r);
            else
                matrix.val.insert(matrix.val.end(), {v.r, v.g, v.b});
        }
        row = ZonalRow();
    }
    return matrix;
}

}  // namespace radiosity
