/// @file row_renderer.cpp
/// @brief Form-factor rows: averaged hemi-cube orientations, then the near-field correction.
#include "radiosity/row_renderer.h"

#include <algorithm>
#include <cmath>

namespace radiosity {

RowRenderer::RowRenderer(std::shared_ptr<const CubeWeights> weights, const RowSettings& settings)
    : hemicube_(std::move(weights)), settings_(settings) {
    if (settings.rotations < 1) throw InputError("hemi-cube rotations must be >= 1, got " + std::to_string(settings.rotations));
    if (settings.near_field.enabled && (settings.near_field.sub_points < 1 || !(settings.near_field.distance >= 0.0f)))
        throw InputError("near field: sub_points must be >= 1 and distance >= 0");
}

void RowRenderer::row(const Elements& elements, int32_t i, SparseRow& out) {
    const int k = settings_.rotations;
    const Vec3 &centre = elements.centre[i], &normal = elements.normal[i];
    if (k == 1) {
        hemicube_.render_hemisphere(elements, centre, normal, i);
        hemicube_.accumulate(hemicube_.weights().form_factor, out);
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
