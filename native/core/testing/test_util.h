/// @file test_util.h
/// @brief Small scenes for the tests, built as the add-on would build them: flat arrays.
#pragma once

#include "bake/bake.h"
#include "geometry/scene.h"

#include <vector>

namespace radiosity::test {

/// A polygon soup that owns its arrays and hands out a SceneInput view of them.
struct SceneArrays {
    std::vector<float> positions;
    std::vector<int32_t> face_offsets{0};
    std::vector<int32_t> corner_vertices;
    std::vector<float> reflectance;
    std::vector<float> emission;
    std::vector<int32_t> material;

    /// Adds a polygon with its own vertices (CCW seen from where its normal points).
    int32_t add_polygon(const std::vector<Vec3>& corners, const Rgb& rho, const Rgb& emitted, int32_t material_id = 0);
    int32_t add_quad(Vec3 a, Vec3 b, Vec3 c, Vec3 d, const Rgb& rho, const Rgb& emitted = Rgb(0),
                     int32_t material_id = 0);
    SceneInput input() const;
    /// Adds the parallelogram origin + [0, 1] u + [0, 1] v as cells x cells quads, each with its own
    /// vertices (as separate faces of a subdivided mesh), normal along u x v.
    void add_grid(const Vec3& origin, const Vec3& u, const Vec3& v, int cells, const Rgb& rho,
                  const Rgb& emitted = Rgb(0), int32_t material_id = 0);
};

/// Two unit squares facing each other, `distance` apart along z: the emitter (index 0) at z = distance
/// facing down, the receiver (index 1) at z = 0 facing up, both over [0,1]^2.
SceneArrays opposed_unit_squares(float distance, const Rgb& rho = Rgb(0.5), const Rgb& emitted = Rgb(1.0));

/// Two unit squares meeting at a right angle along a common edge: index 0 lies in z = 0 facing +z,
/// index 1 lies in x = 0 facing +x, sharing the edge x = z = 0, y in [0,1].
SceneArrays perpendicular_unit_squares(const Rgb& rho = Rgb(0.5), const Rgb& emitted = Rgb(0.0));

/// A closed axis-aligned box [0,size]^3 seen from inside, one quad per side, uniform rho and emission.
SceneArrays closed_box(const Vec3& size, const Rgb& rho, const Rgb& emitted);

/// The Cornell box as a closed 1 m cube (front wall closed too, so no light escapes):
/// red left wall, green right wall, white elsewhere, a square ceiling light and two blocks.
SceneArrays cornell_box();

/// The radiance of the elements that are not an emitting polygon's back side (Elements::side), in
/// order: what the fronts of a closed box's emitting walls show inside. Their back sides face out
/// and see nothing (their L is their E).
std::vector<Rgb> fronts(const Elements& e, const std::vector<Rgb>& radiance);

/// How many elements are not an emitting polygon's back side.
std::size_t front_count(const Elements& e);

/// The worst element's error against its exact direct light from emitter polygon 0 (radiance 1,
/// green channel, one element facing the receivers): elements 1.. up to the emitter's back side
/// take rho * area_flux(e, i, 0) / A_i. As a share of the largest exact value.
double worst_direct_light_error(const BakeResult& r, double rho);

/// The largest |value / expected - 1| over `values` and their channels: how far the worst of them
/// is from a uniform exact answer (a furnace's E / (1 - rho)).
double worst_relative_error(const std::vector<Rgb>& values, const Rgb& expected);

}  // namespace radiosity::test
