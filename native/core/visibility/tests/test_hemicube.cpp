/// @file test_hemicube.cpp
/// @brief Cube weights and hemi-cube rendering against closed forms.

#include "testing/test_util.h"
#include "visibility/hemicube.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <cmath>
#include <numeric>

using namespace radiosity;

namespace {

/// Form factor from element `from` (hemi-cube at its centre) to element `to`.
double point_factor(const Elements& elements, int32_t from, int32_t to, int resolution) {
    Hemicube hemicube(CubeWeights::make(resolution));
    hemicube.render_hemisphere(elements, elements.centre[from], elements.normal[from], from);
    SparseRow row;
    hemicube.accumulate(hemicube.weights().form_factor, row);
    double f = 0.0;
    for (std::size_t k = 0; k < row.col.size(); ++k)
        if (row.col[k] == to) f += row.val[k];
    return f;
}

// Exact point-to-area values (Howell's catalogue).
constexpr double kOpposedPoint = 0.239456;        // centre of a unit square to the opposed one 1 m away
constexpr double kPerpendicularPoint = 0.190136;  // centre of a unit square to a perpendicular one, common edge

}  // namespace

TEST(CubeWeights, DeltaFormFactorsSumToOneAndSolidAnglesToFourPi) {
    for (int n : {2, 8, 50, 128, 256}) {
        const auto w = CubeWeights::make(n);
        ASSERT_EQ(w->form_factor.size(), std::size_t(3 * n * n));
        ASSERT_EQ(w->solid_angle.size(), std::size_t(6 * n * n));
        EXPECT_NEAR(std::accumulate(w->form_factor.begin(), w->form_factor.end(), 0.0), 1.0, 1e-6) << n;
        EXPECT_NEAR(std::accumulate(w->solid_angle.begin(), w->solid_angle.end(), 0.0), 4.0 * M_PI, 4.0 * M_PI * 1e-6)
            << n;
    }
}

TEST(CubeWeights, CellsMatchTheIntegrandNearTheirCentres) {
    // A small cell's exact value is close to integrand x cell area at its centre.
    const int n = 256;
    const auto w = CubeWeights::make(n);
    const double area = (2.0 / n) * (2.0 / n);
    const std::size_t top_centre = std::size_t(n / 2) * n + n / 2;  // centre at (h/2, h/2)
    const double x = 1.0 / n, y = 1.0 / n;
    EXPECT_NEAR(w->form_factor[top_centre], area / (M_PI * std::pow(x * x + y * y + 1, 2)), 1e-4 * area);
    EXPECT_NEAR(w->solid_angle[top_centre], area / std::pow(x * x + y * y + 1, 1.5), 1e-4 * area);
    // Side faces (at distance 1, y = w): integrand w / (pi r^4); row 0 is w in [0, h].
    const std::size_t side = std::size_t(n) * n + n / 2;
    EXPECT_NEAR(w->form_factor[side], y * area / (M_PI * std::pow(x * x + y * y + 1, 2)), 1e-3 * y * area);
}

TEST(Hemicube, PointToOpposedSquareIsExactWhenItsOutlineFollowsCellEdges) {
    // At 1 m the square spans x, y in [-1/2, 1/2] on the top face: cell edges when 4 divides the
    // resolution, so the exact delta form factors add up to the exact value (to its 6 digits).
    const BuildResult r = build_elements(test::opposed_unit_squares(1.0f).input(), 0.0f);
    for (int n : {4, 16, 128}) EXPECT_NEAR(point_factor(r.elements, 1, 0, n), kOpposedPoint, 1e-6) << n;
}

TEST(Hemicube, PointToOpposedSquareConverges) {
    // Resolutions 2 mod 4 put the outline through cell centres: the worst case, and the tie rule's.
    const BuildResult r = build_elements(test::opposed_unit_squares(1.0f).input(), 0.0f);
    double previous = 1.0;
    for (int n : {18, 66, 258}) {
        const double error = std::abs(point_factor(r.elements, 1, 0, n) - kOpposedPoint);
        std::printf("opposed point, res %d: error %.2e\n", n, error);
        EXPECT_LT(error, previous);
        previous = error;
    }
    EXPECT_LT(previous, 2e-3 * kOpposedPoint);
}

TEST(Hemicube, PointToPerpendicularSquareConverges) {
    const BuildResult r = build_elements(test::perpendicular_unit_squares().input(), 0.0f);
    double previous = 1.0;
    for (int n : {16, 64, 256}) {
        const double error = std::abs(point_factor(r.elements, 0, 1, n) - kPerpendicularPoint);
        std::printf("perpendicular point, res %d: error %.2e\n", n, error);
        EXPECT_LT(error, previous);
        previous = error;
    }
    EXPECT_LT(previous, 2e-3 * kPerpendicularPoint);
}

TEST(Hemicube, BackFacesOccludeButAreCreditedToNobody) {
    test::SceneArrays s = test::opposed_unit_squares(1.0f);
    // A square between them facing the emitter: the receiver sees its back side.
    s.add_quad({-1, -1, 0.5f}, {2, -1, 0.5f}, {2, 2, 0.5f}, {-1, 2, 0.5f}, Rgb(0.5));
    const BuildResult r = build_elements(s.input(), 0.0f);
    Hemicube hemicube(CubeWeights::make(32));
    hemicube.render_hemisphere(r.elements, r.elements.centre[1], r.elements.normal[1], 1);
    SparseRow row;
    hemicube.accumulate(hemicube.weights().form_factor, row);
    EXPECT_TRUE(row.col.empty());
    // Seen from the emitter, the same square faces it and hides the receiver.
    hemicube.render_hemisphere(r.elements, r.elements.centre[0], r.elements.normal[0], 0);
    hemicube.accumulate(hemicube.weights().form_factor, row);
    ASSERT_EQ(row.col.size(), 1u);
    EXPECT_EQ(row.col[0], 2);
}

TEST(Hemicube, SubdividedClosedBoxCoversEveryCellOfTheSphere) {
    // Watertight: shared edges inside and between polygons leave no cell uncovered.
    const BuildResult r = build_elements(test::closed_box(Vec3(1, 2, 3), Rgb(0.5), Rgb(0)).input(), 0.3f);
    Hemicube hemicube(CubeWeights::make(64));
    for (const Vec3 eye : {Vec3(0.5f, 1.0f, 1.5f), Vec3(0.1f, 0.2f, 2.9f), Vec3(0.9f, 1.9f, 0.05f)}) {
        hemicube.render_sphere(r.elements, eye, -1);
        const auto& items = hemicube.item_buffer();
        ASSERT_EQ(items.size(), 6u * 64u * 64u);
        for (std::size_t cell = 0; cell < items.size(); ++cell) ASSERT_GE(items[cell], 0) << "cell " << cell;
        SparseRow row;
        hemicube.accumulate(hemicube.weights().solid_angle, row);
        EXPECT_NEAR(std::accumulate(row.val.begin(), row.val.end(), 0.0), 4.0 * M_PI, 1e-5);
    }
}

TEST(Hemicube, CellDirectionsPointAtTheElementsTheySee) {
    const BuildResult r = build_elements(test::closed_box(Vec3(1), Rgb(0.5), Rgb(0)).input(), 0.0f);
    Hemicube hemicube(CubeWeights::make(16));
    const Vec3 eye(0.3f, 0.6f, 0.45f);
    for (bool sphere : {true, false}) {
        if (sphere)
            hemicube.render_sphere(r.elements, eye, -1);
        else
            hemicube.render_hemisphere(r.elements, eye, glm::normalize(Vec3(1, 2, -0.5f)), -1);
        const auto& items = hemicube.item_buffer();
        for (std::size_t cell = 0; cell < items.size(); ++cell) {
            ASSERT_GE(items[cell], 0);
            // Walk along the direction to the wall it hits first; that wall must be the item.
            const Vec3 d = hemicube.cell_direction(cell);
            const Vec3 n = r.elements.normal[items[cell]];
            const float t = glm::dot(r.elements.centre[items[cell]] - eye, n) / glm::dot(d, n);
            const Vec3 hit = eye + t * d;
            for (int k = 0; k < 3; ++k) {
                EXPECT_GE(hit[k], -1e-4f);
                EXPECT_LE(hit[k], 1.0f + 1e-4f);
            }
        }
    }
}
