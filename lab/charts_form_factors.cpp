/// @file charts_form_factors.cpp
/// @brief Chart 1 and the aliasing chart: form-factor error against time per row.
///
/// Every case is one element per polygon, so "hemicube" is the classic centre-point value (Cohen & Greenberg 1985) and
/// "near_field" the corrected row. Time is per row on one thread (render, accumulate, correct),
/// repeated until 50 ms have passed.
#include "charts.h"

#include "testing/test_util.h"
#include "transport/near_field.h"
#include "transport/row_renderer.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>
#include <functional>

namespace radiosity::charts {
namespace {

/// Howell B-3: point to a parallel rectangle a x b at height c, the normal through a corner.
double point_to_parallel_corner(double a, double b, double c) {
    const double X = a / c, Y = b / c;
    return (X / std::sqrt(1 + X * X) * std::atan(Y / std::sqrt(1 + X * X)) +
            Y / std::sqrt(1 + Y * Y) * std::atan(X / std::sqrt(1 + Y * Y))) /
           (2 * M_PI);
}

struct Case {
    const char* name;
    test::SceneArrays scene;
    int32_t from, to;
    double exact;
    bool area;  ///< exact is area-to-area: the near-field correction applies
};

std::vector<Case> cases() {
    // A 1 cm square 10 cm under the centre of a 2 m square: F_small->large is the point value
    // (uniform over the patch to 1e-6), F_large->small follows by reciprocity.
    test::SceneArrays under;
    under.add_quad({-1, -1, 0.1f}, {-1, 1, 0.1f}, {1, 1, 0.1f}, {1, -1, 0.1f}, Rgb(0.5), Rgb(1.0));
    under.add_quad({-0.005f, -0.005f, 0}, {0.005f, -0.005f, 0}, {0.005f, 0.005f, 0}, {-0.005f, 0.005f, 0}, Rgb(0.5),
                   Rgb(0));
    const double F_sl = 4 * point_to_parallel_corner(1, 1, 0.1);
    return {
        {"opposed_point", test::opposed_unit_squares(1.0f), 1, 0, 0.239456, false},
        {"perpendicular_point", test::perpendicular_unit_squares(), 0, 1, 0.190136, false},
        {"small_under_large", under, 1, 0, F_sl, false},
        {"opposed_area", test::opposed_unit_squares(1.0f), 1, 0, 0.1998249, true},
        {"perpendicular_area", test::perpendicular_unit_squares(), 0, 1, 0.2000438, true},
        {"large_over_small_area", under, 0, 1, 1e-4 * F_sl / 4.0, true},
    };
}

/// Seconds per call of `row`, repeated until 50 ms have passed.
double time_per_call(const std::function<void()>& row) {
    int calls = 0;
    const auto start = std::chrono::steady_clock::now();
    do {
        row();
        ++calls;
    } while (seconds_since(start) < 0.05);
    return seconds_since(start) / calls;
}

double entry(const SparseRow& row, int32_t j) {
    for (std::size_t k = 0; k < row.col.size(); ++k)
        if (row.col[k] == j) return row.val[k];
    return 0.0;
}

}  // namespace

void form_factors(const std::string& csv_path) {
    FILE* out = std::fopen(csv_path.c_str(), "w");
    std::fprintf(out, "case,method,resolution,seconds_per_row,value,exact,relative_error\n");
    for (const Case& c : cases()) {
        const Elements e = build_elements(c.scene.input(), 0.0f).elements;
        for (int n : {32, 64, 128, 256, 512, 1024})
            for (bool near : {false, true}) {
                if (near && !c.area) continue;
                RowSettings settings;
                settings.resolution = n;
                settings.near_field.enabled = near;
                RowRenderer renderer(CubeWeights::make(n), settings);
                SparseRow row;
                const double seconds = time_per_call([&] { renderer.row(e, c.from, row); });
                const double value = entry(row, c.to);
                std::fprintf(out, "%s,%s,%d,%.6e,%.9g,%.9g,%.6e\n", c.name, near ? "near_field" : "hemicube", n,
                             seconds, value, c.exact, value / c.exact - 1.0);
            }
    }
    std::fclose(out);
}

void aliasing(const std::string& csv_path) {
    // A 10 cm receiver facing up and a square patch facing it from 1 m, in 64 directions spread
    // over the hemisphere (as test_stability_aliasing.cpp); RMS of the relative error.
    FILE* out = std::fopen(csv_path.c_str(), "w");
    std::fprintf(out, "patch_side,rotations,resolution,seconds_per_row,rms_relative_error,max_relative_error\n");
    for (float side : {0.01f, 0.03f})
        for (int rotations : {1, 4})
            for (int n : {32, 64, 128, 256, 512, 1024}) {
                RowSettings settings;
                settings.resolution = n;
                settings.rotations = rotations;
                RowRenderer renderer(CubeWeights::make(n), settings);
                SparseRow row;
                double sum = 0.0, worst = 0.0, seconds = 0.0;
                for (int p = 0; p < 64; ++p) {
                    const double azimuth = 2 * M_PI * std::fmod(p * 0.6180339887, 1.0),
                                 elevation = 0.2 + 1.2 * (p + 0.5) / 64;
                    const glm::dvec3 c(std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                                       std::sin(elevation));
                    const glm::dvec3 u = glm::normalize(glm::cross(-c, glm::dvec3(0.3, 0.5, 0.7))),
                                     v = glm::cross(-c, u);
                    const double h = side / 2.0;
                    auto at = [&](double a, double b) { return Vec3(c + a * u + b * v); };
                    test::SceneArrays s;
                    s.add_quad({-0.05f, -0.05f, 0}, {0.05f, -0.05f, 0}, {0.05f, 0.05f, 0}, {-0.05f, 0.05f, 0}, Rgb(0.5),
                               Rgb(0));
                    s.add_quad(at(-h, -h), at(h, -h), at(h, h), at(-h, h), Rgb(0.5), Rgb(0));
                    const Elements e = build_elements(s.input(), 0.0f).elements;
                    glm::dvec3 q[4];
                    for (int k = 0; k < 4; ++k) q[k] = glm::dvec3(e.vertices[e.corners[1][k]]);
                    const double exact = point_to_polygon(glm::dvec3(e.centre[0]), glm::dvec3(e.normal[0]), q, 4,
                                                          glm::dvec3(e.normal[1]));
                    const auto start = std::chrono::steady_clock::now();
                    renderer.row(e, 0, row);
                    seconds += seconds_since(start);
                    const double error = entry(row, 1) / exact - 1.0;
                    sum += error * error;
                    worst = std::max(worst, std::abs(error));
                }
                std::fprintf(out, "%g,%d,%d,%.6e,%.6e,%.6e\n", double(side), rotations, n, seconds / 64,
                             std::sqrt(sum / 64), worst);
            }
    std::fclose(out);
}

}  // namespace radiosity::charts
