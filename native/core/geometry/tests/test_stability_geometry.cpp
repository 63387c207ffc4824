/// @file test_stability_geometry.cpp
/// @brief Thin slivers and coplanar overlapping faces: measured errors (intersections:
/// test_stability_intersections.cpp).

#include "bake/bake.h"
#include "testing/test_util.h"
#include "transport/near_field.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace radiosity;

namespace {

BakeSettings settings(float element_size) {
    BakeSettings s;
    s.element_size = element_size;
    s.resolution = 256;
    s.solve.tolerance = 1e-8;
    return s;
}

}  // namespace

TEST(Slivers, AspectSplitFollowsTheLightAlongASliver) {
    // A 1 m x 1 cm strip on the floor under a 20 cm emitter above one end: irradiance varies along
    // the strip, which one element per polygon (aspect 100) samples only at its middle. Truth:
    // each element's area factor to the emitter (Lambert, 8 x 8 Gauss points; no occluders).
    test::SceneArrays scene;
    scene.add_quad({0.0f, 0.1f, 0.3f}, {0.0f, 0.3f, 0.3f}, {0.2f, 0.3f, 0.3f}, {0.2f, 0.1f, 0.3f}, Rgb(0), Rgb(1.0));
    scene.add_quad({0.0f, 0.195f, 0.0f}, {1.0f, 0.195f, 0.0f}, {1.0f, 0.205f, 0.0f}, {0.0f, 0.205f, 0.0f}, Rgb(0.5),
                   Rgb(0));
    for (float aspect : {0.0f, 4.0f}) {
        BakeSettings s = settings(0.0f);
        s.limits.max_aspect = aspect;
        const BakeResult r = bake(scene.input(), s);
        const double worst = test::worst_direct_light_error(r, 0.5);
        std::printf("sliver, max aspect %.0f: %zu elements, worst element error %.3f of the peak radiance\n", aspect,
                    test::front_count(r.build.elements) - 1, worst);
        if (aspect == 0.0f)
            EXPECT_GT(worst, 0.5);  // measured
        else
            EXPECT_LT(worst, 0.05);  // measured
    }
}

TEST(Coplanar, OverlappingFacesResolveTheTieOneWay) {
    // Two emitters in one plane overlapping on [0.5, 1] x [0, 1]: red (index 0) and green. Where
    // they overlap the z-buffer holds equal depths up to rounding; the receiver below must see one
    // of them there, not a speckle of both. Measured: how much of the overlap goes to each.
    test::SceneArrays scene;
    scene.add_quad({0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}, Rgb(0), Rgb(1, 0, 0));
    scene.add_quad({0.5f, 0, 1}, {0.5f, 1, 1}, {1.5f, 1, 1}, {1.5f, 0, 1}, Rgb(0), Rgb(0, 1, 0));
    scene.add_quad({0.65f, 0.4f, 0}, {0.85f, 0.4f, 0}, {0.85f, 0.6f, 0}, {0.65f, 0.6f, 0}, Rgb(0.5), Rgb(0));
    const BakeResult r = bake(scene.input(), settings(0.0f));
    const Elements& e = r.build.elements;
    // Exact unoccluded factors from the receiver's centre to each emitter and to the overlap.
    auto factor = [&](float x0, float x1) {
        const glm::dvec3 q[4] = {{x0, 0, 1}, {x0, 1, 1}, {x1, 1, 1}, {x1, 0, 1}};
        return point_to_polygon(glm::dvec3(e.centre[2]), glm::dvec3(e.normal[2]), q, 4, glm::dvec3(0, 0, -1));
    };
    const double overlap = factor(0.5f, 1.0f), red_only = factor(0.0f, 0.5f), green_only = factor(1.0f, 1.5f);
    const Rgb L = r.solve.radiance[2] / 0.5;  // = sum_j F_2j E_j
    const double red_share = (L.r - red_only) / overlap, green_share = (L.g - green_only) / overlap;
    std::printf("coplanar overlap seen as red %.4f, green %.4f (sum %.4f)\n", red_share, green_share,
                red_share + green_share);
    EXPECT_NEAR(red_share + green_share, 1.0, 0.01);    // the overlap is counted once
    EXPECT_LT(std::min(red_share, green_share), 0.01);  // and given to one face, not speckled
}
