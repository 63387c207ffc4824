/// @file test_merged_elements.cpp
/// @brief The uniform bake's solve elements chosen by the element size, not the faces
/// (geometry/clusters.h): a box whose walls are finely tessellated solves as many unknowns as the
/// coarse box, its light is the coarse bake's, and it agrees with a dense direct solve over every
/// face and with the gathered bake over every face.
#include "bake/bake.h"

#include "testing/dense_solve.h"
#include "testing/test_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <tuple>

namespace radiosity {
namespace {

constexpr float kSize = 0.25f;  // the element size: 4 x 4 elements a wall
constexpr int kWalls = 5;       // floor, back, front, left, right; the ceiling emits

/// A closed 1 m box: its ceiling one emitting quad (radiance 1), every other wall `cells` x `cells`
/// faces of its own material (id = wall + 1): red left, green right, grey elsewhere.
test::SceneArrays tessellated_box(int cells) {
    test::SceneArrays box;
    const Rgb grey(0.7), red(0.6, 0.1, 0.1), green(0.1, 0.6, 0.1);
    box.add_grid(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), cells, grey, Rgb(0.0), 1);   // floor, +z
    box.add_grid(Vec3(0, 1, 0), Vec3(1, 0, 0), Vec3(0, 0, 1), cells, grey, Rgb(0.0), 2);   // back, -y
    box.add_grid(Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(1, 0, 0), cells, grey, Rgb(0.0), 3);   // front, +y
    box.add_grid(Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), cells, red, Rgb(0.0), 4);    // left, +x
    box.add_grid(Vec3(1, 0, 0), Vec3(0, 0, 1), Vec3(0, 1, 0), cells, green, Rgb(0.0), 5);  // right, -x
    box.add_quad({0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}, Rgb(0.0), Rgb(1.0), 0);       // ceiling, -z
    return box;
}

BakeSettings settings(bool merge, bool gather) {
    BakeSettings s;
    s.element_size = kSize;
    s.resolution = 64;
    s.solve.tolerance = 1e-8;
    s.merge_elements = merge;
    s.final_gather.enabled = gather;
    s.final_gather.rays = 1024;
    s.final_gather.field_rays = 64;
    return s;
}

/// Each wall's mean radiance by area over the elements of its faces.
std::vector<Rgb> wall_means(const test::SceneArrays& box, const Elements& elements, const std::vector<Rgb>& radiance) {
    std::vector<Rgb> power(kWalls + 1, Rgb(0.0));
    std::vector<double> area(kWalls + 1, 0.0);
    for (std::size_t e = 0; e < elements.size(); ++e) {
        if (elements.is_back(e)) continue;
        const std::size_t wall = std::size_t(box.material[std::size_t(elements.polygon[e])]);
        power[wall] += double(elements.area[e]) * radiance[e];
        area[wall] += double(elements.area[e]);
    }
    for (std::size_t w = 0; w <= kWalls; ++w) power[w] /= area[w];
    return power;
}

double worst_wall_error(const std::vector<Rgb>& means, const std::vector<Rgb>& truth) {
    double worst = 0.0;
    for (int w = 1; w <= kWalls; ++w)
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(means[w][c] / truth[w][c] - 1.0));
    return worst;
}

/// The output's colour at each (position, wall) of the input corners.
using CornerKey = std::tuple<float, float, float, int32_t>;
std::map<CornerKey, Rgb> corner_colours(const test::SceneArrays& box, const BakeResult& r) {
    std::map<CornerKey, Rgb> out;
    for (std::size_t f = 0; f + 1 < box.face_offsets.size(); ++f)
        for (int32_t c = box.face_offsets[f]; c < box.face_offsets[f + 1]; ++c) {
            const float* p = &box.positions[3 * std::size_t(box.corner_vertices[std::size_t(c)])];
            out[{p[0], p[1], p[2], box.material[f]}] = r.colors.input_corner[std::size_t(c)];
        }
    return out;
}

/// The RMS and worst relative difference of `colours` from `truth`'s at truth's corners (green,
/// the channel every wall reflects), walls only.
std::pair<double, double> corner_difference(const std::map<CornerKey, Rgb>& colours,
                                            const std::map<CornerKey, Rgb>& truth) {
    double sum = 0.0, worst = 0.0;
    int count = 0;
    for (const auto& [key, value] : truth) {
        if (std::get<3>(key) == 0) continue;
        const auto found = colours.find(key);
        EXPECT_NE(found, colours.end());
        if (found == colours.end()) continue;
        const double d = found->second.g / value.g - 1.0;
        sum += d * d;
        worst = std::max(worst, std::abs(d));
        ++count;
    }
    return {std::sqrt(sum / count), worst};
}

TEST(MergedElements, TessellatedBoxSolvesTheCoarseBoxsUnknowns) {
    // 4 x 4 elements a wall and the ceiling's 16, front and back, at every density; and the same
    // light: the clusters are the coarse box's elements, so each wall's mean is the coarse bake's.
    const test::SceneArrays coarse = tessellated_box(4);
    const BakeResult reference = bake(coarse.input(), settings(true, false));
    ASSERT_EQ(reference.solve_elements, std::size_t(kWalls * 16 + 2 * 16));
    ASSERT_EQ(reference.build.elements.size(), reference.solve_elements);
    const std::vector<Rgb> reference_means = wall_means(coarse, reference.build.elements, reference.solve.radiance);
    for (const int cells : {8, 16, 32}) {
        const test::SceneArrays box = tessellated_box(cells);
        // The solve's progress shows its light on the output's elements, which plan() gives a preview.
        const std::size_t planned = plan(box.input(), settings(true, false)).build.elements.size();
        std::size_t reports = 0;
        const ProgressFn progress = [&](const Progress& p) {
            if (p.radiance != nullptr) {
                EXPECT_EQ(p.element_count, planned);
                ++reports;
            }
            return true;
        };
        BakeSettings progressive = settings(true, false);
        progressive.solve.method = Method::Progressive;
        bake(box.input(), progressive, progress);
        EXPECT_GT(reports, 0u);
        const BakeResult r = bake(box.input(), settings(true, false));
        EXPECT_EQ(r.solve_elements, reference.solve_elements) << cells;
        EXPECT_EQ(r.build.elements.size(), std::size_t(kWalls * cells * cells + 2 * 16)) << cells;
        const double error = worst_wall_error(wall_means(box, r.build.elements, r.solve.radiance), reference_means);
        std::printf("%d faces a wall edge: %zu output elements, %zu solved, walls' means %.2e from the coarse bake's\n",
                    cells, r.build.elements.size(), r.solve_elements, error);
        EXPECT_LT(error, 1e-5) << cells;
    }
}

TEST(MergedElements, TessellatedBoxAgreesWithTheDenseSolveOverEveryFace) {
    // Truth: the dense direct solve of the hemi-cube matrix over every face of the 16 x 16 box
    // (elements 4 x 4 times smaller than the merged ones). The merged bake's walls differ from it
    // by what elements of the element size resolve, exactly as the coarse bake's do, and within
    // Medium's error target (1.5%).
    const test::SceneArrays box = tessellated_box(16);
    const BakeResult unmerged = bake(box.input(), settings(false, false));
    const Elements& faces = unmerged.build.elements;
    const std::vector<Rgb> truth = test::direct_solve(faces, test::dense(compute_form_factors(faces, 64)));
    ASSERT_LT(test::max_relative_error(unmerged.solve.radiance, truth), 1e-5);
    const std::vector<Rgb> truth_means = wall_means(box, faces, truth);

    const BakeResult merged = bake(box.input(), settings(true, false));
    const double merged_error =
        worst_wall_error(wall_means(box, merged.build.elements, merged.solve.radiance), truth_means);
    const test::SceneArrays coarse = tessellated_box(4);
    const BakeResult coarse_bake = bake(coarse.input(), settings(true, false));
    const double coarse_error =
        worst_wall_error(wall_means(coarse, coarse_bake.build.elements, coarse_bake.solve.radiance), truth_means);
    std::printf("walls' means against the dense solve over %zu faces: merged %.3f%%, coarse box %.3f%%\n", faces.size(),
                100.0 * merged_error, 100.0 * coarse_error);
    EXPECT_LT(merged_error, 0.015);
    EXPECT_NEAR(merged_error, coarse_error, 1e-5);
}

TEST(MergedElements, GatheredCornersMatchTheBakeOverEveryFace) {
    // With the final gather, what the artist sees: the corners of the 16 x 16 box merged against the
    // same box solved over every face, and against the coarse box at its own corners.
    const test::SceneArrays box = tessellated_box(16), coarse = tessellated_box(4);
    const BakeResult merged = bake(box.input(), settings(true, true));
    const BakeResult unmerged = bake(box.input(), settings(false, true));
    const BakeResult coarse_bake = bake(coarse.input(), settings(true, true));
    const auto [rms, worst] = corner_difference(corner_colours(box, merged), corner_colours(box, unmerged));
    const auto [coarse_rms, coarse_worst] =
        corner_difference(corner_colours(box, merged), corner_colours(coarse, coarse_bake));
    std::printf(
        "gathered corners, merged (%zu unknowns) against every face (%zu): RMS %.3f%%, worst %.3f%%; "
        "against the coarse box at its corners: RMS %.3f%%, worst %.3f%%\n",
        merged.solve_elements, unmerged.solve_elements, 100.0 * rms, 100.0 * worst, 100.0 * coarse_rms,
        100.0 * coarse_worst);
    EXPECT_LT(rms, 0.005);
    EXPECT_LT(worst, 0.015);
    EXPECT_LT(coarse_rms, 0.005);
}

}  // namespace
}  // namespace radiosity
