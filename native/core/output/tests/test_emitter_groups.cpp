/// @file test_emitter_groups.cpp
/// @brief The final gather's emitter runs: a tessellated emitter (each face a polygon of its own) is
/// one run whose light at a point is the exact factor of the whole rectangle; separate panels in one
/// plane stay separate runs.
#include "output/emitter_groups.h"

#include "testing/test_util.h"

#include <gtest/gtest.h>

#include <cmath>

namespace radiosity::detail {
namespace {

/// The factor from a point to a parallel X x Y rectangle at distance 1, over one of its corners
/// (Howell's catalogue, B-3): (1 / 2 pi) [X / sqrt(1 + X^2) atan(Y / sqrt(1 + X^2)) + Y / sqrt(1 + Y^2)
/// atan(X / sqrt(1 + Y^2))].
double corner_factor(double X, double Y) {
    const double a = std::sqrt(1.0 + X * X), b = std::sqrt(1.0 + Y * Y);
    return (X / a * std::atan(Y / a) + Y / b * std::atan(X / b)) / (2.0 * M_PI);
}

std::vector<EmitterRun> runs_of(const test::SceneArrays& scene, BuildResult& build, std::vector<Emitter>& emitters) {
    build = build_elements(scene.input(), 0.0f);
    emitters = emitting_elements(build.elements, build.elements.emission);
    return emitter_runs(build.elements, emitters);
}

TEST(EmitterGroups, TessellatedEmitterIsOneRunWithTheRectanglesExactLight) {
    // A unit square emitter 1 m over the origin, facing down, as 8 x 8 faces: one run a side, its
    // outline the square's 4 sides (the faces' shared edges cancel, and the 8 pieces of each side
    // join), and its light at the origin the factor of the square seen from under its corner.
    test::SceneArrays scene;
    scene.add_grid(Vec3(0, 0, 1), Vec3(0, 1, 0), Vec3(1, 0, 0), 8, Rgb(0.0), Rgb(2.0));
    BuildResult build;
    std::vector<Emitter> emitters;
    const std::vector<EmitterRun> runs = runs_of(scene, build, emitters);
    ASSERT_EQ(runs.size(), 2u);  // the front and the back side
    EXPECT_EQ(runs[0].last - runs[0].first, 64u);
    EXPECT_EQ(runs[0].outline.size(), 4u);
    const EmitterGroups seen = emitter_groups(emitters, runs, glm::dvec3(0.0, 0.0, 0.0), glm::dvec3(0, 0, 1));
    EXPECT_NEAR(seen.groups[0].light.g / (2.0 * corner_factor(1.0, 1.0)), 1.0, 1e-9);
    EXPECT_EQ(max_channel(seen.groups[1].light), 0.0);  // the back side faces away
}

TEST(EmitterGroups, SeparatePanelsInOnePlaneAreRunsOfTheirOwn) {
    // Two panels of 2 x 2 faces under one ceiling, 0.5 m apart: they meet nowhere.
    test::SceneArrays scene;
    scene.add_grid(Vec3(0, 0, 1), Vec3(0, 0.5f, 0), Vec3(0.5f, 0, 0), 2, Rgb(0.0), Rgb(2.0));
    scene.add_grid(Vec3(1, 0, 1), Vec3(0, 0.5f, 0), Vec3(0.5f, 0, 0), 2, Rgb(0.0), Rgb(2.0));
    BuildResult build;
    std::vector<Emitter> emitters;
    const std::vector<EmitterRun> runs = runs_of(scene, build, emitters);
    EXPECT_EQ(runs.size(), 4u);  // each panel's front and back
}

}  // namespace
}  // namespace radiosity::detail
