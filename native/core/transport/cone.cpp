/// @file cone.cpp
/// @brief The clipped irradiance of a cone of uniform radiance and its uniform directions (cone.h).
#include "transport/cone.h"

#include "common/stratified.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace radiosity::detail {

double clipped_cone_cosine(double cos_theta, double sin2_sigma) {
    cos_theta = std::clamp(cos_theta, -1.0, 1.0);
    if (sin2_sigma >= 1.0) return M_PI;
    if (cos_theta * cos_theta > sin2_sigma) return cos_theta > 0.0 ? M_PI * sin2_sigma * cos_theta : 0.0;
    const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    const double x = std::sqrt(1.0 / sin2_sigma - 1.0);  // cot sigma
    const double y = std::clamp(-x * cos_theta / sin_theta, -1.0, 1.0);
    const double s = sin_theta * std::sqrt(1.0 - y * y);
    return std::max(0.0, (cos_theta * std::acos(y) - x * s) * sin2_sigma + std::atan(s / x));
}

Cone::Cone(const glm::dvec3& unit_axis, double cos_half_angle) : axis(unit_axis), cos_max(cos_half_angle) {
    tangent_frame(axis, t, b);
}

glm::dvec3 Cone::direction(double u, double v) const {
    const double cos_theta = 1.0 - u * (1.0 - cos_max);
    const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    const double phi = 2.0 * M_PI * v;
    return sin_theta * std::cos(phi) * t + sin_theta * std::sin(phi) * b + cos_theta * axis;
}

uint32_t position_seed(const Vec3& x, uint32_t salt) {
    uint32_t bits[3];
    std::memcpy(bits, &x, sizeof(bits));
    return mix_seed(mix_seed(mix_seed(bits[0], bits[1]), bits[2]), salt);
}

}  // namespace radiosity::detail
