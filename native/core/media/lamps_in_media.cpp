/// @file lamps_in_media.cpp
/// @brief lamps_through_media(): the lamps' light on elements through the media, and on zones by
/// the midpoints of sub-cubes or, near a lamp, by stratified directions out of it.
#include "media/lamps_in_media.h"

#include "common/parallel_rows.h"
#include "common/stratified.h"
#include "visibility/shadow_ray.h"

#include <tbb/enumerable_thread_specific.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <unordered_map>

namespace radiosity {
namespace {

constexpr int kGrid = 3;                    // midpoints per zone edge seen from afar
constexpr int kFineGrid = 16;               // at most, per edge of a zone near a lamp with a radius
constexpr float kNearZone = 2.0f;           // a zone within this many of its edges of a lamp is near
constexpr float kShapedRadius = 0.25f;      // a lamp of this many zone edges is a shape to the zone
constexpr std::size_t kDirections = 32768;  // directions out of a lamp with near zones
constexpr float kInfinity = std::numeric_limits<float>::infinity();

/// What every pass reads: the elements (and their occluders), the zones and the media's walk.
struct ZoneScene {
    const Elements& elements;
    const Zones& zones;
    const MediumTracer& tracer;
    const hr::Visibility* visibility;  ///< the elements as occluders; null without elements

    bool clear(const Vec3& from, const Vec3& to) const { return !visibility || visibility->clear(from, to); }
    bool clear_towards(const Vec3& from, const Vec3& d) const {
        return !visibility || visibility->clear_towards(from, d);
    }
    float first_hit(const Vec3& from, const Vec3& d) const {
        if (!visibility) return kInfinity;
        const hr::Visibility::Hit hit = visibility->first_hit(from, d, 0.0f);
        return hit.patch >= 0 ? hit.distance : kInfinity;
    }
};

/// Direction i of n on the unit sphere, a spherical Fibonacci lattice (equal areas, well spread).
Vec3 fibonacci_direction(std::size_t i, std::size_t n) {
    constexpr double golden = 1.6180339887498948482;
    const double z = 1.0 - (2.0 * double(i) + 1.0) / double(n);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = 2.0 * M_PI * std::fmod(double(i) / golden, 1.0);
    return Vec3(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
}

/// Point i of the `grid`^3 midpoints of zone k's sub-cubes (the midpoint rule, exact for light
/// linear across the zone).
Vec3 zone_point(const Zones& zones, std::size_t k, int grid, int i) {
    const Vec3 cell(float(i % grid), float((i / grid) % grid), float(i / (grid * grid)));
    return zones.centre[k] + zones.edge[k] * ((cell + 0.5f) / float(grid) - 0.5f);
}

bool near_lamp(const Zones& zones, std::size_t k, const Vec3& lamp) {
    return glm::length(zones.centre[k] - lamp) < kNearZone * zones.edge[k];
}

/// Whether a lamp's radius, against zone k's edge, lets points take the zone's mean near it: its
/// light is bounded there (point_fluence) and varies over about its radius.
bool shaped_near(const PointLight& lamp, const Zones& zones, std::size_t k) {
    return lamp.radius >= kShapedRadius * zones.edge[k];
}

/// The grid a zone near a lamp with a radius takes: sub-cubes of about an eighth of the radius.
int shaped_grid(const PointLight& lamp, const Zones& zones, std::size_t k) {
    return std::clamp(int(std::ceil(8.0f * zones.edge[k] / lamp.radius)), kGrid, kFineGrid);
}

/// H_k of a point or spot lamp at the `grid`^3 midpoints of zone k: 1 / (4 pi) times the mean of
/// tau times the lamp's fluence there (point_fluence: I profile / d^2 for a point).
Rgb point_lamp_at_points(const ZoneScene& scene, const PointLight& lamp, std::size_t k, int grid,
                         std::vector<ZoneCredit>& credits) {
    glm::dvec3 sum(0.0);
    const int points = grid * grid * grid;
    for (int i = 0; i < points; ++i) {
        const Vec3 x = zone_point(scene.zones, k, grid, i);
        const Vec3 d = x - lamp.position;
        const float r = glm::length(d);
        if (!(r > 0.0f) || !scene.clear(lamp.position, x)) continue;
        const Channels tau = scene.tracer.trace(lamp.position, d / r, r, credits);
        sum += glm::dvec3(tau) * glm::dvec3(point_fluence(lamp, x));
    }
    return Rgb(sum / (4.0 * M_PI * points));
}

/// H_k of a point or spot lamp for the zones near it: the take-up form over stratified
/// directions, P_k = I * (4 pi / n) sum of profile * credit, H_k = P_k / (4 pi K_t V).
void point_lamp_on_near_zones(const ZoneScene& scene, const PointLight& lamp, const std::vector<int32_t>& near,
                              std::vector<Rgb>& incident) {
    std::unordered_map<int32_t, std::size_t> slot;
    for (std::size_t s = 0; s < near.size(); ++s) slot[near[s]] = s;
    tbb::enumerable_thread_specific<std::vector<glm::dvec3>> taken(std::vector<glm::dvec3>(near.size()));
    tbb::enumerable_thread_specific<std::vector<ZoneCredit>> credits;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, kDirections, 256), [&](const auto& range) {
        std::vector<glm::dvec3>& sum = taken.local();
        std::vector<ZoneCredit>& walk = credits.local();
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
            const Vec3 d = fibonacci_direction(i, kDirections);
            const float profile = spot_profile(lamp, d);
            if (!(profile > 0.0f)) continue;
            scene.tracer.trace(lamp.position, d, scene.first_hit(lamp.position, d), walk);
            for (const ZoneCredit& c : walk) {
                const auto s = slot.find(c.zone);
                if (s != slot.end()) sum[s->second] += double(profile) * glm::dvec3(c.fraction);
            }
        }
    });
    for (std::size_t s = 0; s < near.size(); ++s) {
        glm::dvec3 total(0.0);
        for (const std::vector<glm::dvec3>& sum : taken) total += sum[s];
        const std::size_t k = near[s];
        const Rgb K_t_V = scene.zones.extinction[k] * scene.zones.volume(k);
        for (int c = 0; c < 3; ++c)
            if (K_t_V[c] > 0.0) incident[k][c] += lamp.intensity[c] * total[c] / (double(kDirections) * K_t_V[c]);
    }
}

void point_lamp_on_zones(const ZoneScene& scene, const PointLight& lamp, std::vector<Rgb>& incident,
                         const ProgressFn& progress) {
    std::vector<int32_t> near;
    for (std::size_t k = 0; k < scene.zones.size(); ++k)
        if (near_lamp(scene.zones, k, lamp.position) && !shaped_near(lamp, scene.zones, k)) near.push_back(int32_t(k));
    if (!near.empty()) point_lamp_on_near_zones(scene, lamp, near, incident);
    tbb::enumerable_thread_specific<std::vector<ZoneCredit>> credits;
    detail::parallel_rows("lights", scene.zones.size(), 16, scene.elements.size(), progress, [&](std::size_t k) {
        if (!near_lamp(scene.zones, k, lamp.position))
            incident[k] += point_lamp_at_points(scene, lamp, k, kGrid, credits.local());
        else if (shaped_near(lamp, scene.zones, k))
            incident[k] += point_lamp_at_points(scene, lamp, k, shaped_grid(lamp, scene.zones, k), credits.local());
        return true;
    });
}

/// Direction i within the sun's cone about the direction towards it, uniform in solid angle
/// (two coordinates of Roberts' R3 sequence).
Vec3 towards_sun(const SunLight& sun, std::size_t i) {
    const glm::dvec3 axis = -glm::dvec3(sun.direction);
    if (!(sun.half_angle > 0.0f)) return Vec3(axis);
    glm::dvec3 t, b;
    detail::tangent_frame(axis, t, b);
    const Vec3 u = detail::r3_point(i);
    const double cos_theta = 1.0 - double(u.x) * (1.0 - std::cos(double(sun.half_angle)));
    const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta)), phi = 2.0 * M_PI * u.y;
    return Vec3(glm::normalize(sin_theta * (std::cos(phi) * t + std::sin(phi) * b) + cos_theta * axis));
}

void sun_on_zones(const ZoneScene& scene, const SunLight& sun, std::vector<Rgb>& incident, const ProgressFn& progress) {
    tbb::enumerable_thread_specific<std::vector<ZoneCredit>> credits;
    detail::parallel_rows("lights", scene.zones.size(), 16, scene.elements.size(), progress, [&](std::size_t k) {
        constexpr int points = kGrid * kGrid * kGrid;
        glm::dvec3 sum(0.0);
        for (int i = 0; i < points; ++i) {
            const Vec3 x = zone_point(scene.zones, k, kGrid, i);
            const Vec3 d = towards_sun(sun, k * points + std::size_t(i));
            if (scene.clear_towards(x, d)) sum += glm::dvec3(scene.tracer.trace(x, d, kInfinity, credits.local()));
        }
        incident[k] += sun.irradiance * (sum / (4.0 * M_PI * points));
        return true;
    });
}

/// One lamp's light on the elements times the transmittance from each element's centre to it
/// (`towards` gives the unit direction and distance from a point to the lamp).
template <typename Towards>
void one_lamp_on_elements(const ZoneScene& scene, const Lights& one, Towards towards, std::vector<Rgb>& irradiance,
                          const ProgressFn& progress) {
    const Elements& elements = scene.elements;
    const std::vector<Rgb> unattenuated = direct_irradiance(elements, one, *scene.visibility, progress);
    tbb::enumerable_thread_specific<std::vector<ZoneCredit>> credits;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, elements.size(), 64), [&](const auto& range) {
        for (std::size_t e = range.begin(); e != range.end(); ++e) {
            if (!(max_channel(unattenuated[e]) > 0.0)) continue;
            float distance = kInfinity;
            const Vec3 d = towards(elements.centre[e], distance);
            irradiance[e] +=
                unattenuated[e] * Rgb(scene.tracer.trace(elements.centre[e], d, distance, credits.local()));
        }
    });
}

/// Every lamp's light on the elements, each dimmed by the media to it.
void light_elements(const ZoneScene& scene, const Lights& lights, std::vector<Rgb>& irradiance,
                    const ProgressFn& progress) {
    for (const PointLight& lamp : lights.points) {
        Lights one;
        one.points.push_back(lamp);
        const auto towards = [&](const Vec3& x, float& distance) {
            distance = glm::length(lamp.position - x);
            return distance > 0.0f ? (lamp.position - x) / distance : Vec3(0.0f, 0.0f, 1.0f);
        };
        one_lamp_on_elements(scene, one, towards, irradiance, progress);
    }
    for (const SunLight& sun : lights.suns) {
        Lights one;
        one.suns.push_back(sun);
        one.resolution = lights.resolution;
        one_lamp_on_elements(
            scene, one, [&](const Vec3&, float&) { return -sun.direction; }, irradiance, progress);
    }
}

}  // namespace

LampsThroughMedia lamps_through_media(const Elements& elements, const Lights& lights, const Zones& zones,
                                      const MediumTracer& tracer, const ProgressFn& progress) {
    LampsThroughMedia out;
    out.element_irradiance.assign(elements.size(), Rgb(0.0));
    out.zone_incident.assign(zones.size(), Rgb(0.0));
    if (lights.empty()) return out;
    std::optional<hr::Visibility> occluders;  // one for the elements' light and the zones'
    if (elements.size() > 0)
        occluders.emplace(elements.vertices, detail::blocking_corners(elements), scene_diagonal(elements.vertices));
    const ZoneScene scene{elements, zones, tracer, occluders ? &*occluders : nullptr};
    if (occluders) light_elements(scene, lights, out.element_irradiance, progress);
    if (zones.size() == 0) return out;
    for (const PointLight& lamp : lights.points) point_lamp_on_zones(scene, lamp, out.zone_incident, progress);
    for (const SunLight& sun : lights.suns) sun_on_zones(scene, sun, out.zone_incident, progress);
    return out;
}

}  // namespace radiosity
