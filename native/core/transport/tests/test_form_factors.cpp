/// @file test_form_factors.cpp
/// @brief Form-factor matrices: area-to-area closed forms, row sums and reciprocity, progress and cancel.

#include "testing/test_util.h"
#include "transport/form_factors.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>

using namespace radiosity;

namespace {

// Exact area-to-area values (Howell's catalogue).
constexpr double kOpposedArea = 0.19982;        // opposed unit squares 1 m apart
constexpr double kPerpendicularArea = 0.20004;  // perpendicular unit squares with a common edge

/// Area-weighted mean over the elements of polygon `from` of their factors to polygon `to`:
/// the area-to-area factor, gathered with one hemi-cube per element.
double area_factor(const Elements& e, const SparseMatrix& f, int32_t from, int32_t to) {
    double flux = 0.0, area = 0.0;
    for (std::size_t i = 0; i < e.size(); ++i) {
        if (e.polygon[i] != from) continue;
        area += e.area[i];
        for (int64_t k = f.row_start[i]; k < f.row_start[i + 1]; ++k)
            if (e.polygon[f.col[k]] == to) flux += e.area[i] * f.val[k];
    }
    return flux / area;
}

/// Subdivides polygon `gather` into k x k elements and keeps every other polygon one element.
Elements gather_split(const test::SceneArrays& scene, int32_t gather, int k) {
    const SceneInput in = scene.input();
    Elements fine = build_elements(in, 1.0f / k).elements, coarse = build_elements(in, 0.0f).elements, out;
    for (const Elements* part : {&fine, &coarse}) {
        const auto offset = static_cast<int32_t>(out.vertices.size());
        out.vertices.insert(out.vertices.end(), part->vertices.begin(), part->vertices.end());
        for (std::size_t i = 0; i < part->size(); ++i) {
            if ((part->polygon[i] == gather) != (part == &fine)) continue;
            auto c = part->corners[i];
            for (int32_t& v : c) v = v < 0 ? v : v + offset;
            out.corners.push_back(c);
            out.centre.push_back(part->centre[i]);
            out.normal.push_back(part->normal[i]);
            out.area.push_back(part->area[i]);
            out.polygon.push_back(part->polygon[i]);
            out.reflectance.push_back(part->reflectance[i]);
            out.emission.push_back(part->emission[i]);
        }
    }
    return out;
}

/// |error| of the area factor for k x k gathering elements at resolution n.
double area_error(const test::SceneArrays& scene, int32_t gather, int32_t to, double exact, int k, int n) {
    const Elements e = gather_split(scene, gather, k);
    return std::abs(area_factor(e, compute_form_factors(e, n), gather, to) - exact);
}

}  // namespace

TEST(FormFactors, OpposedSquaresAreaToAreaConverges) {
    const test::SceneArrays scene = test::opposed_unit_squares(1.0f);
    double previous = 1.0;
    for (auto [k, n] : {std::pair{2, 32}, {4, 64}, {16, 256}}) {
        const double error = area_error(scene, 1, 0, kOpposedArea, k, n);
        std::printf("opposed area, %dx%d elements, res %d: error %.2e\n", k, k, n, error);
        EXPECT_LT(error, previous);
        previous = error;
    }
    EXPECT_LT(previous, 1e-3 * kOpposedArea);  // measured 6e-4 relative
}

TEST(FormFactors, PerpendicularSquaresAreaToAreaConverges) {
    const test::SceneArrays scene = test::perpendicular_unit_squares();
    double previous = 1.0;
    for (auto [k, n] : {std::pair{2, 32}, {4, 64}, {16, 256}}) {
        const double error = area_error(scene, 0, 1, kPerpendicularArea, k, n);
        std::printf("perpendicular area, %dx%d elements, res %d: error %.2e\n", k, k, n, error);
        EXPECT_LT(error, previous);
        previous = error;
    }
    EXPECT_LT(previous, 1e-3 * kPerpendicularArea);  // measured 4e-4 relative
}

TEST(FormFactors, ClosedBoxRowsSumToOneAndAreReciprocal) {
    // Inside a closed box every cell sees some element, so each row sums to the sum of the delta
    // form factors, 1, up to float rounding.
    // Reciprocity: a hemi-cube at the element centre measures the point-to-element factor, not
    // the element-to-element one, so A_i F_ij = A_j F_ji holds only up to that near-field error
    // (largest for neighbours at a corner, and independent of scale). Resolution removes the
    // sampling part of the mismatch: it falls towards the centre-point limit, measured as 0.0108
    // at resolution 1024 for these 0.5 m elements (the pair at a corner of the floor and wall).
    const Elements e = build_elements(test::closed_box(Vec3(1, 2, 1.5f), Rgb(0.5), Rgb(0)).input(), 0.5f).elements;
    double previous = 1.0;
    for (int n : {16, 64, 256}) {
        const SparseMatrix f = compute_form_factors(e, n);
        ASSERT_EQ(f.rows(), e.size());
        for (std::size_t i = 0; i < e.size(); ++i) {
            const double sum = std::accumulate(f.val.begin() + f.row_start[i], f.val.begin() + f.row_start[i + 1], 0.0);
            ASSERT_NEAR(sum, 1.0, 1e-5) << "row " << i;
            ASSERT_TRUE(std::is_sorted(f.col.begin() + f.row_start[i], f.col.begin() + f.row_start[i + 1]));
        }
        std::vector<std::vector<double>> dense(e.size(), std::vector<double>(e.size(), 0.0));
        for (std::size_t i = 0; i < e.size(); ++i)
            for (int64_t k = f.row_start[i]; k < f.row_start[i + 1]; ++k) dense[i][f.col[k]] = f.val[k];
        double worst = 0.0;  // max |A_i F_ij - A_j F_ji| / A_i (all elements have equal areas here)
        for (std::size_t i = 0; i < e.size(); ++i)
            for (std::size_t j = i + 1; j < e.size(); ++j)
                worst = std::max(worst, std::abs(e.area[i] * dense[i][j] - e.area[j] * dense[j][i]) / e.area[i]);
        std::printf("closed box, res %d: worst reciprocity mismatch %.4f\n", n, worst);
        EXPECT_LT(worst, previous);
        previous = worst;
    }
    EXPECT_LT(previous, 0.0115);  // measured 0.0111 at 256, limit 0.0108
}

TEST(FormFactors, StoredAndOnDemandRowsAgree) {
    const Elements e = build_elements(test::cornell_box().input(), 0.25f).elements;
    const SparseMatrix f = compute_form_factors(e, 32);
    StoredRows stored(f);
    HemicubeRows rendered(e, 32);
    SparseRow a, b;
    for (int32_t i = 0; i < static_cast<int32_t>(e.size()); ++i) {
        stored.row(i, a);
        rendered.row(i, b);
        ASSERT_EQ(a.col, b.col);
        ASSERT_EQ(a.val, b.val);
    }
}

TEST(FormFactors, ReportsProgressAndCancels) {
    const Elements e = build_elements(test::cornell_box().input(), 0.2f).elements;
    std::size_t calls = 0, last = 0;
    bool ordered = true;
    compute_form_factors(e, 16, [&](const Progress& p) {
        ordered = ordered && std::string(p.phase) == "form_factors" && p.total == e.size() && p.done <= p.total;
        last = p.done;
        ++calls;
        return true;
    });
    EXPECT_TRUE(ordered);
    EXPECT_EQ(last, e.size());
    EXPECT_GE(calls, 50u);
    EXPECT_LE(calls, 102u);

    std::size_t calls_after_cancel = 0;
    bool cancelled = false;
    EXPECT_THROW(compute_form_factors(e, 16,
                                      [&](const Progress&) {
                                          if (cancelled) ++calls_after_cancel;
                                          cancelled = true;
                                          return false;
                                      }),
                 Cancelled);
    EXPECT_LE(calls_after_cancel, 2u);  // at most a report already under way on another thread
}
