/// @file world_light.h
/// @brief The world's irradiance at a point, by multiple importance sampling of an
/// equirectangular map and the cosine (internal; world.h).
#pragma once

#include "transport/world.h"
#include "visibility/ray_tracer.h"

#include <vector>

namespace radiosity::detail {

/// Draws directions from a WorldLight in proportion to its power (a CDF over rows, then over the
/// pixels of the chosen row, weighted by luminance times the pixel's solid angle) and estimates
/// irradiance with cosine-weighted directions beside them (balance heuristic, Veach & Guibas 1995):
/// a sample w from either strategy counts L(w) cos / (n_cos pdf_cos(w) + n_map pdf_map(w)).
/// A uniform map is sampled by the cosine alone, which makes an unoccluded plane exact.
class WorldSampler {
public:
    explicit WorldSampler(const WorldLight& world);

    bool empty() const { return empty_; }

    /// Irradiance from the world at `origin` (a point lifted off its surface) facing unit
    /// `normal`: cos_grid^2 cosine-weighted and map_grid^2 map samples (stratified), counting those
    /// along which nothing hides the sky. Deterministic in `seed`. Thread-safe.
    Rgb irradiance(const hr::Visibility& visibility, const Vec3& origin, const Vec3& normal, uint32_t seed,
                   int cos_grid, int map_grid) const;
    /// The same with the grids WorldLight::point_samples asks for.
    Rgb irradiance(const hr::Visibility& visibility, const Vec3& origin, const Vec3& normal, uint32_t seed) const {
        return irradiance(visibility, origin, normal, seed, point_cos_grid_, point_map_grid_);
    }

    /// Samples per strategy for WorldLight::samples: grid x grid each (0 map samples for a uniform map).
    int cos_grid() const { return cos_grid_; }
    int map_grid() const { return map_grid_; }

private:
    /// A direction drawn from the map for the point (a, b) of the unit square.
    glm::dvec3 map_direction(double a, double b) const;
    /// The map strategy's density per steradian along unit `direction`.
    double map_pdf(const glm::dvec3& direction) const;
    /// Adds one sample's contribution (unit direction `w` at `cosine` to the normal; `cos_count`
    /// and `map_count` samples of each strategy) to `sum`.
    void add(const hr::Visibility& visibility, const Vec3& origin, const glm::dvec3& w, double cosine, int cos_count,
             int map_count, Rgb& sum) const;

    const WorldLight& world_;
    bool empty_ = true;
    int cos_grid_ = 0, map_grid_ = 0, point_cos_grid_ = 0, point_map_grid_ = 0;
    std::vector<double> row_cdf_;    ///< height entries, the last 1
    std::vector<double> pixel_cdf_;  ///< width entries per row, each row's last 1
    std::vector<double> pixel_pdf_;  ///< probability of each pixel
};

/// The world's first reflection, rho E / pi, at each corner of `mesh` (4 slots per element, the
/// 4th of a triangle zero), a hair inside the element: computed once per vertex and polygon (the
/// faces of one polygon around a vertex share it), with WorldLight::point_samples rays seeded by
/// the vertex. Zero for elements that reflect nothing. Progress phase "output"; throws Cancelled.
std::vector<Rgb> world_light_at_corners(const Elements& mesh, const WorldLight& world, const hr::Visibility& visibility,
                                        float scene_size, const ProgressFn& progress);

}  // namespace radiosity::detail
