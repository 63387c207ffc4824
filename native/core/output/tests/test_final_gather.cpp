/// @file test_final_gather.cpp
/// @brief The uniform bake's final gather at the output corners (bake.h FinalGatherSettings):
/// exact direct light from an emitter and from a point lamp where interpolation is far off, floor
/// corners at a block's corner lit from the side Cycles bakes them from, the exact light on both
/// sides of a contact line, the field gathered at the elements' vertices under a coarse solution,
/// the light turning around a fin's foot, corners inside a wall or on another face black as in Cycles,
/// how far an element's corners beside a lamp were from its exact light (what the estimate reads),
/// the furnace at every corner (seams of a closed box), determinism, and cancelling.
#include "bake/bake.h"
#include "output/coincident_faces.h"
#include "output/corner_approach.h"

#include "testing/test_util.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace radiosity {
namespace {

BakeSettings gather_settings(float element_size, bool gather) {
    BakeSettings s;
    s.element_size = element_size;
    s.resolution = 128;
    s.solve.tolerance = 1e-8;
    s.final_gather.enabled = gather;
    return s;
}

/// Four 5 m floor quads (normal +z) meeting at the origin; their corners there are input corners.
void add_floor(test::SceneArrays& s, const Rgb& rho) {
    s.add_quad({0, 0, 0}, {5, 0, 0}, {5, 5, 0}, {0, 5, 0}, rho);
    s.add_quad({-5, 0, 0}, {0, 0, 0}, {0, 5, 0}, {-5, 5, 0}, rho);
    s.add_quad({-5, -5, 0}, {0, -5, 0}, {0, 0, 0}, {-5, 0, 0}, rho);
    s.add_quad({0, -5, 0}, {5, -5, 0}, {5, 0, 0}, {0, 0, 0}, rho);
}

/// The input corners at point p.
std::vector<std::size_t> corners_at(const test::SceneArrays& s, const Vec3& p) {
    std::vector<std::size_t> found;
    for (std::size_t c = 0; c < s.corner_vertices.size(); ++c) {
        const float* q = &s.positions[3 * s.corner_vertices[c]];
        if (q[0] == p.x && q[1] == p.y && q[2] == p.z) found.push_back(c);
    }
    return found;
}

/// A unit square of radiance Le (reflecting nothing) at height h over the origin, facing down.
void add_emitter(test::SceneArrays& s, double h, const Rgb& Le) {
    const float z = float(h);
    s.add_quad({-0.5f, -0.5f, z}, {-0.5f, 0.5f, z}, {0.5f, 0.5f, z}, {0.5f, -0.5f, z}, Rgb(0.0), Le, 1);
}

/// `settings` with a point lamp of intensity I at `position` added.
BakeSettings with_lamp(BakeSettings settings, const Vec3& position, const Rgb& I) {
    PointLight lamp;
    lamp.position = position;
    lamp.intensity = I;
    settings.lights.points.push_back(lamp);
    return settings;
}

/// The Medium preset's gather at `element_size`: 3,136 rays a corner, the field gathered at the
/// vertices with 64, 256 shadow rays, the indirect light shared at accuracy 0.15.
BakeSettings medium_gather_settings(float element_size) {
    BakeSettings settings = gather_settings(element_size, true);
    settings.final_gather.rays = 3136;
    settings.final_gather.field_rays = 64;
    settings.final_gather.shadow_rays = 256;
    settings.final_gather.cache_accuracy = 0.15;
    return settings;
}

/// Bakes `s` at 0.5 m elements under a point lamp of intensity I at height h over the origin.
BakeResult bake_under_lamp(const test::SceneArrays& s, const Rgb& I, double h, bool gather) {
    return bake(s.input(), with_lamp(gather_settings(0.5f, gather), Vec3(0.0f, 0.0f, float(h)), I));
}

/// Largest |L / expected - 1| over the channels of the input corners `corners`.
double worst_relative_error(const BakeResult& r, const std::vector<std::size_t>& corners, const Rgb& expected) {
    double worst = 0.0;
    for (const std::size_t c : corners)
        for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(r.colors.input_corner[c][k] / expected[k] - 1.0));
    return worst;
}

/// Howell's factor from a point to a parallel a x b rectangle at distance c, the point under one
/// of its corners.
double corner_factor(double a, double b, double c) {
    const double X = a / c, Y = b / c;
    return (X / std::sqrt(1 + X * X) * std::atan(Y / std::sqrt(1 + X * X)) +
            Y / std::sqrt(1 + Y * Y) * std::atan(X / std::sqrt(1 + Y * Y))) /
           (2 * M_PI);
}

/// Lambert's contour integral: the factor from a point at the origin with normal n to the polygon
/// `corners` (relative to the point, counter-clockwise seen from the point's side).
double lambert_factor(const std::vector<glm::dvec3>& corners, const glm::dvec3& n) {
    double sum = 0.0;
    for (std::size_t i = 0; i < corners.size(); ++i) {
        const glm::dvec3 a = glm::normalize(corners[i]), b = glm::normalize(corners[(i + 1) % corners.size()]);
        sum += std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0)) * glm::dot(glm::normalize(glm::cross(a, b)), n);
    }
    return std::abs(sum) / (2.0 * M_PI);
}

/// Adds the five faces (no bottom, outward normals) of the box [lo, hi].
void add_block(test::SceneArrays& s, const Vec3& lo, const Vec3& hi, const Rgb& rho) {
    const float x0 = lo.x, y0 = lo.y, z0 = lo.z, x1 = hi.x, y1 = hi.y, z1 = hi.z;
    s.add_quad({x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}, rho);  // +z
    s.add_quad({x0, y0, z0}, {x1, y0, z0}, {x1, y0, z1}, {x0, y0, z1}, rho);  // -y
    s.add_quad({x1, y1, z0}, {x0, y1, z0}, {x0, y1, z1}, {x1, y1, z1}, rho);  // +y
    s.add_quad({x0, y1, z0}, {x0, y0, z0}, {x0, y0, z1}, {x0, y1, z1}, rho);  // -x
    s.add_quad({x1, y0, z0}, {x1, y1, z0}, {x1, y1, z1}, {x1, y0, z1}, rho);  // +x
}

/// The light (irradiance / pi) from a point lamp of intensity I at `lamp`, unshadowed, where Cycles
/// bakes input corner `corner` of the triangles `s` holds (3 corners each): a hair from its vertex
/// towards the triangle's centroid (detail::bake_offset for a scene of size `scene_size`).
double lamp_light_where_baked(const test::SceneArrays& s, std::size_t corner, const Vec3& lamp, double I,
                              float scene_size = 1.0f) {
    Vec3 triangle[3], centroid(0.0f);
    for (std::size_t j = 0; j < 3; ++j) {
        const float* p = &s.positions[3 * s.corner_vertices[corner - corner % 3 + j]];
        triangle[j] = Vec3(p[0], p[1], p[2]);
        centroid += triangle[j] / 3.0f;
    }
    const Vec3& vertex = triangle[corner % 3];
    const Vec3 x = vertex + detail::bake_offset(vertex, scene_size) * glm::normalize(centroid - vertex);
    const glm::dvec3 n =
        glm::normalize(glm::cross(glm::dvec3(triangle[1] - triangle[0]), glm::dvec3(triangle[2] - triangle[0])));
    const glm::dvec3 to_lamp = glm::dvec3(lamp - x);
    return I * glm::dot(n, to_lamp) / std::pow(glm::length(to_lamp), 3.0) / M_PI;
}

TEST(FinalGather, FloorCornersAtABlocksFootSeeWhatCyclesSeesThere) {
    // A black block on the quadrant x < 0 < y stands on a floor of three quads around the origin,
    // under a unit square emitter over the origin. The light is discontinuous at the block's foot
    // corner: a floor corner there is lit by what it sees from the side Cycles bakes it from, a
    // hair from the vertex towards the centroid of the corner's first fan triangle. Seen from that
    // close, the block hides the emitter's points in a wedge of directions: from the +y axis to the
    // apex's direction for the quad beside its +x face, from the apex's direction to the -x axis
    // beside its -y face, the quadrant behind it from the diagonal quad. L = rho Le F, F Lambert's
    // factor of the rest of the square (nothing else lights the floor: the block and the emitter
    // reflect nothing, and the floor does not see itself).
    const double h = 0.5;
    const Rgb rho(0.5, 0.6, 0.7), Le(1.0, 2.0, 0.5), black(0.0);
    test::SceneArrays s;
    s.add_quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, rho);      // beside +x: the origin is corner 0
    s.add_quad({0, -1, 0}, {1, -1, 0}, {1, 0, 0}, {0, 0, 0}, rho);    // diagonal: corner 3
    s.add_quad({-1, -1, 0}, {0, -1, 0}, {0, 0, 0}, {-1, 0, 0}, rho);  // beside -y: corner 2
    add_block(s, Vec3(-1.0f, 0.0f, 0.0f), Vec3(0.0f, 1.0f, 0.4f), black);
    add_emitter(s, h, Le);
    // The visible part of the square at height h: from the direction where the wedge ends, round
    // through the open side to where it starts (counter-clockwise seen from below: the point's side).
    auto visible = [&](double from_degrees, double to_degrees) {  // wedge [from, to], counter-clockwise
        std::vector<glm::dvec3> polygon{{0.0, 0.0, h}};
        auto to_edge = [&](double degrees) {  // where the ray from the centre at this azimuth meets the square
            const glm::dvec2 d(std::cos(degrees * M_PI / 180.0), std::sin(degrees * M_PI / 180.0));
            return glm::dvec3(0.5 * d / std::max(std::abs(d.x), std::abs(d.y)), h);
        };
        polygon.push_back(to_edge(to_degrees));
        for (const double corner : {45.0, 135.0, 225.0, 315.0, 405.0, 495.0, 585.0})
            if (corner > to_degrees && corner < from_degrees + 360.0) polygon.push_back(to_edge(corner));
        polygon.push_back(to_edge(from_degrees + 360.0));
        return lambert_factor(polygon, glm::dvec3(0.0, 0.0, 1.0));
    };
    const double beside_x = visible(90.0, 180.0 + std::atan(0.5) * 180.0 / M_PI);  // approached along (2, 1)
    const double diagonal = visible(90.0, 180.0);
    const double beside_y = visible(180.0 + std::atan(2.0) * 180.0 / M_PI - 180.0, 180.0);  // along (-1, -2)
    BakeSettings settings = gather_settings(0.125f, true);
    settings.final_gather.shadow_rays = 4096;
    const BakeResult r = bake(s.input(), settings);
    const std::size_t corner[3] = {0, 7, 10};  // the quads' corners at the origin
    const double factor[3] = {beside_x, diagonal, beside_y};
    for (int q = 0; q < 3; ++q) {
        const Rgb expected = rho * Le * factor[q];
        const double error = worst_relative_error(r, {corner[q]}, expected);
        std::printf("floor quad %d at the block's corner: %.6f (exact %.6f), relative error %.2e\n", q,
                    r.colors.input_corner[corner[q]].g, expected.g, error);
        EXPECT_LT(error, 5e-3) << q;
    }
}

TEST(FinalGather, ContactLineBetweenAnEmittingFloorAndAWallIsExact) {
    // A 20 m floor (y > 0) that emits Le and reflects rho_f, and a 20 m wall on its edge (the
    // plane y = 0, facing +y) reflecting rho_w; nothing else. At the foot each sees the other's
    // light at the foot in half its hemisphere (every ray towards it meets it there), so
    //   wall:  L_w = rho_w (Le F + L_f,reflected / 2),  floor: L_f,reflected = rho_f L_w / 2,
    // F the exact factor from the wall's foot to the floor: L_w = rho_w Le F / (1 - rho_w rho_f / 4).
    // The gather's seam vertices read each other: their light is solved, not passed a few times.
    const Rgb rho_f(0.9, 0.8, 0.7), rho_w(0.95, 0.9, 0.6), Le(1.0, 2.0, 0.5);
    test::SceneArrays s;
    const float a = 10.0f, b = 20.0f;
    for (const float x0 : {-a, 0.0f}) {
        s.add_quad({x0, 0, 0}, {x0 + a, 0, 0}, {x0 + a, b, 0}, {x0, b, 0}, rho_f, Le);  // floor, +z
        s.add_quad({x0, 0, 0}, {x0, 0, b}, {x0 + a, 0, b}, {x0 + a, 0, 0}, rho_w);      // wall, +y
    }
    // Seen from a hair in front of the foot and above it (on the edge itself the formula is 0 / 0),
    // of the floor in front of that point.
    const double hair = 1e-7;
    const glm::dvec3 p(0.0, hair, hair);
    const double F = lambert_factor({glm::dvec3(-a, b, 0.0) - p, glm::dvec3(-a, hair, 0.0) - p,
                                     glm::dvec3(a, hair, 0.0) - p, glm::dvec3(a, b, 0.0) - p},
                                    glm::dvec3(0.0, 1.0, 0.0));
    const Rgb wall = rho_w * Le * F / (1.0 - rho_w * rho_f / 4.0);
    const Rgb floor = Le + rho_f * wall / 2.0;
    BakeSettings settings = gather_settings(2.0f, true);
    settings.final_gather.rays = 4096;
    const BakeResult r = bake(s.input(), settings);
    for (const std::size_t c : corners_at(s, Vec3(0.0f))) {
        const bool on_wall = c % 8 >= 4;
        const double error = worst_relative_error(r, {c}, on_wall ? wall : floor);
        std::printf("%s corner at the foot: %.5f (exact %.5f), relative error %.2e\n", on_wall ? "wall" : "floor",
                    r.colors.input_corner[c].g, (on_wall ? wall : floor).g, error);
        EXPECT_LT(error, 5e-3) << c;  // the rays that read the floor further out read the solution there
    }
}

TEST(FinalGather, CeilingOverAnEmittersBackIsExact) {
    // The unit emitter faces down, 5 cm under a large ceiling that faces down too: the ceiling sees
    // only the emitter's back side (emitting faces are two-sided), L = rho Le F. The gather's rays
    // up there meet the emitter's two coincident sides; the one facing them is the one they see,
    // so the ceiling is neither dark nor taken for buried.
    const double gap = 0.05, h = 1.0;
    const Rgb rho(0.5, 0.6, 0.7), Le(1.0, 2.0, 0.5);
    test::SceneArrays s;
    add_emitter(s, h, Le);
    const float top = float(h + gap);
    for (const auto& [x0, y0] : {std::pair{0.0f, 0.0f}, {-5.0f, 0.0f}, {-5.0f, -5.0f}, {0.0f, -5.0f}})
        s.add_quad({x0, y0, top}, {x0, y0 + 5, top}, {x0 + 5, y0 + 5, top}, {x0 + 5, y0, top}, rho);  // normal -z
    const Rgb expected = rho * Le * (4.0 * corner_factor(0.5, 0.5, gap));
    const std::vector<std::size_t> over = corners_at(s, Vec3(0.0f, 0.0f, top));
    ASSERT_EQ(over.size(), 4u);
    const BakeResult r = bake(s.input(), gather_settings(0.5f, true));
    const double worst = worst_relative_error(r, over, expected);
    std::printf("ceiling over the emitter's back %.6f (exact %.6f), worst relative error %.2e\n",
                r.colors.input_corner[over[0]].g, expected.g, worst);
    EXPECT_LT(worst, 1e-3);
    EXPECT_EQ(r.buried_points, 0u);
}

TEST(FinalGather, FloorUnderASquareEmitterIsExact) {
    // A unit square of radiance Le (reflecting nothing) at height h over the centre of a large
    // floor: the floor's vertex under it has L = rho Le F, F Howell's point-to-square factor (four
    // corner rectangles of 0.5 x 0.5). Nothing else lights the floor: its rays hit the emitter
    // (radiance less emission: 0) or leave the scene.
    const double h = 0.5;
    const Rgb rho(0.5, 0.6, 0.7), Le(1.0, 2.0, 0.5);
    test::SceneArrays s;
    add_emitter(s, h, Le);
    add_floor(s, rho);
    const Rgb expected = rho * Le * (4.0 * corner_factor(0.5, 0.5, h));
    const std::vector<std::size_t> under = corners_at(s, Vec3(0.0f));
    ASSERT_EQ(under.size(), 4u);
    for (const bool gather : {false, true}) {
        const BakeResult r = bake(s.input(), gather_settings(0.5f, gather));
        const double worst = worst_relative_error(r, under, expected);
        std::printf("gather %d: floor under the emitter %.6f (exact %.6f), worst relative error %.2e, %.3f s gather\n",
                    int(gather), r.colors.input_corner[under[0]].g, expected.g, worst, r.seconds_gather);
        if (gather) {
            EXPECT_LT(worst, 1e-3);
            EXPECT_EQ(r.buried_points, 0u);
        } else {
            EXPECT_GT(worst, 2e-2);  // interpolating the elements around it is far off
        }
    }
}

TEST(FinalGather, WallStandingUnderTheEmitterHidesExactlyHalfOfIt) {
    // As above, with a thin black wall (x in [-1 mm, 0], 0.3 m high, no bottom) standing on the
    // floor along y under the emitter's centre line. The floor's corners at the origin on the +x
    // side lie at the wall's foot, a seam: their shadow rays see exactly the emitter's +x half (its
    // elements split at x = 0). Those on the -x side are inside the wall (buried, and so is their
    // element, cut along the wall's footprint): the field and the seams read them gathered further
    // into their polygon, but they show what Cycles bakes there, inside a closed wall: nothing.
    const double h = 0.5;
    const Rgb rho(0.5, 0.6, 0.7), Le(1.0, 2.0, 0.5);
    test::SceneArrays s;
    add_emitter(s, h, Le);
    add_floor(s, rho);
    const float x0 = -0.001f, x1 = 0.0f, y0 = -1.0f, y1 = 1.0f, z1 = 0.3f;
    const Rgb black(0.0);
    s.add_quad({x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}, black, black, 2);  // top, +z
    s.add_quad({x0, y0, 0}, {x0, y0, z1}, {x0, y1, z1}, {x0, y1, 0}, black, black, 2);    // -x
    s.add_quad({x1, y0, 0}, {x1, y1, 0}, {x1, y1, z1}, {x1, y0, z1}, black, black, 2);    // +x
    s.add_quad({x0, y0, 0}, {x1, y0, 0}, {x1, y0, z1}, {x0, y0, z1}, black, black, 2);    // -y
    s.add_quad({x0, y1, 0}, {x0, y1, z1}, {x1, y1, z1}, {x1, y1, 0}, black, black, 2);    // +y
    const Rgb expected = rho * Le * (2.0 * corner_factor(0.5, 0.5, h));
    std::vector<std::size_t> lit, inside;  // the corners at the origin of the floor quads on the +x, -x side
    for (const std::size_t c : corners_at(s, Vec3(0.0f)))
        if (c < 4 * 5) (c / 4 == 1 || c / 4 == 4 ? lit : inside).push_back(c);
    ASSERT_EQ(lit.size(), 2u);
    ASSERT_EQ(inside.size(), 2u);
    for (const bool gather : {false, true}) {
        const BakeResult r = bake(s.input(), gather_settings(0.5f, gather));
        const double worst = worst_relative_error(r, lit, expected);
        for (const Rgb& L : r.colors.input_corner)
            for (int k = 0; k < 3; ++k) ASSERT_TRUE(std::isfinite(L[k]) && L[k] >= 0.0);
        std::printf(
            "gather %d: floor at the wall's foot %.6f (exact %.6f), worst relative error %.2e; "
            "%zu points gathered, %zu buried\n",
            int(gather), r.colors.input_corner[lit[0]].g, expected.g, worst, r.gathered_points, r.buried_points);
        if (gather) {
            EXPECT_LT(worst, 1e-3);
            EXPECT_EQ(r.buried_points, 0u);
            for (const std::size_t c : inside) {
                EXPECT_EQ(max_channel(r.colors.input_corner[c]), 0.0);
                EXPECT_EQ(max_channel(r.light_colors.input_corner[c]), 0.0);
            }
        } else {
            EXPECT_GT(worst, 2e-2);
        }
    }
}

TEST(FinalGather, FloorUnderAPointLampIsExact) {
    // A point lamp of intensity I at height h over the floor's centre: the vertex under it has
    // L = rho I / (pi h^2) exactly; the rest of the floor lights it only by what escapes (nothing).
    const double h = 0.5;
    const Rgb rho(0.5, 0.6, 0.7), I(1.0, 2.0, 3.0);
    test::SceneArrays s;
    add_floor(s, rho);
    for (const bool gather : {false, true}) {
        const BakeResult r = bake_under_lamp(s, I, h, gather);
        const Rgb expected = rho * I / (M_PI * h * h);
        const double worst = worst_relative_error(r, corners_at(s, Vec3(0.0f)), expected);
        std::printf("gather %d: floor under the lamp, worst relative error %.2e\n", int(gather), worst);
        if (gather)
            EXPECT_LT(worst, 1e-3);
        else
            EXPECT_GT(worst, 2e-2);
    }
}

/// The light arriving at X (normal +x) from a Lambertian floor z = 0 over [x0, x1] x [y0, y1], lit
/// only by a point lamp of intensity I at P: the floor's radiance rho I h / (pi d^3) carried by
/// cos cos / r^2, summed by the midpoint rule on cells of `step` metres.
double floor_light_at(const glm::dvec3& X, const glm::dvec3& P, double rho, double I, double x0, double x1, double y0,
                      double y1, double step) {
    const int nx = int(std::lround((x1 - x0) / step)), ny = int(std::lround((y1 - y0) / step));
    const double dx = (x1 - x0) / nx, dy = (y1 - y0) / ny;
    double sum = 0.0;
    for (int i = 0; i < nx; ++i)
        for (int j = 0; j < ny; ++j) {
            const glm::dvec3 Y(x0 + (i + 0.5) * dx, y0 + (j + 0.5) * dy, 0.0);
            const glm::dvec3 toLamp = P - Y, toX = X - Y;
            const double d = glm::length(toLamp), r2 = glm::dot(toX, toX);
            const double radiance = rho * I * P.z / (M_PI * d * d * d);
            sum += radiance * Y.x * X.z / (r2 * r2);  // cos at X = Y.x / r, cos at Y = X.z / r
        }
    return sum * dx * dy;
}

/// The light arriving at the wall's input corners `corners` at X (green channel), each within
/// `tolerance` of `expected` (`direct` the lamp's part of it, irradiance), printed.
void expect_wall_light(const BakeResult& r, const std::vector<std::size_t>& corners, const glm::dvec3& X, double direct,
                       double expected, double tolerance) {
    for (const std::size_t c : corners) {
        const double light = r.light_colors.input_corner[c].g;
        std::printf("wall at (%.2f, %.2f): light %.5f, exact %.5f (direct %.5f), %+.2f%%\n", X.y, X.z, light, expected,
                    direct / M_PI, 100.0 * (light / expected - 1.0));
        EXPECT_NEAR(light / expected, 1.0, tolerance);
    }
}

TEST(FinalGather, AWallBesideALampHungOverAFloorVertexTakesItsExactReflection) {
    // A floor of 8 x 8 faces (reflectance 0.5) with a point lamp 5 cm over one of its vertices, and a
    // wall of 8 x 8 faces standing on the floor's edge that reflects nothing: the light arriving at
    // the wall is the lamp's and one reflection off the floor, exact by quadrature. The floor's
    // corners at the lamp's foot hold the lamp's peak, 400 times the light 1 m off; read as the
    // corners of the faces around it, they would bring those faces' light to several times what
    // the lamp gives them, after every pass that writes gathered light back into the field (the
    // points beside the seam are gathered again).
    const double h = 0.05, rho = 0.5, I = 1.0;
    const glm::dvec3 P(0.5, 0.0, h);
    test::SceneArrays s;
    s.add_grid(Vec3(0, -1, 0), Vec3(2, 0, 0), Vec3(0, 2, 0), 8, Rgb(rho));  // the floor, normal +z
    s.add_grid(Vec3(0, -1, 0), Vec3(0, 2, 0), Vec3(0, 0, 2), 8, Rgb(0.0));  // the wall, normal +x
    const BakeResult r = bake(s.input(), with_lamp(medium_gather_settings(0.5f), Vec3(P), Rgb(I)));
    for (const glm::dvec3 X :
         {glm::dvec3(0, 0, 0.25), glm::dvec3(0, 0, 0.5), glm::dvec3(0, 0.5, 0.25), glm::dvec3(0, 0, 1.0)}) {
        const glm::dvec3 toLamp = P - X;
        const double direct = I * toLamp.x / std::pow(glm::length(toLamp), 3.0);
        const double reflected = floor_light_at(X, P, rho, I, 0.3, 0.7, -0.2, 0.2, 5e-4) +
                                 floor_light_at(X, P, rho, I, 0.0, 2.0, -1.0, 1.0, 5e-3) -
                                 floor_light_at(X, P, rho, I, 0.3, 0.7, -0.2, 0.2, 5e-3);
        const double expected = (direct + reflected) / M_PI;
        const std::vector<std::size_t> corners = corners_at(s, Vec3(X));
        ASSERT_EQ(corners.size(), 4u);
        expect_wall_light(r, corners, X, direct, expected, 0.03);
    }
}

/// The solid angle of the rectangle [x0, x1] x [y0, y1] in the plane z = 0 seen from (0, 0, h):
/// the signed sum of the rectangles from the foot to its corners, atan(x y / (h sqrt(h^2 + x^2 + y^2))).
double rectangle_solid_angle(double x0, double x1, double y0, double y1, double h) {
    auto from_foot = [h](double x, double y) { return std::atan(x * y / (h * std::sqrt(h * h + x * x + y * y))); };
    return from_foot(x1, y1) - from_foot(x0, y1) - from_foot(x1, y0) + from_foot(x0, y0);
}

TEST(FinalGather, AnElementBesideALampReportsHowFarItsCornersWereFromItsLight) {
    // The 1 m face under a point lamp 30 cm high, nearer than half its size: its corners' light,
    // I h / d^3 at each, spread linearly over it, is 0.30 of the light it receives, I times its
    // solid angle; the field keeps the latter (the lamp's exact mean), and the statistics the
    // estimate reads keep the difference, which tells how little of the light's shape the corners hold.
    const double rho = 0.5, I = 1.0, h = 0.3;
    const glm::dvec3 P(0.7, 0.3, h);
    test::SceneArrays s;
    s.add_grid(Vec3(0, -2, 0), Vec3(4, 0, 0), Vec3(0, 4, 0), 4, Rgb(rho));
    BakeSettings settings = gather_settings(1.0f, true);
    settings.final_gather.field_rays = 64;  // the field gathered at the vertices: each its exact direct light
    const BakeResult r = bake(s.input(), with_lamp(settings, Vec3(P), Rgb(I)));
    ASSERT_TRUE(r.gather_statistics.has_value());
    const Elements& elements = r.build.elements;
    std::size_t under = elements.size();
    for (std::size_t e = 0; e < elements.size(); ++e)
        if (glm::distance(elements.centre[e], Vec3(0.5f, 0.5f, 0.0f)) < 1e-4f) under = e;
    ASSERT_LT(under, elements.size());
    double corners = 0.0;
    for (const glm::dvec3 X : {glm::dvec3(0, 0, 0), glm::dvec3(1, 0, 0), glm::dvec3(1, 1, 0), glm::dvec3(0, 1, 0)})
        corners += I * h / std::pow(glm::length(P - X), 3.0) / 4.0;
    const double mean = I * rectangle_solid_angle(-0.7, 0.3, -0.3, 0.7, h);
    const double expected = rho / M_PI * (corners - mean);
    const double reported = r.gather_statistics->element_field_error[under].g;
    std::printf("corners' light %.4f, its mean %.4f: field error %.5f, reported %.5f\n", corners, mean, expected,
                reported);
    EXPECT_NEAR(reported / expected, 1.0, 1e-3);
    EXPECT_NEAR(r.gather_statistics->element_reflected[under].g, rho / M_PI * mean, 1e-3 * rho / M_PI * mean);
}

TEST(FinalGather, TheFieldCarriesALampsExactLightOverEveryElement) {
    // A floor of 1 m faces under a point lamp 90 cm over the middle of one: farther than half its
    // size, so its corners keep their own light, I h / d^3, 0.69 of the light it receives (I times
    // its solid angle); the faces beyond hold less than their corners' blend (the light falls as
    // 1 / d^3). With each element's bubble the field's mean over every face is the lamp's exact light
    // there, which is what the floor reflects into the rest of the scene.
    const double rho = 0.5, I = 1.0, h = 0.9;
    const glm::dvec3 P(0.5, 0.5, h);
    test::SceneArrays s;
    s.add_grid(Vec3(-2, -2, 0), Vec3(4, 0, 0), Vec3(0, 4, 0), 4, Rgb(rho));
    BakeSettings settings = gather_settings(1.0f, true);
    settings.final_gather.field_rays = 64;
    const BakeResult r = bake(s.input(), with_lamp(settings, Vec3(P), Rgb(I)));
    ASSERT_TRUE(r.gather_statistics.has_value());
    const Elements& elements = r.build.elements;
    ASSERT_EQ(elements.size(), 16u);
    for (std::size_t e = 0; e < elements.size(); ++e) {
        const glm::dvec3 c(elements.centre[e]);
        const double exact =
            rho / M_PI * I *
            rectangle_solid_angle(c.x - 0.5 - P.x, c.x + 0.5 - P.x, c.y - 0.5 - P.y, c.y + 0.5 - P.y, h);
        const double solved = r.gather_statistics->element_reflected[e].g;
        const double field = solved + r.gather_statistics->element_field_error[e].g;
        std::printf("face at (%+.1f, %+.1f): exact %.5f, solved %.5f, field %.5f\n", c.x, c.y, exact, solved, field);
        EXPECT_NEAR(solved / exact, 1.0, 1e-3);
        EXPECT_NEAR(field / exact, 1.0, 2e-3);
    }
}

TEST(FinalGather, AWallBesideALampOverTheMiddleOfAFloorFaceTakesItsExactReflection) {
    // A floor of 1 m faces (reflectance 0.5) with a point lamp 60 cm over the middle of one, next to
    // a wall of 0.25 m faces that reflects nothing: the light arriving at the wall is the lamp's and
    // one reflection off the floor, exact by quadrature. The corners of the face under the lamp hold
    // 0.45 of the light it receives: read as their blend alone, the wall would get too little of it.
    const double rho = 0.5, I = 1.0, h = 0.6;
    const glm::dvec3 P(0.5, 0.0, h);
    test::SceneArrays s;
    s.add_grid(Vec3(0, -2, 0), Vec3(3, 0, 0), Vec3(0, 4, 0), 3, Rgb(rho));  // the floor: 3 x 3 faces of 1 x 1.33 m
    s.add_grid(Vec3(0, -2, 0), Vec3(0, 4, 0), Vec3(0, 0, 2), 8, Rgb(0.0));  // the wall, normal +x
    const BakeResult r = bake(s.input(), with_lamp(medium_gather_settings(2.0f), Vec3(P), Rgb(I)));
    for (const glm::dvec3 X :
         {glm::dvec3(0, 0, 0.5), glm::dvec3(0, 0, 1.0), glm::dvec3(0, -1.0, 0.5), glm::dvec3(0, 1.5, 0.25)}) {
        const glm::dvec3 toLamp = P - X;
        const double direct = I * toLamp.x / std::pow(glm::length(toLamp), 3.0);
        const double reflected = floor_light_at(X, P, rho, I, 0.0, 3.0, -2.0, 2.0, 2e-3);
        const double expected = (direct + reflected) / M_PI;
        const std::vector<std::size_t> corners = corners_at(s, Vec3(X));
        ASSERT_FALSE(corners.empty());
        expect_wall_light(r, corners, X, direct, expected, 0.02);
    }
}

TEST(FinalGather, CornersLyingOnAnotherFaceAreBlackAsInCycles) {
    // A 2 m square of its own lies on the floor (the same plane, facing up, as duplicate faces of
    // game levels do), under a point lamp. Cycles' rays leave a point without an offset and meet
    // the other face's back at distance 0: the square's corners, which lie on the floor, and the
    // floor's corners at the origin, which lie on the square, bake black. The floor's outer
    // corners lie on nothing else and take the lamp's exact light.
    const double h = 0.5;
    const Rgb rho(0.5, 0.6, 0.7), I(1.0, 2.0, 3.0);
    test::SceneArrays s;
    add_floor(s, rho);
    s.add_quad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, rho);
    const BakeResult r = bake_under_lamp(s, I, h, true);
    std::vector<std::size_t> on_another = corners_at(s, Vec3(0.0f));
    for (const float x : {-1.0f, 1.0f})
        for (const float y : {-1.0f, 1.0f})
            for (const std::size_t c : corners_at(s, Vec3(x, y, 0.0f))) on_another.push_back(c);
    ASSERT_EQ(on_another.size(), 8u);
    for (const std::size_t c : on_another) EXPECT_EQ(max_channel(r.colors.input_corner[c]), 0.0) << c;
    const double d2 = 50.0 + h * h;
    const Rgb outer = rho * I * (h / std::sqrt(d2) / d2 / M_PI);
    EXPECT_LT(worst_relative_error(r, corners_at(s, Vec3(5.0f, 5.0f, 0.0f)), outer), 1e-3);
    EXPECT_EQ(r.buried_points, 0u);
}

TEST(FinalGather, ASliversCornersBakedInsideTheFaceUnderItAreBlackAsInCycles) {
    // Floor faces of a game level (OpenArena's kaos, moved to the origin): a strip 2.5 cm wide and 8 m
    // long (a sliver of two triangles) and a triangle of its width, 3.25 m long, lying on it, beside
    // two floor triangles that lie on nothing. Cycles bakes a corner a hair from its vertex towards
    // its triangle's centroid: the triangle's corners lie on the strip, one of them 2e-6 m inside its
    // edge, and the strip's corner at the triangle's end lies on the triangle. Their rays meet the
    // other face's back at distance 0 there, and Cycles bakes them black (as kaos' own corners are).
    const Rgb rho(0.5);
    auto at = [](double x, double y) { return Vec3(float(x - 8.0), float(y + 15.0), 0.0f); };
    const Vec3 a = at(4.877, -15.062), b = at(4.877, -15.037), c = at(13.005, -15.037), d = at(13.005, -15.062),
               e = at(8.128, -15.037), f = at(13.005, -9.754), g = at(4.877, -9.754);
    test::SceneArrays s;
    s.add_polygon({b, a, e}, rho, Rgb(0.0));  // the triangle lying on the strip
    s.add_polygon({b, a, c}, rho, Rgb(0.0));  // the strip
    s.add_polygon({a, d, c}, rho, Rgb(0.0));
    s.add_polygon({b, c, f}, rho, Rgb(0.0));  // the floor beside it
    s.add_polygon({b, f, g}, rho, Rgb(0.0));
    BakeSettings settings = gather_settings(3.9f, true);
    settings.final_gather.field_rays = 64;
    const Vec3 lamp = at(8.94, -15.44) + Vec3(0.0f, 0.0f, 3.86f);
    const BakeResult r = bake(s.input(), with_lamp(settings, lamp, Rgb(100.0)));
    // The triangle's three corners, and the strip's at the end the triangle covers.
    for (const std::size_t corner : {0, 1, 2, 3}) EXPECT_EQ(max_channel(r.colors.input_corner[corner]), 0.0) << corner;
    for (std::size_t corner = 4; corner < 15; ++corner) {  // nothing lies under them: the lamp's exact light
        const float* p = &s.positions[3 * s.corner_vertices[corner]];
        const Vec3 x(p[0], p[1], p[2]);
        const glm::dvec3 to_lamp = glm::dvec3(lamp - x);
        const double direct = 100.0 * to_lamp.z / std::pow(glm::length(to_lamp), 3.0);
        EXPECT_NEAR(r.colors.input_corner[corner].g / (0.5 * direct / M_PI), 1.0, 2e-3) << corner;
    }
}

TEST(FinalGather, ASliverUnderTheFootOfARampIsBlackAsInCycles) {
    // Faces of a game level (OpenArena's oa_bases3, where they lie in it): a ramp descending to its
    // foot, a floor strip 3.2 mm wide (two triangles) running on under the ramp's foot from there,
    // and the steeper slope beyond the foot; a black ground of the level's size under them and a lamp
    // over the ramp. Cycles bakes the strip's corners a hair towards their triangles' centroids,
    // under the ramp (at the foot 11 micrometres under it), and its rays, which leave the point
    // itself, meet the ramp's back or leave through the slit, which faces no surface here: black.
    // The gather's rays, lifted a millionth of the scene over the point, passed above the ramp there
    // and found the lamp (0.81 of the ramp's light in the level, where Cycles has 0.002 to 0.014).
    const Rgb rho(0.8);
    const Vec3 ramp_top(96.7232f, 3.84175f, 4.4704f), ramp_top_2(93.472f, 3.84175f, 4.4704f),
        ramp_side(93.472f, 5.2705f, 3.6576f), foot(96.7232f, 10.8458f, 0.4826f), foot_2(93.472f, 10.8458f, 0.4826f),
        strip(96.7232f, 10.84262f, 0.4826f), strip_2(93.472f, 10.84262f, 0.4826f), slope(96.7232f, 10.9728f, 0.4064f),
        slope_2(93.472f, 10.9728f, 0.4064f);
    test::SceneArrays s;
    s.add_polygon({ramp_top, foot, ramp_top_2}, rho, Rgb(0.0));
    s.add_polygon({foot, ramp_side, ramp_top_2}, rho, Rgb(0.0));
    s.add_polygon({foot, foot_2, ramp_side}, rho, Rgb(0.0));
    s.add_polygon({strip, foot, strip_2}, rho, Rgb(0.0));  // the strip under the ramp's foot
    s.add_polygon({foot, foot_2, strip_2}, rho, Rgb(0.0));
    s.add_polygon({foot, slope, foot_2}, rho, Rgb(0.0));
    s.add_polygon({slope, slope_2, foot_2}, rho, Rgb(0.0));
    s.add_polygon({Vec3(-18.3f, -38.2f, -14.6f), Vec3(101.2f, -38.2f, -14.6f), Vec3(101.2f, 15.4f, -14.6f),
                   Vec3(-18.3f, 15.4f, -14.6f)},
                  Rgb(0.0), Rgb(0.0));
    BakeSettings settings = gather_settings(3.9f, true);
    settings.final_gather.field_rays = 64;
    settings.hard_edge_angle = 0.0f;  // every face its own corner colours, as Cycles bakes flat faces
    const Vec3 lamp(95.0976f, 3.6576f, 8.5344f);
    const BakeResult r = bake(s.input(), with_lamp(settings, lamp, Rgb(100.0)));
    const float scene_size = glm::length(Vec3(119.5f, 53.6f, 29.7f));
    for (std::size_t polygon = 0; polygon < 7; ++polygon)
        for (std::size_t k = 0; k < 3; ++k) {
            const std::size_t corner = 3 * polygon + k;
            const Rgb& baked = r.colors.input_corner[corner];
            if (polygon == 3 || polygon == 4) {
                EXPECT_EQ(max_channel(baked), 0.0) << corner;
                continue;
            }
            // The ramp and the slope beyond its foot see nothing that reflects: the lamp's exact light
            // where Cycles bakes the corner.
            EXPECT_NEAR(baked.g / (0.8 * lamp_light_where_baked(s, corner, lamp, 100.0, scene_size)), 1.0, 2e-3)
                << corner;
        }
}

TEST(FinalGather, ACornerBakedOnTheEdgeOfAFaceLyingOnItsOwnIsBlackAsInCycles) {
    // Ceiling faces of a game level (OpenArena's q3dm6ish, where they lie in it; facing down), two
    // brushes' faces overlapping in one plane, a lamp under them. At the vertex (-12.192, -6.5024)
    // the triangle (-10.16, -7.3152) (-12.192, -6.5024) (-12.192, -5.6896) overlaps the other brush's
    // triangle ending at y = -6.5024 in a wedge, and its centroid lies on that line: Cycles bakes
    // the corner on the other face's edge, its rays meet that face at distance 0 there, and it bakes
    // the corner black (4 seeds of 1,024 samples in the level: 0), as every other corner at that
    // vertex, which lies inside a face of the other brush.
    const Rgb rho(0.5);
    const Vec3 a(-8.9408f, -7.3152f, 1.6256f), b(-12.192f, -5.6896f, 1.6256f), c(-8.9408f, -5.6896f, 1.6256f),
        d(-10.16f, -7.3152f, 1.6256f), e(-12.192f, -6.5024f, 1.6256f), f(-10.9728f, -7.3152f, 1.6256f),
        g(-12.192f, -7.3152f, 1.6256f), h(-8.9408f, -6.5024f, 1.6256f), k(-8.9408f, -10.5664f, 1.6256f);
    test::SceneArrays s;
    s.add_polygon({a, b, c}, rho, Rgb(0.0));  // the first brush's ceiling
    s.add_polygon({a, d, b}, rho, Rgb(0.0));
    s.add_polygon({d, e, b}, rho, Rgb(0.0));  // the triangle whose corner at e lies on the edge
    s.add_polygon({d, f, e}, rho, Rgb(0.0));
    s.add_polygon({f, g, e}, rho, Rgb(0.0));
    s.add_polygon({g, h, k}, rho, Rgb(0.0));  // the second brush's, overlapping it
    s.add_polygon({g, e, h}, rho, Rgb(0.0));
    BakeSettings settings = gather_settings(3.9f, true);
    settings.final_gather.field_rays = 64;
    const BakeResult r = bake(s.input(), with_lamp(settings, Vec3(-10.5f, -6.6f, 0.0f), Rgb(100.0)));
    const std::vector<std::size_t> at_e = corners_at(s, e);
    ASSERT_EQ(at_e.size(), 4u);
    for (const std::size_t corner : at_e) EXPECT_EQ(max_channel(r.colors.input_corner[corner]), 0.0) << corner;
}

TEST(FinalGather, SliversSideBySideInOnePlaneKeepTheirLight) {
    // Faces of a game level (OpenArena's q3dm6ish, where they lie in it), each a sliver 1 to 16 mm
    // wide between two faces of its plane (the wall's within 0.7 degrees of it), meeting them edge
    // to edge, none lying on another: a wall's and a floor's, each under a lamp. A sliver's corner is
    // baked a hair towards its centroid, within round-off of its neighbours' edges, but no neighbour
    // lies on it there, and Cycles bakes it lit (the wall's: 0.024 in the level, its neighbours
    // 0.032): every corner takes the lamp's exact light (nothing else reflects here).
    const Rgb rho(0.5);
    const Vec3 wall_a(-12.9921f, -8.1153f, -4.4704f), wall_b(-15.433675f, -11.3792f, -4.4704f),
        wall_c(-12.9921f, -8.1153f, -4.064f), wall_d(-13.001625f, -8.128f, -4.064f),
        wall_e(-15.433675f, -11.3792f, -4.064f);
    const Vec3 floor_a(-3.25755f, 17.88795f, -4.8768f), floor_b(-6.5024f, 15.0241f, -4.8768f),
        floor_c(-3.2512f, 16.2433f, -4.8768f), floor_d(-3.267075f, 17.8816f, -4.8768f),
        floor_e(-6.5024f, 15.351125f, -4.8768f);
    const std::vector<std::pair<std::vector<std::vector<Vec3>>, Vec3>> cases = {
        {{{wall_a, wall_b, wall_c}, {wall_b, wall_d, wall_c}, {wall_b, wall_e, wall_d}}, Vec3(-15.0f, -9.15f, -3.5f)},
        {{{floor_a, floor_b, floor_c}, {floor_a, floor_d, floor_b}, {floor_d, floor_e, floor_b}},
         Vec3(-4.5f, 16.0f, -3.0f)},
    };
    for (const auto& [faces, lamp] : cases) {
        test::SceneArrays s;
        for (const std::vector<Vec3>& face : faces) s.add_polygon(face, rho, Rgb(0.0));
        BakeSettings settings = gather_settings(3.9f, true);
        settings.final_gather.field_rays = 64;
        settings.hard_edge_angle = 0.0f;  // every face its own corner colours, as Cycles bakes flat faces
        const BakeResult r = bake(s.input(), with_lamp(settings, lamp, Rgb(100.0)));
        for (std::size_t corner = 0; corner < 9; ++corner)
            EXPECT_NEAR(r.colors.input_corner[corner].g / (0.5 * lamp_light_where_baked(s, corner, lamp, 100.0)), 1.0,
                        2e-3)
                << corner;
    }
}

TEST(FinalGather, ACornerOfTwoWallsUnderTheSkyHoldsTheInfiniteWedgesLight) {
    // Two walls 20 m wide and 100 m long meeting at an edge of angle a (90, 45 and 20 degrees), open
    // to a uniform sky. Seen from a point on their edge the other wall hides the directions behind
    // its plane, whatever its size, and its light there is the point's own, so on the edge
    //   L = rho F_open L_sky / (1 - rho F_other),  F_open = (1 - cos a) / 2 = 1 - F_other,
    // F_open the cosine-weighted share of the directions within a of the wall's plane on the open
    // side (Hottel's formula for a strip seen from a line). Cycles bakes the corners 20 micrometres
    // from the other wall (a 5 m by 25 m triangle at the origin), nearer than a millionth of the
    // scene: the sky's rays that left that far above the point, or skipped that far at their start,
    // passed the other wall and found 1.85 (90 degrees), 3.3 (45) and 16.6 (20) times this light.
    const Rgb rho(0.5);
    const float width = 20.0f, length = 100.0f;
    for (const double degrees : {90.0, 45.0, 20.0}) {
        const double a = degrees * M_PI / 180.0;
        test::SceneArrays s;
        s.add_grid(Vec3(-width, 0.0f, -length / 2), Vec3(width, 0.0f, 0.0f), Vec3(0.0f, 0.0f, length), 4, rho);  // -y
        s.add_grid(Vec3(0.0f, 0.0f, -length / 2), width * Vec3(-float(std::cos(a)), -float(std::sin(a)), 0.0f),
                   Vec3(0.0f, 0.0f, length), 4, rho);
        BakeSettings settings = medium_gather_settings(5.0f);
        settings.world = WorldLight::uniform(Rgb(1.0));
        const BakeResult r = bake(s.input(), settings);
        const double open = (1.0 - std::cos(a)) / 2.0, exact = 0.5 * open / (1.0 - 0.5 * (1.0 - open));
        int checked = 0;
        for (std::size_t c = 0; c < r.colors.input_corner.size(); ++c) {
            const float* p = &s.positions[3 * s.corner_vertices[c]];
            if (p[0] != 0.0f || p[1] != 0.0f || std::abs(p[2]) > 0.3f * length) continue;  // on the edge, off its ends
            EXPECT_NEAR(r.colors.input_corner[c].g / exact, 1.0, 0.01) << degrees << " degrees, corner " << c;
            ++checked;
        }
        EXPECT_EQ(checked, 12);  // three vertices along the edge, four corners each
    }
}

TEST(FinalGather, AnAcuteNotchInAFurnaceKeepsItsLight) {
    // A closed box, and in it a closed prism whose section has a notch of 45 degrees beside a step
    // 1 cm wide, as a game level's brushes leave them; every face emits E and reflects rho, so
    // L = E / (1 - rho) everywhere. The step's and the notch's corners lie a fraction of a
    // millimetre from the other face: shadow rays towards emitters that left a gap of a millionth
    // of the scene saw the faces behind the notch's other face and found the step 28% too bright,
    // and where they left a millionth above the point, the notch's other face was 7.3% dark. What is
    // left at the step's corners, 2.1% and 2.5% dark where the notch's edge meets the prism's ends,
    // is described in docs/accuracy.md.
    const Rgb rho(0.5), E(1.0);
    const Rgb expected = E / (1.0 - rho);
    test::SceneArrays s;
    const std::vector<glm::vec2> section = {{-0.9f, -0.9f}, {0.9f, -0.9f},  {0.9f, 0.9f},
                                            {-0.01f, 0.9f}, {-0.01f, 0.0f}, {0.0f, 0.0f}};
    for (std::size_t i = 0; i < section.size(); ++i) {  // the sides, facing out
        const glm::vec2 a = section[i], b = section[(i + 1) % section.size()];
        s.add_polygon({Vec3(b, 0.0f), Vec3(b, 1.0f), Vec3(a, 1.0f), Vec3(a, 0.0f)}, rho, E);
    }
    for (const auto& t : std::vector<std::array<int, 3>>{{0, 1, 5}, {1, 2, 5}, {2, 3, 4}, {2, 4, 5}}) {  // the ends
        s.add_polygon({Vec3(section[t[0]], 1.0f), Vec3(section[t[1]], 1.0f), Vec3(section[t[2]], 1.0f)}, rho, E);
        s.add_polygon({Vec3(section[t[2]], 0.0f), Vec3(section[t[1]], 0.0f), Vec3(section[t[0]], 0.0f)}, rho, E);
    }
    const float x0 = -1.5f, x1 = 1.5f, z0 = -0.5f, z1 = 1.5f;  // the box around it, facing in
    s.add_quad({x0, x0, z0}, {x1, x0, z0}, {x1, x1, z0}, {x0, x1, z0}, rho, E);
    s.add_quad({x0, x0, z1}, {x0, x1, z1}, {x1, x1, z1}, {x1, x0, z1}, rho, E);
    s.add_quad({x0, x0, z0}, {x0, x1, z0}, {x0, x1, z1}, {x0, x0, z1}, rho, E);
    s.add_quad({x1, x0, z0}, {x1, x0, z1}, {x1, x1, z1}, {x1, x1, z0}, rho, E);
    s.add_quad({x0, x0, z0}, {x0, x0, z1}, {x1, x0, z1}, {x1, x0, z0}, rho, E);
    s.add_quad({x0, x1, z0}, {x1, x1, z0}, {x1, x1, z1}, {x0, x1, z1}, rho, E);
    BakeSettings settings = medium_gather_settings(0.5f);
    settings.final_gather.shadow_rays = 1024;
    const BakeResult r = bake(s.input(), settings);
    // The step's corners and the notch's other face's, at the notch's edge.
    for (const std::size_t c : {16, 17, 22, 23}) EXPECT_NEAR(r.colors.input_corner[c].g / expected.g, 1.0, 0.03) << c;
    const double worst = test::worst_relative_error(r.colors.input_corner, expected);
    std::printf("notch: worst corner %.2e off\n", worst);
    EXPECT_LT(worst, 0.03);
}

TEST(FinalGather, LightOnlyUnderAPointLampIsExact) {
    // The light arriving under the lamp is I / (pi h^2), whatever the colour, and light x rho is the
    // radiance at every corner. A channel of reflectance 0: the gather still finds its light; the
    // interpolated light is 0 there (nothing in the element's radiance tells it).
    const double h = 0.5;
    const Rgb rho(0.5, 0.0, 0.7), I(1.0, 2.0, 3.0);
    test::SceneArrays s;
    add_floor(s, rho);
    for (const bool gather : {false, true}) {
        const BakeResult r = bake_under_lamp(s, I, h, gather);
        ASSERT_EQ(r.light_colors.input_corner.size(), r.colors.input_corner.size());
        for (std::size_t c = 0; c < r.colors.input_corner.size(); ++c)
            for (int k = 0; k < 3; ++k)
                EXPECT_NEAR(r.light_colors.input_corner[c][k] * rho[k], r.colors.input_corner[c][k],
                            1e-6 * (1.0 + r.colors.input_corner[c][k]));
        const Rgb expected = I / (M_PI * h * h);
        for (const std::size_t c : corners_at(s, Vec3(0.0f))) {
            const Rgb& light = r.light_colors.input_corner[c];
            std::printf("gather %d: light under the lamp %.5f %.5f %.5f, exact %.5f %.5f %.5f\n", int(gather), light.r,
                        light.g, light.b, expected.r, expected.g, expected.b);
            if (gather) {
                for (int k = 0; k < 3; ++k) EXPECT_NEAR(light[k] / expected[k], 1.0, 1e-3);
            } else {
                EXPECT_EQ(light.g, 0.0);
            }
        }
    }
}

/// A 1 cm sensor (facing +x, reflecting rho_s, its centre at height h) over a floor (reflecting
/// rho_f), a 1 m square emitter (radiance Le) 1 m over the floor at x in [1, 2], |y| < 0.5, and a
/// black 1 mm slab (the plate) with its top at height plate_z that shades part of the floor;
/// nothing else. The floor is lit only by the emitter (the sensor's own light on it is below 2e-4
/// of it), so at a sensor corner P
///   L(P) = rho_s [Le F_P + (1/pi) Int_floor rho_f Le F_y cos_P cos_y / r^2 dy],
/// F_x the exact factor from x to the part of the square the plate leaves visible (the square less
/// the plate's shadow from x on its plane, both rectangles: Lambert's contour integral), the
/// integral by the midpoint rule on `cell` cells.
struct SensorOverShadedFloor {
    double h, plate_z, plate[4];  // plate: x0 x1 y0 y1
    const Rgb rho_s{0.5, 0.6, 0.7}, rho_f{0.8}, Le{1.0};
    static constexpr float half = 0.005f;
    static constexpr std::size_t sensor_corner = 4;  // the sensor's first corner

    test::SceneArrays scene() const {
        test::SceneArrays s;
        const float z = float(h), pz = float(plate_z);
        s.add_quad({-1, -3, 0}, {4, -3, 0}, {4, 3, 0}, {-1, 3, 0}, rho_f);
        s.add_quad({0, -half, z - half}, {0, half, z - half}, {0, half, z + half}, {0, -half, z + half}, rho_s);
        s.add_quad({1, -0.5f, 1}, {1, 0.5f, 1}, {2, 0.5f, 1}, {2, -0.5f, 1}, Rgb(0.0), Le, 1);
        const float x0 = float(plate[0]), x1 = float(plate[1]), y0 = float(plate[2]), y1 = float(plate[3]);
        s.add_quad({x0, y0, pz}, {x1, y0, pz}, {x1, y1, pz}, {x0, y1, pz}, Rgb(0.0));
        const float under = pz - 0.001f;  // a slab: the floor under it sees its black underside
        s.add_quad({x0, y0, under}, {x0, y1, under}, {x1, y1, under}, {x1, y0, under}, Rgb(0.0));
        return s;
    }

    static double factor_to_rectangle(const glm::dvec3& x, const glm::dvec3& n, double x0, double x1, double y0,
                                      double y1) {
        if (!(x0 < x1 && y0 < y1)) return 0.0;
        std::vector<glm::dvec3> corners{{x0, y0, 1.0}, {x1, y0, 1.0}, {x1, y1, 1.0}, {x0, y1, 1.0}};
        for (glm::dvec3& corner : corners) corner -= x;
        return lambert_factor(corners, n);
    }

    double factor_to_emitter(const glm::dvec3& x, const glm::dvec3& n) const {
        const double scale = (1.0 - x.z) / (plate_z - x.z);  // the plate seen from x, on the emitter's plane
        const double sx0 = x.x + scale * (plate[0] - x.x), sx1 = x.x + scale * (plate[1] - x.x);
        const double sy0 = x.y + scale * (plate[2] - x.y), sy1 = x.y + scale * (plate[3] - x.y);
        return factor_to_rectangle(x, n, 1.0, 2.0, -0.5, 0.5) -
               factor_to_rectangle(x, n, std::max(1.0, sx0), std::min(2.0, sx1), std::max(-0.5, sy0),
                                   std::min(0.5, sy1));
    }

    Rgb exact(double cell) const {
        const glm::dvec3 p(0.0, -half, h - half), n(1.0, 0.0, 0.0), up(0.0, 0.0, 1.0);
        double indirect = 0.0;
        for (double x = 0.5 * cell; x < 4.0; x += cell)  // the floor the sensor faces (x > 0)
            for (double y = -3.0 + 0.5 * cell; y < 3.0; y += cell) {
                const glm::dvec3 d = glm::dvec3(x, y, 0.0) - p;
                const double r2 = glm::dot(d, d);
                const double cosines = glm::dot(d, n) * -glm::dot(d, up) / (r2 * r2);
                indirect += factor_to_emitter(glm::dvec3(x, y, 0.0), up) * cosines * cell * cell / M_PI;
            }
        return rho_s * Le * (factor_to_emitter(p, n) + rho_f * indirect);
    }

    /// The relative error at the sensor's corner of a bake at 0.25 m elements.
    double error(int resolution, int field_rays, const Rgb& expected) const {
        BakeSettings settings = gather_settings(0.25f, true);
        settings.resolution = resolution;
        settings.final_gather.rays = 4096;
        settings.final_gather.field_rays = field_rays;
        const BakeResult r = bake(scene().input(), settings);
        const double error = worst_relative_error(r, {sensor_corner}, expected);
        std::printf("resolution %d, field rays %d: sensor corner %.6f (exact %.6f), relative error %.2e\n", resolution,
                    field_rays, r.colors.input_corner[sensor_corner].g, expected.g, error);
        return error;
    }
};

TEST(FinalGather, TheFieldGatheredAtTheElementsVerticesReadsExactFloorLight) {
    // The sensor 0.3 m up, the plate's shadow 0.6 to 1.6 m in front of it. At hemi-cube resolution 8
    // the solution's floor light is off by the hemi-cube's aliasing (3.5% at the sensor); gathering
    // the field at the elements' vertices first puts the floor's exact direct light under the
    // gather's rays.
    const SensorOverShadedFloor case_{0.3, 0.5, {0.9, 1.3, -0.2, 0.2}};
    const Rgb expected = case_.exact(0.005);
    EXPECT_GT(case_.error(8, 0, expected), 1e-2);
    EXPECT_LT(case_.error(8, 64, expected), 3e-3);
}

/// A black fin (the plane x = 0 for y < 0, 3 m tall, facing +x) stands on add_floor's floor, its
/// foot at the origin, and hides an emitter behind it (x < 0, 1 m up: lower than the fin, so the fin
/// hides it as a half-plane would). A floor point q in front (q_x > 0) sees the part of the emitter
/// with q_x e_y - q_y e_x >= 0: next to the foot the floor's light turns with the direction from the
/// vertex, from none (along the fin) to all of it (beyond the fin's end). The fin's corner at its
/// foot, baked a hair up and along the fin (Cycles' bake_offset_towards_center), sees that floor
/// within a few hairs: the light arriving there is
///   E(P) = Int_{q_x > 0} rho_f Le F(q) cos_P cos_q / (pi r^2) dq,
/// F(q) Lambert's factor of the visible part, the integral in polar coordinates about P's foot.
struct FinAtItsFoot {
    const Rgb rho_f{0.5}, Le{1.0, 2.0, 0.5};
    static constexpr double x0 = -1.5, x1 = -0.5, y0 = -0.5, y1 = 0.5, height = 1.0;
    static constexpr std::size_t foot_corner = 17;  // after the floor's 16: the fin's corner 1

    test::SceneArrays scene() const {
        test::SceneArrays s;
        add_floor(s, rho_f);
        s.add_quad({0, -6, 0}, {0, 0, 0}, {0, 0, 3}, {0, -6, 3}, Rgb(0.0));  // the fin, +x
        const float ex0 = float(x0), ex1 = float(x1), ey0 = float(y0), ey1 = float(y1), z = float(height);
        s.add_quad({ex0, ey0, z}, {ex0, ey1, z}, {ex1, ey1, z}, {ex1, ey0, z}, Rgb(0.0), Le, 1);  // -z
        return s;
    }

    /// The factor from floor point q (q_x > 0) to the part of the emitter the fin leaves visible.
    static double visible_factor(const glm::dvec2& q) {
        const std::vector<glm::dvec2> square{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
        std::vector<glm::dvec3> clipped;  // Sutherland-Hodgman against q_x e_y - q_y e_x >= 0
        auto side = [&](const glm::dvec2& e) { return q.x * e.y - q.y * e.x; };
        for (std::size_t i = 0; i < square.size(); ++i) {
            const glm::dvec2 a = square[i], b = square[(i + 1) % square.size()];
            const double sa = side(a), sb = side(b);
            if (sa >= 0.0) clipped.emplace_back(a - q, height);
            if ((sa >= 0.0) != (sb >= 0.0)) clipped.emplace_back(a + (b - a) * (sa / (sa - sb)) - q, height);
        }
        return clipped.size() < 3 ? 0.0 : lambert_factor(clipped, glm::dvec3(0.0, 0.0, 1.0));
    }

    /// E(P) / pi at P = (0, py, pz).
    Rgb exact(double py, double pz) const {
        const int rings = 600, sectors = 360;
        const double log_inner = std::log(1e-9), log_outer = std::log(15.0);
        double sum = 0.0;
        for (int i = 0; i < rings; ++i) {
            const double r = std::exp(log_inner + (i + 0.5) * (log_outer - log_inner) / rings);
            for (int j = 0; j < sectors; ++j) {
                const double phi = -M_PI / 2.0 + (j + 0.5) * M_PI / sectors;
                const glm::dvec2 q(r * std::cos(phi), py + r * std::sin(phi));
                if (q.x > 5.0 || std::abs(q.y) > 5.0) continue;
                const double d2 = r * r + pz * pz;
                sum += visible_factor(q) * q.x * pz / (M_PI * d2 * d2) * r * r;  // cos cos / (pi r^2) r^2 dln r
            }
        }
        return rho_f * Le * (sum * (log_outer - log_inner) / rings * M_PI / sectors);
    }
};

TEST(FinalGather, TheLightTurningAroundAFinsFootReachesItsCorner) {
    // The floor's elements hold one value at the foot's vertex, but the fin's corner reads the
    // floor within a hair of it, where the light turns from none to all of the emitter: without
    // the tables of corner_wedges.h the corner is 19% dark, 40% bright with its rays leaving from
    // 1e-5 of the scene's size off the fin (twice as far as the corner is from the floor), and 3%
    // bright from 1e-6: its rays leave the point itself, as Cycles' do. The tables near the fin take
    // a quarter of the shadow rays each; at 256 their noise alone moved the corner by 4%.
    const FinAtItsFoot fin;
    const double hair = 1e-4 / std::sqrt(5.0);  // towards the centroid of (0, -6, 0), (0, 0, 0), (0, 0, 3)
    const Rgb expected = fin.exact(-2.0 * hair, hair);
    BakeSettings settings = gather_settings(0.25f, true);
    settings.final_gather.rays = 4096;
    settings.final_gather.field_rays = 64;
    settings.final_gather.shadow_rays = 2048;
    const BakeResult r = bake(fin.scene().input(), settings);
    const Rgb got = r.light_colors.input_corner[FinAtItsFoot::foot_corner];
    double worst = 0.0;
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(got[c] / expected[c] - 1.0));
    std::printf("fin's foot: %.6f (exact %.6f), relative error %.2e\n", got.g, expected.g, worst);
    EXPECT_LT(worst, 0.02);
}

TEST(FinalGather, FurnaceAtEveryCornerOfAClosedBox) {
    // Closed box, uniform E and rho: L = E / (1 - rho) everywhere, at each box corner too, where
    // three faces meet: the unoccluded factors to the other faces sum to 1, and no gather ray may
    // slip out through a seam or stop at the neighbouring face at distance 0. Every corner must be
    // gathered (none judged buried).
    const Rgb rho(0.5, 0.7, 0.9), E(1.0, 0.5, 2.0);
    const Rgb expected = E / (1.0 - rho);
    const test::SceneArrays box = test::closed_box(Vec3(1.0f, 1.5f, 0.8f), rho, E);
    for (const float element_size : {0.0f, 0.3f}) {
        const BakeResult r = bake(box.input(), gather_settings(element_size, true));
        ASSERT_EQ(r.colors.input_corner.size(), 24u);
        EXPECT_EQ(r.gathered_points, 24u);
        EXPECT_EQ(r.buried_points, 0u);
        const double worst = test::worst_relative_error(r.colors.input_corner, expected);
        std::printf("furnace element_size %.1f: worst corner %.2e\n", element_size, worst);
        EXPECT_LT(worst, 1e-3) << element_size;
    }
}

TEST(FinalGather, EmissionCountsOnceInARotatedFurnace) {
    // The furnace turned about a skew axis, as an artist's rotated object is: every point lies in its
    // element's plane only to round-off, and so in front of or behind the back side that its
    // two-sided emitting element also has. Seen from in front of it, that back side's factor is the
    // whole hemisphere: counted, the light is E + rho (2 E + rho L) ~ 1.75 / 1.4 of the exact.
    const Rgb rho(0.5), E(0.7);
    const Rgb expected = E / (1.0 - rho);
    test::SceneArrays box = test::closed_box(Vec3(2.0f, 1.5f, 0.8f), rho, E);
    const glm::mat3 turn = glm::mat3(glm::rotate(glm::mat4(1.0f), 0.9f, glm::normalize(Vec3(0.3f, 0.5f, 0.7f))));
    for (std::size_t v = 0; v + 2 < box.positions.size(); v += 3) {
        const Vec3 p = turn * Vec3(box.positions[v], box.positions[v + 1], box.positions[v + 2]);
        for (int c = 0; c < 3; ++c) box.positions[v + std::size_t(c)] = p[c];
    }
    for (const float element_size : {0.0f, 0.2f}) {
        const BakeResult r = bake(box.input(), gather_settings(element_size, true));
        EXPECT_EQ(r.gathered_points, 24u);
        const double worst = test::worst_relative_error(r.colors.input_corner, expected);
        std::printf("rotated furnace element_size %.1f: worst corner %.2e\n", element_size, worst);
        EXPECT_LT(worst, 1e-3) << element_size;
    }
}

TEST(FinalGather, ABendingSmoothSurfaceKeepsOneColourPerVertex) {
    // Two faces folded by 20 degrees (within the hard-edge angle) along y, under an emitter off to
    // one side: each sees it differently, but the vertices they share show one colour, the mean
    // of theirs, as interpolation would; the faces' far corners keep their own.
    const Rgb rho(0.5), Le(1.0);
    const float rise = std::tan(20.0f * float(M_PI) / 180.0f);
    test::SceneArrays s;
    s.add_quad({-1, 0, 0}, {0, 0, 0}, {0, 1, 0}, {-1, 1, 0}, rho);                              // flat, +z
    s.add_quad({0, 0, 0}, {1, 0, rise}, {1, 1, rise}, {0, 1, 0}, rho);                          // rising, about +z
    s.add_quad({-0.5f, 0, 1.5f}, {-0.5f, 1, 1.5f}, {1, 1, 1.5f}, {1, 0, 1.5f}, Rgb(0), Le, 1);  // emitter, -z
    const BakeResult r = bake(s.input(), gather_settings(0.25f, true));
    ASSERT_EQ(r.gathered_points, 12u);
    for (const Vec3 ridge : {Vec3(0, 0, 0), Vec3(0, 1, 0)}) {
        const std::vector<std::size_t> at = corners_at(s, ridge);
        ASSERT_EQ(at.size(), 2u);
        EXPECT_EQ(r.colors.input_corner[at[0]], r.colors.input_corner[at[1]]);
        EXPECT_GT(r.colors.input_corner[at[0]].g, 0.0);
    }
}

TEST(FinalGather, SameBakeTwiceIsBitIdentical) {
    const test::SceneArrays box = test::cornell_box();
    const BakeSettings settings = gather_settings(0.1f, true);
    const BakeResult a = bake(box.input(), settings), b = bake(box.input(), settings);
    ASSERT_GT(a.gathered_points, 0u);
    ASSERT_EQ(a.colors.input_corner.size(), b.colors.input_corner.size());
    for (const Rgb& L : a.colors.input_corner)
        for (int c = 0; c < 3; ++c) ASSERT_TRUE(std::isfinite(L[c]) && L[c] >= 0.0);
    EXPECT_EQ(std::memcmp(a.colors.input_corner.data(), b.colors.input_corner.data(),
                          a.colors.input_corner.size() * sizeof(Rgb)),
              0);
    std::printf("Cornell box: %zu corners gathered, %zu buried, %.3f s\n", a.gathered_points, a.buried_points,
                a.seconds_gather);
}

TEST(FinalGather, ReportsProgressAndCancels) {
    const test::SceneArrays box = test::closed_box(Vec3(1.0f), Rgb(0.5), Rgb(1.0));
    std::size_t reports = 0;
    const BakeResult r = bake(box.input(), gather_settings(0.5f, true), [&](const Progress& p) {
        if (std::strcmp(p.phase, "gather") == 0) ++reports;
        return true;
    });
    EXPECT_GT(reports, 0u);
    EXPECT_EQ(r.gathered_points, 24u);
    EXPECT_THROW(bake(box.input(), gather_settings(0.5f, true),
                      [](const Progress& p) { return std::strcmp(p.phase, "gather") != 0; }),
                 Cancelled);
}

}  // namespace
}  // namespace radiosity
