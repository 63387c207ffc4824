/// @file world.h
/// @brief The world's light: radiance arriving from every direction that escapes the scene, as
/// Blender's World gives it to Cycles, held as an equirectangular map.
///
/// Each element (and, with the final gather, each output point) receives the world's irradiance
/// E = integral over the directions its rays escape the scene of L_world(w) cos(theta) dw, and
/// reflects rho E / pi, which joins its emitted radiance as the lamps' first reflection does
/// (lights.h). The integral is estimated by stratified rays traced with Embree (at output points,
/// spent where the sky's edges are), drawn by two strategies combined with the balance heuristic (multiple importance
/// sampling, Veach & Guibas 1995): cosine-weighted directions, and directions drawn in proportion to the map's power (a
/// luminance CDF over its pixels), so a small bright sun disc is found by a few rays.
#pragma once

#include "geometry/scene.h"

#include <vector>

namespace radiosity {

/// An equirectangular map in Cycles' convention (direction_to_equirectangular): pixel (i, j), rows
/// counted from the bottom as Blender stores images, covers u in [i, i + 1) / width and v in
/// [j, j + 1) / height; (u, v) looks along phi = pi - 2 pi u (the azimuth from +x towards +y) and
/// theta = pi (1 - v) (from +z, up): (sin theta cos phi, sin theta sin phi, cos theta). So u = 0.5
/// looks along +x, u = 0.25 along +y, the top row up. Radiance is constant over a pixel.
struct WorldLight {
    int width = 0, height = 0;
    std::vector<Rgb> radiance;  ///< width * height, bottom row first; radiance per RGB channel
    /// Rays per element in the solve (rounded up to square grids; half of them drawn from the
    /// map unless it is uniform), from a grid of points over the element, padded so that together
    /// they stratify the directions as finely as one point with all of them would.
    int samples = 1024;
    /// Rays per output point in the final gather, at most, where the world's light is seen
    /// directly (half of them drawn from the map unless it is uniform): of the cosine's, a third
    /// find where what the point sees of the sky has edges, a third go one to each cell of its
    /// stratified square, and the rest to the cells on those edges (world_point.cpp). On a 2 m room lit
    /// through a 0.8 m window by a uniform sky (blender_tests/test_world.py), against Cycles'
    /// bake of the same room lit by an area lamp filling the window, whose own bake has 0.34%:
    /// 0.42% RMS at 1024 and 16384 (element and point rays), 0.53% at 1024 and 8192; by plain
    /// stratified rays, 0.91% at 1024 and 8192 (lab/world_window/measure.py).
    int point_samples = 16384;

    /// A map of one pixel: the same radiance from every direction (a plain Background colour).
    static WorldLight uniform(const Rgb& radiance, int samples = 256);
    /// True without a map or when it is black everywhere: no world light.
    bool empty() const;
    /// The radiance arriving from the world along -direction (unit `direction` points at the sky).
    Rgb radiance_from(const Vec3& direction) const;
    /// InputError unless the size matches the pixels, every value is finite and >= 0, samples and
    /// point_samples >= 1.
    void check() const;
};

/// The world's irradiance per element, the mean over it (front sides; both sides of every element
/// occlude): `world.samples` rays from stratified points of the element. Seeded per element, so
/// the result does not depend on threads. Progress phase "world", one unit per element; throws
/// Cancelled. Zero for elements that reflect nothing.
std::vector<Rgb> world_irradiance(const Elements& elements, const WorldLight& world, const ProgressFn& progress = {});

/// The world's irradiance at points on `surfaces`, each facing its unit normal
/// (`world.point_samples` rays from each point, seeded by its index).
std::vector<Rgb> world_irradiance_at(const Elements& surfaces, const WorldLight& world, const std::vector<Vec3>& points,
                                     const std::vector<Vec3>& normals);

}  // namespace radiosity
