/// @file world_light.h
/// @brief The world's irradiance at a point, by multiple importance sampling of an
/// equirectangular map and the cosine (internal; world.h).
#pragma once

#include "transport/world.h"
#include "visibility/ray_tracer.h"

#include <glm/vec2.hpp>

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
    /// `normal`, from given points of the unit square: `cos_count` of `cos_uv` mapped to
    /// cosine-weighted directions and `map_count` of `map_uv` to directions drawn from the map
    /// (ignored for a uniform map), weighted by the balance heuristic for those counts; counting
    /// the rays along which nothing hides the sky. Thread-safe.
    Rgb irradiance(const hr::Visibility& visibility, const Vec3& origin, const Vec3& normal, const glm::dvec2* cos_uv,
                   int cos_count, const glm::dvec2* map_uv, int map_count) const;
    /// The same at an output point with at most WorldLight::point_samples rays, spent where what
    /// the point sees of the sky has its edges (world_point.cpp). Deterministic in `seed`.
    Rgb irradiance(const hr::Visibility& visibility, const Vec3& origin, const Vec3& normal, uint32_t seed) const;

    /// Samples per strategy for WorldLight::samples: grid x grid each (0 map samples for a uniform map).
    int cos_grid() const { return cos_grid_; }
    int map_grid() const { return map_grid_; }

private:
    /// A direction drawn from the map for the point (a, b) of the unit square.
    glm::dvec3 map_direction(double a, double b) const;
    /// The map strategy's density per steradian along unit `direction`.
    double map_pdf(const glm::dvec3& direction) const;
    /// Adds one sample's contribution to `sum`: unit direction `w` at `cosine` to the normal, where
    /// the cosine strategy's samples have the density cos_density cos / pi per steradian (their
    /// count, for samples spread evenly over the unit square) and the map's `map_count` samples
    /// map_count pdf_map.
    void add(const hr::Visibility& visibility, const Vec3& origin, const glm::dvec3& w, double cosine,
             double cos_density, int map_count, Rgb& sum) const;

    const WorldLight& world_;
    bool empty_ = true;
    int cos_grid_ = 0, map_grid_ = 0;
    int point_cos_rays_ = 0, point_map_grid_ = 0;  ///< an output point's rays: the cosine's, the map's grid
    std::vector<double> row_cdf_;                  ///< height entries, the last 1
    std::vector<double> pixel_cdf_;                ///< width entries per row, each row's last 1
    std::vector<double> pixel_pdf_;                ///< probability of each pixel
};

/// `points` x `grid` x `grid` points of the unit square, `grid` x `grid` for each of `points`
/// sample points (a square number) of an element, padded across them: each point has one in each
/// cell of the grid x grid coarse grid, and in each coarse cell the points take the cells of its
/// sqrt(points) x sqrt(points) sub-grid each once (a random permutation per coarse cell), so that
/// all of them together have one in each cell of the fine grid (the padding of multi-jittered
/// sampling, Chiu, Shirley & Wang 1994). Point k's are [k grid^2, (k + 1) grid^2). Advances `seed`.
std::vector<glm::dvec2> padded_samples(int points, int grid, uint32_t& seed);

/// `grid` x `grid` points of the unit square, one in each cell and, across all of them, one in each
/// of the grid^2 columns and of the grid^2 rows (multi-jittered sampling, Chiu, Shirley & Wang
/// 1994; its shuffles drawn from `seed`, so each point is uniform over its cell). A map's rows are
/// drawn by the first coordinate: a sun a few rows tall gets its share of the points to one point.
std::vector<glm::dvec2> multi_jittered_samples(int grid, uint32_t& seed);

/// The world's first reflection, rho E / pi, at each corner of `mesh` (4 slots per element, the
/// 4th of a triangle zero), a hair inside the element: computed once per vertex and polygon (the
/// faces of one polygon around a vertex share it), with WorldLight::point_samples rays seeded by
/// the vertex. Zero for elements that reflect nothing. Progress phase "output"; throws Cancelled.
std::vector<Rgb> world_light_at_corners(const Elements& mesh, const WorldLight& world, const hr::Visibility& visibility,
                                        float scene_size, const ProgressFn& progress);

}  // namespace radiosity::detail
