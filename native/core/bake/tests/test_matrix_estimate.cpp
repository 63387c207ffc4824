/// @file test_matrix_estimate.cpp
/// @brief estimate_matrix against the nonzeros of the whole matrix, on a closed scene (the Cornell
/// box) and an open one (a corner of walls and a block under an open sky).
#include "bake/bake.h"
#include "bake/matrix_estimate.h"
#include "testing/test_util.h"
#include "transport/form_factors.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace radiosity {
namespace {

/// A 4 x 4 m floor, two 2 m walls along two of its sides and a 1 m block on it, open above and on
/// the other two sides: elements on the block's top see little, the floor's see walls and block.
test::SceneArrays open_corner() {
    test::SceneArrays s;
    const Rgb white(0.7);
    s.add_quad({0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, white);  // floor
    s.add_quad({0, 4, 0}, {4, 4, 0}, {4, 4, 2}, {0, 4, 2}, white);  // back wall, facing -y
    s.add_quad({0, 0, 0}, {0, 4, 0}, {0, 4, 2}, {0, 0, 2}, white);  // left wall, facing +x
    s.add_quad({2, 1, 1}, {3, 1, 1}, {3, 2, 1}, {2, 2, 1}, white);  // block: top
    s.add_quad({2, 1, 0}, {3, 1, 0}, {3, 1, 1}, {2, 1, 1}, white);  // front, facing -y
    s.add_quad({3, 1, 0}, {3, 2, 0}, {3, 2, 1}, {3, 1, 1}, white);  // right, facing +x
    s.add_quad({3, 2, 0}, {2, 2, 0}, {2, 2, 1}, {3, 2, 1}, white);  // back, facing +y
    s.add_quad({2, 2, 0}, {2, 1, 0}, {2, 1, 1}, {2, 2, 1}, white);  // left, facing -x
    return s;
}

struct Counted {
    MatrixEstimate estimate;
    std::size_t nonzeros = 0, bytes = 0;
};

Counted count(const test::SceneArrays& scene, float element_size, int resolution) {
    const Elements elements = build_elements(scene.input(), element_size).elements;
    RowSettings rows;
    rows.resolution = resolution;
    const SparseMatrix matrix = compute_form_factors(elements, rows);
    Counted counted{estimate_matrix(elements, rows), matrix.nonzeros(), matrix.bytes()};
    const MatrixEstimate& e = counted.estimate;
    std::printf(
        "%zu elements at %d: %zu nonzeros, estimated %.0f +- %.0f from %zu rows, with the margin %zu "
        "(%.3f of the count)\n",
        elements.size(), resolution, counted.nonzeros, e.mean_fill * elements.size(),
        e.standard_error * elements.size(), e.rows_sampled, e.nonzeros, double(e.nonzeros) / counted.nonzeros);
    return counted;
}

/// The sample's mean within its 3 standard errors of the true mean fill, and the estimate with
/// its margin (3 standard errors above) at or above the count, yet within 1.25 of it: a matrix
/// planned for is about the matrix stored.
void expect_within_margin(const Counted& c, std::size_t n) {
    const double mean = double(c.nonzeros) / double(n);
    EXPECT_EQ(c.estimate.rows_sampled, 256u);
    EXPECT_LE(std::abs(c.estimate.mean_fill - mean), 3.0 * c.estimate.standard_error);
    EXPECT_GE(c.estimate.nonzeros, c.nonzeros);
    EXPECT_LE(double(c.estimate.nonzeros), 1.25 * double(c.nonzeros));
    EXPECT_EQ(c.estimate.bytes, c.bytes + (c.estimate.nonzeros - c.nonzeros) * 8);
}

TEST(MatrixEstimate, ClosedCornellBoxWithinTheMargin) {
    const test::SceneArrays box = test::cornell_box();
    const Counted c = count(box, 0.05f, 64);
    expect_within_margin(c, build_elements(box.input(), 0.05f).elements.size());
}

TEST(MatrixEstimate, OpenCornerWithinTheMargin) {
    const test::SceneArrays corner = open_corner();
    const std::size_t n = build_elements(corner.input(), 0.15f).elements.size();
    const Counted c = count(corner, 0.15f, 64);
    expect_within_margin(c, n);
    // Half the hemi-cubes see the sky: far under the bound's n min(n, 3 N^2) nonzeros.
    EXPECT_LT(double(c.estimate.nonzeros), 0.7 * double(n) * double(n));
}

TEST(MatrixEstimate, EveryRowSampledCountsExactly) {
    const Elements elements = build_elements(test::cornell_box().input(), 0.2f).elements;
    RowSettings rows;
    rows.resolution = 32;
    MatrixSampling all;
    all.rows = int(elements.size());
    const MatrixEstimate estimate = estimate_matrix(elements, rows, all);
    const SparseMatrix matrix = compute_form_factors(elements, rows);
    EXPECT_EQ(estimate.standard_error, 0.0);
    EXPECT_EQ(estimate.nonzeros, matrix.nonzeros());
    EXPECT_EQ(estimate.bytes, matrix.bytes());
}

TEST(MatrixEstimate, PlanAndBakeStoreWhatTheEstimateFits) {
    // Budgets between the stored matrix and the bound: the core judges F by the estimate, and plan()
    // and bake() agree on it; a byte under the matrix itself, the estimate (never under it) does not fit.
    const test::SceneArrays corner = open_corner();
    BakeSettings settings;
    settings.element_size = 0.25f;
    settings.resolution = 32;
    const BakeResult stored = bake(corner.input(), settings);
    ASSERT_TRUE(stored.matrix_stored);
    const BakePlan roomy = plan(corner.input(), settings);
    EXPECT_EQ(roomy.matrix_bytes_planned, roomy.matrix_bytes_bound);  // within the budget: no sample needed
    for (const double share : {0.8, 0.5}) {  // of the bound, over the matrix stored (0.38 of it)
        settings.matrix_budget_bytes = std::size_t(share * double(roomy.matrix_bytes_bound));
        const BakePlan planned = plan(corner.input(), settings);
        std::printf("budget %zu: stored %zu bytes, bound %zu, planned %zu\n", settings.matrix_budget_bytes,
                    stored.matrix_bytes, planned.matrix_bytes_bound, planned.matrix_bytes_planned);
        EXPECT_GE(planned.matrix_bytes_planned, stored.matrix_bytes);
        EXPECT_LE(double(planned.matrix_bytes_planned), 1.25 * double(stored.matrix_bytes));
        EXPECT_TRUE(planned.matrix_stored);
        const BakeResult baked = bake(corner.input(), settings);
        EXPECT_TRUE(baked.matrix_stored);
        EXPECT_EQ(baked.matrix_bytes, stored.matrix_bytes);
    }
    settings.matrix_budget_bytes = stored.matrix_bytes - 1;
    EXPECT_FALSE(plan(corner.input(), settings).matrix_stored);
    EXPECT_FALSE(bake(corner.input(), settings).matrix_stored);
}

}  // namespace
}  // namespace radiosity
