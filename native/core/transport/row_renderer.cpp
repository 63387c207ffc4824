/// @file row_renderer.cpp
/// @brief Form-factor rows: averaged hemi-cube orientations, then the near-field correction.
#include "transport/row_renderer.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace radiosity {

RowRenderer::RowRenderer(std::shared_ptr<const CubeWeights> weights, const RowSettings& settings)
    : hemicube_(std::move(weights)), settings_(settings) {
    if (settings.rotations < 1)
        throw InputError("hemi-cube rotations must be >= 1, got " + std::to_string(settings.rotations));
    if (settings.near_field.enabled && (settings.near_field.sub_points < 1 || !(settings.near_field.distance >= 0.0f)))
        throw InputError("near field: sub_points must be >= 1 and distance >= 0");
}

void RowRenderer::fill_pinholes(SparseRow& row) {
    const std::vector<int32_t>& item = hemicube_.item_buffer();
    const std::vector<float>& weight = hemicube_.weights().form_factor;
    const std::size_t n = static_cast<std::size_t>(hemicube_.weights().resolution);
    // Faces: the top (n x n), then four sides of n x n/2 (cube_faces.h); interior cells only.
    auto scan = [&](std::size_t offset, std::size_t rows) {
        for (std::size_t r = 1; r + 1 < rows; ++r)
            for (std::size_t c = 1; c + 1 < n; ++c) {
                const std::size_t cell = offset + r * n + c;
                if (item[cell] >= 0) continue;
                const std::array<int32_t, 4> around{item[cell - n], item[cell - 1], item[cell + 1], item[cell + n]};
                if (*std::min_element(around.begin(), around.end()) < 0) continue;
                int32_t best = around[0];
                int best_count = 0;
                for (int32_t id : around) {
                    const auto count = static_cast<int>(std::count(around.begin(), around.end(), id));
                    if (count > best_count) best = id, best_count = count;
                }
                const auto at = std::lower_bound(row.col.begin(), row.col.end(), best);
                row.val[static_cast<std::size_t>(at - row.col.begin())] +=
                    weight[cell];  // best is in the row: it was seen
            }
    };
    scan(0, n);
    for (std::size_t f = 0; f < 4; ++f) scan(n * n + f * n * (n / 2), n / 2);
}

void RowRenderer::row(const Elements& elements, int32_t i, SparseRow& out) {
    const int k = settings_.rotations;
    const Vec3 &centre = elements.centre[i], &normal = elements.normal[i];
    if (k == 1) {
        hemicube_.render_hemisphere(elements, centre, normal, i);
        hemicube_.accumulate(hemicube_.weights().form_factor, out);
        if (settings_.fill_pinholes) fill_pinholes(out);
    } else {
        // The hemi-cube repeats every quarter turn; the offset (golden ratio sequence) keeps
        // neighbouring elements from sharing one set of orientations.
        const double offset = std::fmod(0.6180339887498949 * i, 1.0);
        if (sum_.size() < elements.size()) sum_.resize(elements.size(), 0.0);
        touched_.clear();
        for (int m = 0; m < k; ++m) {
            const auto angle = static_cast<float>(0.5 * M_PI * (m + offset) / k);
            hemicube_.render_hemisphere(elements, centre, normal, i, angle);
            hemicube_.accumulate(hemicube_.weights().form_factor, turn_);
            if (settings_.fill_pinholes) fill_pinholes(turn_);
            for (std::size_t c = 0; c < turn_.col.size(); ++c) {
                const int32_t j = turn_.col[c];
                if (sum_[j] == 0.0) touched_.push_back(j);
                sum_[j] += turn_.val[c];
            }
        }
        std::sort(touched_.begin(), touched_.end());
        out.clear();
        for (int32_t j : touched_) {
            out.col.push_back(j);
            out.val.push_back(static_cast<float>(sum_[j] / k));
            sum_[j] = 0.0;
        }
    }
    if (settings_.near_field.enabled) correct_near_field(elements, i, settings_.resolution, settings_.near_field, out);
}

}  // namespace radiosity
