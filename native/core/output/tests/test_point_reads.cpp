/// @file test_point_reads.cpp
/// @brief A point's rays folded into weights (point_reads.h) against the same rays read hit by hit:
/// the sum, the halves' difference, the probe field's read, the rest beside the near reads and the
/// gradients, on elements with wedge tables and an emitter, for any values read.
#include "output/point_reads.h"

#include "geometry/scene.h"
#include "output/corner_blend.h"
#include "testing/test_util.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <random>

namespace radiosity::detail {
namespace {

/// A box of 3 x 3 quads a side, its floor emitting: elements with and without emission.
Elements box_elements() {
    test::SceneArrays box;
    const Vec3 o(0.0f), x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
    box.add_grid(o, y, x, 3, Rgb(0.5), Rgb(0.3, 0.2, 0.1));  // floor, facing +z
    box.add_grid(o, x, z, 3, Rgb(0.6, 0.4, 0.2));            // facing +y
    box.add_grid(o, z, y, 3, Rgb(0.7));                      // facing +x
    return build_elements(box.input(), 0.0f).elements;
}

/// What the hits read, hit by hit, as final_gather.cpp's rays read them.
struct HitByHit {
    Rgb sum{0.0}, rest{0.0}, difference{0.0}, probe{0.0};
    PlaneGradients gradients;
    Rgb wedges{0.0};  ///< what the wedge tables gave, to see that the rays read them
};

HitByHit read_hit_by_hit(const Elements& elements, const ReadValues& values, const RayGrid& grid,
                         const std::vector<RayHit>& hits) {
    HitByHit out;
    std::vector<double> inverse(hits.size(), 0.0);
    std::vector<Rgb> seen(hits.size(), Rgb(0.0));
    for (std::size_t i = 0; i < hits.size(); ++i) {
        const hr::Visibility::Hit& hit = hits[i].hit;
        if (hit.patch < 0) continue;
        inverse[i] = 1.0 / double(hit.distance);
        if (!hits[i].front) continue;
        const std::size_t h = std::size_t(hit.patch);
        const Rgb field = blend_corners(elements, h, &values.field[4 * h], hit.u, hit.v);
        const Rgb wedge = values.wedges->correction(elements, h, hit.u, hit.v);
        seen[i] = field + wedge - values.emitted[h];
        out.wedges += wedge;
        out.sum += seen[i];
        out.difference += half_sign(int(i), grid.grid) * seen[i];
        out.probe += blend_corners(elements, h, &(*values.probe)[4 * h], hit.u, hit.v);
        const bool near = hit.distance < grid.near * std::sqrt(elements.area[h]);
        out.rest += near ? wedge - values.emitted[h] : seen[i];
    }
    const GradientWeights weights = gradient_weights(grid.grid, inverse);
    for (std::size_t i = 0; i < hits.size(); ++i)
        for (std::size_t c = 0; c < 3; ++c) {
            out.gradients.rotation[c] += seen[i][int(c)] * weights.rotation[i];
            out.gradients.translation[c] += seen[i][int(c)] * weights.translation[i];
        }
    return out;
}

void expect_near(const Rgb& folded, const Rgb& truth, double scale, const char* what) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(folded[c], truth[c], 1e-6 * scale) << what << " channel " << c;
}

TEST(PointReads, FoldedReadsGiveWhatTheHitsGiveForAnyValues) {
    const Elements elements = box_elements();
    std::vector<uint8_t> on_seam(elements.vertices.size(), 0);
    for (std::size_t v = 0; v < on_seam.size(); v += 3) on_seam[v] = 1;
    std::mt19937 random(7);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    const CornerWedges wedges(
        elements, on_seam, 1.0f,
        [&](std::size_t, int, const Vec3*, Rgb* table) {
            for (int i = 0; i < CornerWedges::kBins; ++i) table[i] = Rgb(uniform(random), uniform(random), 0.1);
        },
        [](std::size_t count, const auto& body) {
            for (std::size_t i = 0; i < count; ++i) body(i);
        });
    ASSERT_FALSE(wedges.empty());

    const RayGrid grid{48, 0.05f, true};
    std::vector<RayHit> hits(std::size_t(grid.grid * grid.grid));
    // Rays on few elements (as a point's rays land), some near the point, some on backs, some missing.
    for (RayHit& ray : hits) {
        const double pick = uniform(random);
        if (pick < 0.05) continue;  // missed
        ray.hit.patch = int32_t(std::min(double(elements.size()) - 1.0, uniform(random) * 6.0));
        ray.hit.u = float(uniform(random));
        ray.hit.v = float(uniform(random)) * (1.0f - ray.hit.u);
        ray.hit.distance = float(pick < 0.2 ? 0.001 : 0.1 + uniform(random));
        ray.front = pick > 0.1;
    }
    const PointReads reads = fold_reads(elements, elements.emission, &wedges, grid, hits);
    EXPECT_LT(reads.terms.size(), hits.size() / 4);  // many rays, few values

    for (int lighting = 0; lighting < 3; ++lighting) {  // one fold, any lighting
        std::vector<Rgb> field(4 * elements.size()), probe(4 * elements.size()), emitted(elements.size());
        for (Rgb& f : field) f = Rgb(uniform(random), uniform(random), uniform(random));
        for (Rgb& p : probe) p = Rgb(uniform(random) - 0.5);
        for (std::size_t e = 0; e < elements.size(); ++e) emitted[e] = elements.emission[e] * double(lighting);
        const std::vector<Rgb> radiance(elements.size(), Rgb(0.0));
        const ReadValues values{elements, field, radiance, emitted, &wedges, &probe};
        const ReadSums folded = evaluate(reads, values);
        const HitByHit truth = read_hit_by_hit(elements, values, grid, hits);
        const double rays = double(hits.size());
        ASSERT_GT(truth.wedges.r, 0.01 * rays);                // the tables are read
        ASSERT_GT(glm::length(truth.sum - truth.rest), 0.01);  // and the near reads
        expect_near(folded.sum, truth.sum, rays, "sum");
        expect_near(folded.rest, truth.rest, rays, "rest");
        expect_near(folded.difference, truth.difference, rays, "difference");
        expect_near(folded.probe, truth.probe, rays, "probe");
        for (std::size_t c = 0; c < 3; ++c) {
            EXPECT_NEAR(glm::length(folded.gradients.rotation[c] - truth.gradients.rotation[c]), 0.0,
                        1e-5 * glm::length(truth.gradients.rotation[c]));
            EXPECT_NEAR(glm::length(folded.gradients.translation[c] - truth.gradients.translation[c]), 0.0,
                        1e-5 * glm::length(truth.gradients.translation[c]));
        }
    }
}

}  // namespace
}  // namespace radiosity::detail
