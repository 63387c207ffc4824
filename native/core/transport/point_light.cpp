/// @file point_light.cpp
/// @brief Point and spot lamps as spheres or disks (point_light.h).
#include "transport/point_light.h"

#include "common/stratified.h"
#include "transport/cone.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace radiosity {

float spot_profile(const PointLight& light, const Vec3& direction_from_light) {
    if (light.cos_half_angle <= -1.0f) return 1.0f;
    const float cos_angle = glm::dot(direction_from_light, light.direction);
    if (cos_angle <= light.cos_half_angle) return 0.0f;
    const float t = cos_angle - light.cos_half_angle;
    const float falloff = light.cosine_profile ? cos_angle : 1.0f;
    if (light.smooth <= 0.0f || t >= light.smooth) return falloff;
    const float s = t / light.smooth;
    return falloff * s * s * (3.0f - 2.0f * s);
}

namespace {

/// The lamp seen from a point: the unit axis towards its centre, the distance, and sin^2 of the
/// half-angle of the cone it fills (1 or more inside a sphere).
struct View {
    glm::dvec3 axis{0.0};
    double distance = 0.0, sin2 = 0.0;
};

View view_of(const PointLight& light, const Vec3& x) {
    View v;
    const glm::dvec3 d = glm::dvec3(light.position) - glm::dvec3(x);
    v.distance = glm::length(d);
    if (!(v.distance > 0.0)) return v;
    v.axis = d / v.distance;
    const double r2 = double(light.radius) * light.radius, d2 = v.distance * v.distance;
    v.sin2 = light.shape == LampShape::Sphere ? r2 / d2 : r2 / (d2 + r2);
    return v;
}

double radiance_scale(const PointLight& light) { return 1.0 / (M_PI * double(light.radius) * light.radius); }

/// Distance along unit `u` from the shading point to the lamp's surface.
double distance_to_lamp(const PointLight& light, const View& v, const glm::dvec3& u) {
    const double along = glm::dot(u, v.axis);
    if (light.shape != LampShape::Sphere) return v.distance / std::max(along, 1e-9);
    const double r2 = double(light.radius) * light.radius;
    const double rest = v.distance * v.distance * (along * along - 1.0) + r2;
    const double root = std::sqrt(std::max(0.0, rest));
    return v.distance * along + (v.sin2 < 1.0 ? -root : root);  // the near side, or the way out
}

/// How much less (or more) light the lamp's sphere or disk gives a polygon than a point at its
/// centre: the point's light at stratified points of the polygon weighting the ratio of the two
/// there (a disk facing x gives I cos / (d^2 + r^2) where the point gives I cos / d^2: 0.72 of it
/// 8 cm from a 5 cm lamp). More points where the polygon is large next to the lamp's `height` over
/// its plane, whose light peaks under the lamp.
double shape_over_point(const PointLight& light, const Vec3* corners, int count, const Vec3& normal, double area,
                        double height) {
    if (light.radius <= 0.0f) return 1.0;
    constexpr int kMinGrid = 4, kMaxGrid = 16;
    const int grid = std::clamp(int(std::ceil(kMinGrid * std::sqrt(area) / height)), kMinGrid, kMaxGrid);
    std::array<Vec3, kMaxGrid * kMaxGrid> points;
    detail::stratified_points(corners, count, grid, 0x5A0FU, points.data());
    PointLight point = light;
    point.radius = 0.0f;
    double shaped = 0.0, pointed = 0.0;
    for (int k = 0; k < grid * grid; ++k) {
        shaped += max_channel(point_unshadowed(light, points[std::size_t(k)], normal));
        pointed += max_channel(point_unshadowed(point, points[std::size_t(k)], normal));
    }
    return pointed > 0.0 ? shaped / pointed : 1.0;
}

}  // namespace

Rgb point_unshadowed(const PointLight& light, const Vec3& x, const Vec3& normal) {
    const View v = view_of(light, x);
    if (!(v.distance > 0.0)) return Rgb(0.0);
    const double cos_theta = glm::dot(glm::dvec3(normal), v.axis);
    const double profile = spot_profile(light, Vec3(-v.axis));
    if (light.radius <= 0.0f)
        return cos_theta > 0.0 ? light.intensity * (profile * cos_theta / (v.distance * v.distance)) : Rgb(0.0);
    return light.intensity * (radiance_scale(light) * profile * detail::clipped_cone_cosine(cos_theta, v.sin2));
}

Rgb point_fluence(const PointLight& light, const Vec3& x) {
    const View v = view_of(light, x);
    if (!(v.distance > 0.0)) {  // at the centre: inside a sphere, or a disk's full half-space
        if (light.radius <= 0.0f) return Rgb(0.0);
        const double solid_angle = light.shape == LampShape::Sphere ? 4.0 * M_PI : 2.0 * M_PI;
        return light.intensity * (radiance_scale(light) * solid_angle);
    }
    const double profile = spot_profile(light, Vec3(-v.axis));
    if (light.radius <= 0.0f) return light.intensity * (profile / (v.distance * v.distance));
    // 1 - cos = sin^2 / (1 + cos), without the cancellation of 1 - cos for a far lamp.
    const double solid_angle = v.sin2 >= 1.0 ? 4.0 * M_PI : 2.0 * M_PI * v.sin2 / (1.0 + std::sqrt(1.0 - v.sin2));
    return light.intensity * (radiance_scale(light) * solid_angle * profile);
}

int point_rays(const PointLight& light, const Vec3& x) {
    if (light.radius <= 0.0f) return 1;
    const double sin_sigma = std::sqrt(std::min(1.0, view_of(light, x).sin2));
    const int grid = std::clamp(int(std::ceil(16.0 * sin_sigma)), 1, 8);
    return grid * grid;
}

Rgb point_irradiance(const PointLight& light, const hr::Visibility& visibility, const Vec3& x, const Vec3& normal,
                     int rays, uint32_t seed) {
    const View v = view_of(light, x);
    const Rgb unshadowed = point_unshadowed(light, x, normal);
    if (!(max_channel(unshadowed) > 0.0)) return Rgb(0.0);
    if (light.radius <= 0.0f) return visibility.clear_from_surface(x, normal, light.position) ? unshadowed : Rgb(0.0);
    const detail::Cone cone(v.axis, v.sin2 < 1.0 ? std::sqrt(1.0 - v.sin2) : -1.0);
    const glm::dvec3 n(normal);
    const int grid = std::max(1, int(std::lround(std::sqrt(double(rays)))));
    const double share = detail::lit_share(
        cone, n, grid, seed, [&](const glm::dvec3& u) { return double(spot_profile(light, Vec3(-u))); },
        [&](const glm::dvec3& u) {
            return visibility.clear_from_surface(x, normal, x + Vec3(u * distance_to_lamp(light, v, u)));
        });
    if (share >= 0.0)
        return light.intensity *
               (radiance_scale(light) * detail::clipped_cone_cosine(glm::dot(n, v.axis), v.sin2) * share);
    return visibility.clear_from_surface(x, normal, light.position) ? unshadowed
                                                                    : Rgb(0.0);  // the rays missed a sliver of cone
}

Rgb point_polygon_unshadowed(const PointLight& light, const Vec3* corners, int count, const Vec3& normal, double area) {
    const glm::dvec3 p(light.position);
    if (!(area > 0.0) || !(glm::dot(glm::dvec3(normal), p - glm::dvec3(corners[0])) > 0.0)) return Rgb(0.0);
    double solid_angle = 0.0;
    glm::dvec3 centre(0.0);
    for (int k = 0; k < count; ++k) centre += glm::dvec3(corners[k]) / double(count);
    for (int k = 1; k + 1 < count; ++k) {
        const glm::dvec3 a = glm::dvec3(corners[0]) - p, b = glm::dvec3(corners[k]) - p,
                         c = glm::dvec3(corners[k + 1]) - p;
        const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
        const double numerator = std::abs(glm::dot(a, glm::cross(b, c)));
        const double denominator = la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
        solid_angle += 2.0 * std::atan2(numerator, denominator);
    }
    const double profile = spot_profile(light, Vec3(glm::normalize(centre - p)));
    const double height = glm::dot(glm::dvec3(normal), p - glm::dvec3(corners[0]));
    return light.intensity *
           (profile * solid_angle / area * shape_over_point(light, corners, count, normal, area, height));
}

}  // namespace radiosity
