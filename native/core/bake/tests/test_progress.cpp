/// @file test_progress.cpp
/// @brief Phases that can take more than a second report as they go: building elements, the
/// texture means, and a Gauss-Seidel sweep whose rows are rendered on demand (row by row, so it
/// can be cancelled within a sweep).
#include "bake/bake.h"

#include "testing/test_util.h"

#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <vector>

namespace radiosity {
namespace {

TEST(Progress, BuildingElementsReportsItsPolygonsUpToAll) {
    const test::SceneArrays box = test::cornell_box();
    std::vector<std::size_t> done;
    std::size_t total = 0;
    build_elements(box.input(), 0.05f, {}, [&](const Progress& p) {
        EXPECT_EQ(std::string(p.phase), "elements");
        done.push_back(p.done);
        total = p.total;
        return true;
    });
    ASSERT_GE(done.size(), 2u);
    EXPECT_EQ(total, box.material.size());
    EXPECT_EQ(done.front(), 0u);
    EXPECT_EQ(done.back(), total);
    for (std::size_t k = 1; k < done.size(); ++k) EXPECT_GE(done[k], done[k - 1]);
}

TEST(Progress, BuildingElementsCanBeCancelled) {
    const test::SceneArrays box = test::cornell_box();
    EXPECT_THROW(build_elements(box.input(), 0.05f, {}, [](const Progress&) { return false; }), Cancelled);
}

TEST(Progress, GaussSeidelOnDemandReportsRowsWithinASweepAndCancelsThere) {
    // About 1,500 elements at resolution 256 with no room for the matrix: each sweep renders
    // every row's hemi-cube, which takes seconds here.
    const test::SceneArrays box = test::closed_box(Vec3(1.0f, 1.5f, 0.8f), Rgb(0.5), Rgb(1.0));
    BakeSettings settings;
    settings.element_size = 0.06f;
    settings.resolution = 256;
    settings.matrix_budget_bytes = 1;
    settings.solve.method = Method::GaussSeidel;
    settings.solve.tolerance = 1e-8;
    std::size_t rows_reported = 0, sweeps_reported = 0, elements = 0;
    const auto start = std::chrono::steady_clock::now();
    EXPECT_THROW(bake(box.input(), settings,
                      [&](const Progress& p) {
                          const std::string phase = p.phase;
                          if (phase == "solve") ++sweeps_reported;
                          if (phase != "solve rows") return true;
                          ++rows_reported;
                          elements = p.total;
                          EXPECT_GT(p.done, 0u);
                          EXPECT_LT(p.done, p.total);
                          EXPECT_NE(p.radiance, nullptr);
                          return false;  // cancel at the first report of rows
                      }),
                 Cancelled);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(rows_reported, 1u);
    EXPECT_EQ(sweeps_reported, 0u);  // cancelled within the first sweep
    EXPECT_GT(elements, 1000u);
    EXPECT_LT(seconds, 30.0);
}

}  // namespace
}  // namespace radiosity
