/// @file lamp_bubbles.cpp
/// @brief The lamps' light an element's corner blend misses, as a bubble (lamp_bubbles.h).
#include "output/lamp_bubbles.h"

#include "common/parallel_rows.h"
#include "output/corner_blend.h"
#include "transport/cone.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

namespace radiosity::detail {
namespace {

/// Below this share of the lamp's mean over an element, the blend's error is left alone.
constexpr double kNegligible = 2e-3;

/// A spot whose profile at a corner differs from the centre's by more than this share is left out.
constexpr double kProfileChange = 1e-2;

/// The seed of the shadow rays at an element's corners, and the name of their kept values' point.
constexpr uint32_t kSeed = 0xB0BB1EU;

/// Element e's corners and where the field's point of each lies: a hair towards the centre, as
/// the gather takes its element vertices (final_gather.h).
struct ElementCorners {
    std::array<Vec3, 4> at{};
    std::array<Vec3, 4> point{};
    int count = 0;
};

/// The lamps' light with shadows at an element's corner points, each lamp's read from what an
/// earlier bake kept under its signature where it is there, else traced (and kept by finish()).
class CornerShadows {
public:
    CornerShadows(KeptDirectLight* kept, const SourceSignatures& signatures, const ElementCorners& corners,
                  const Vec3& normal)
        : kept_(kept), signatures_(signatures), corners_(corners), normal_(normal) {}
    CornerShadows(const CornerShadows&) = delete;
    CornerShadows& operator=(const CornerShadows&) = delete;
    ~CornerShadows() {
        for (auto& point : points_)
            if (point) point->finish();
    }

    /// Lamp `l`'s irradiance with shadows at corner k.
    Rgb light(const hr::Visibility& visibility, const PointLight& lamp, std::size_t l, int k) {
        const Vec3 x = corners_.point[std::size_t(k)];
        std::optional<KeptDirectLight::Point>& point = points_[std::size_t(k)];
        if (!point) point.emplace(kept_, x, normal_, kSeed);
        return point->light(signatures_.lamps[l][1], [&] {
            return point_irradiance(lamp, visibility, x, normal_, point_rays(lamp, x), position_seed(x, kSeed));
        });
    }

private:
    KeptDirectLight* kept_;
    const SourceSignatures& signatures_;
    const ElementCorners& corners_;
    Vec3 normal_;
    std::array<std::optional<KeptDirectLight::Point>, 4> points_;
};

ElementCorners corners_of(const Elements& elements, std::size_t e) {
    ElementCorners c;
    c.count = elements.corner_count(e);
    for (int k = 0; k < c.count; ++k) {
        c.at[k] = elements.vertices[std::size_t(elements.corners[e][k])];
        c.point[k] = c.at[k] + 1e-3f * (elements.centre[e] - c.at[k]);
    }
    return c;
}

/// Whether the lamp's profile is the same over the element (point lamps always).
bool even_profile(const PointLight& lamp, const ElementCorners& c, const Vec3& centre) {
    if (!(lamp.cos_half_angle > -1.0f)) return true;
    const double middle = spot_profile(lamp, glm::normalize(centre - lamp.position));
    for (int k = 0; k < c.count; ++k) {
        const double profile = spot_profile(lamp, glm::normalize(c.at[k] - lamp.position));
        if (std::abs(profile - middle) > kProfileChange * std::max(middle, 1e-12)) return false;
    }
    return middle > 0.0;
}

/// One lamp's part of element e's bubble amplitude (irradiance): the exact unshadowed mean less
/// the blend's, times the corners' unhidden share, over the bubble's mean; bounded below so that
/// the lamp's light at the element's centre stays at least 0.
Rgb lamp_part(const PointLight& lamp, std::size_t l, const Elements& elements, std::size_t e, const ElementCorners& c,
              const ElementMeans& means, const hr::Visibility& visibility, CornerShadows& shadows) {
    const Vec3 normal = elements.normal[e];
    if (!(glm::dot(normal, lamp.position - elements.centre[e]) > 0.0f)) return Rgb(0.0);
    if (!even_profile(lamp, c, elements.centre[e])) return Rgb(0.0);
    const Rgb exact = point_polygon_unshadowed(lamp, c.at.data(), c.count, normal, double(elements.area[e]));
    std::array<Rgb, 4> at{};
    Rgb blended(0.0), centre(0.0);
    for (int k = 0; k < c.count; ++k) {
        at[k] = point_unshadowed(lamp, c.point[k], normal);
        blended += means.corner[k] * at[k];
        centre += at[k] / double(c.count);
    }
    const double scale = std::max(max_channel(exact), max_channel(blended));
    if (!(scale > 0.0) || max_channel(glm::abs(exact - blended)) < kNegligible * scale) return Rgb(0.0);
    double seen = 0.0, open = 0.0;
    for (int k = 0; k < c.count; ++k) {
        const double unshadowed = max_channel(at[k]);
        if (!(unshadowed > 0.0)) continue;
        seen += max_channel(shadows.light(visibility, lamp, l, k));
        open += unshadowed;
    }
    const double unhidden = open > 0.0 ? std::clamp(seen / open, 0.0, 1.0) : 0.0;
    return glm::max(unhidden * (exact - blended) / means.bubble, -unhidden * centre);
}

}  // namespace

ElementMeans element_means(const Elements& elements, std::size_t e) {
    ElementMeans means;
    if (elements.is_triangle(e)) {
        means.bubble = 27.0 / 60.0;  // the integral of l0 l1 l2 over a triangle is its area / 60
        for (int k = 0; k < 3; ++k) means.corner[k] = 1.0 / 3.0;
        return means;
    }
    // Two Gauss points per direction: the area element of a planar quad is bilinear in (u, v),
    // so this is exact for the corner weights (bilinear) and the bubble (quadratic) times it.
    std::array<glm::dvec3, 4> p;
    for (int k = 0; k < 4; ++k) p[k] = glm::dvec3(elements.vertices[std::size_t(elements.corners[e][k])]);
    const double g = 0.5 / std::sqrt(3.0);
    double area = 0.0;
    for (const double u : {0.5 - g, 0.5 + g})
        for (const double v : {0.5 - g, 0.5 + g}) {
            const glm::dvec3 du = (1.0 - v) * (p[1] - p[0]) + v * (p[2] - p[3]);
            const glm::dvec3 dv = (1.0 - u) * (p[3] - p[0]) + u * (p[2] - p[1]);
            const double jacobian = glm::length(glm::cross(du, dv));
            const std::array<double, 4> w = corner_weights(elements, e, float(u), float(v));
            for (int k = 0; k < 4; ++k) means.corner[k] += jacobian * w[std::size_t(k)];
            means.bubble += jacobian * 16.0 * u * (1.0 - u) * v * (1.0 - v);
            area += jacobian;
        }
    if (!(area > 0.0)) return ElementMeans{4.0 / 9.0, {0.25, 0.25, 0.25, 0.25}};
    for (double& weight : means.corner) weight /= area;
    means.bubble /= area;
    return means;
}

std::vector<Rgb> lamp_bubbles(const Elements& elements, const Lights& lights, const hr::Visibility& visibility,
                              const std::vector<std::size_t>& skip, KeptDirectLight* kept,
                              const SourceSignatures& signatures, const ProgressFn& progress) {
    std::vector<Rgb> bubbles(elements.size(), Rgb(0.0));
    if (lights.points.empty()) return bubbles;
    std::vector<uint8_t> skipped(elements.size(), 0);
    for (const std::size_t e : skip) skipped[e] = 1;
    parallel_rows("gather lamp bubbles", elements.size(), 64, 0, progress, [&](std::size_t e) {
        if (skipped[e] || elements.is_back(e) || !(max_channel(elements.reflectance[e]) > 0.0f)) return true;
        const ElementCorners c = corners_of(elements, e);
        const ElementMeans means = element_means(elements, e);
        CornerShadows shadows(kept, signatures, c, elements.normal[e]);
        Rgb irradiance(0.0);
        for (std::size_t l = 0; l < lights.points.size(); ++l)
            irradiance += lamp_part(lights.points[l], l, elements, e, c, means, visibility, shadows);
        bubbles[e] = Rgb(elements.reflectance[e]) * irradiance / M_PI;
        return true;
    });
    return bubbles;
}

void append_bubbles(const Elements& elements, const std::vector<Rgb>& bubbles, std::vector<Rgb>& field) {
    field.resize(4 * elements.size());
    field.insert(field.end(), bubbles.begin(), bubbles.end());
}

}  // namespace radiosity::detail
