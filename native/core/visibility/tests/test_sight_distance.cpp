/// @file test_sight_distance.cpp
/// @brief sight_distance against Cauchy's mean chord 4 V / S of closed boxes, and its independence
/// of a corridor's length, where half the bounding box's diagonal follows the length.
#include "geometry/scene.h"
#include "testing/test_util.h"
#include "visibility/sight_distance.h"

#include <gtest/gtest.h>

#include <cstdio>

namespace radiosity {
namespace {

Elements box_elements(const Vec3& size, float element_size) {
    return build_elements(test::closed_box(size, Rgb(0.5), Rgb(0.0)).input(), element_size).elements;
}

double mean_chord(const Vec3& size) {
    const double volume = size.x * size.y * size.z;
    const double surface = 2.0 * (size.x * size.y + size.y * size.z + size.z * size.x);
    return 4.0 * volume / surface;
}

TEST(SightDistance, MeanChordOfClosedBoxesIsCauchys) {
    SightSettings mean;  // every chord, not their power mean
    mean.exponent = 1.0;
    mean.skip_near_hits = false;
    for (const Vec3 size : {Vec3(1, 1, 1), Vec3(1, 2, 3), Vec3(0.2f, 3, 3)}) {
        const double sampled = sight_distance(box_elements(size, 0.1f), mean);
        std::printf("box %g x %g x %g: mean hit distance %.4f, 4 V / S %.4f\n", size.x, size.y, size.z, sampled,
                    mean_chord(size));
        // 4,096 rays: the chords' spread is about their mean, so 3 standard errors are about 5%;
        // the stratified sample does better.
        EXPECT_NEAR(sampled / mean_chord(size), 1.0, 0.02);
    }
}

TEST(SightDistance, CorridorKeepsItsWidthNotItsLength) {
    const Elements shorter = box_elements(Vec3(2, 2, 10), 0.25f), longer = box_elements(Vec3(2, 2, 40), 0.25f);
    const double d10 = sight_distance(shorter), d40 = sight_distance(longer);
    std::printf("2 x 2 m corridor: sight distance %.3f m at 10 m long, %.3f m at 40 m (half diagonals %.2f, %.2f)\n",
                d10, d40, half_diagonal(shorter), half_diagonal(longer));
    // The power mean weighs the long chords along the corridor a little more than Cauchy's mean
    // (1.82 and 1.95 m), and so does leaving out the chords shorter than an element (at the corners);
    // it stays near the width while the half diagonal grows fourfold.
    EXPECT_GT(d10, mean_chord(Vec3(2, 2, 10)));
    EXPECT_LT(d40, 1.5 * d10);
    EXPECT_LT(d40, 0.2 * half_diagonal(longer));
}

TEST(SightDistance, NothingSeenFallsBackToHalfTheDiagonal) {
    test::SceneArrays plane;
    plane.add_quad({0, 0, 0}, {3, 0, 0}, {3, 4, 0}, {0, 4, 0}, Rgb(0.5));
    const Elements elements = build_elements(plane.input(), 0.5f).elements;
    EXPECT_DOUBLE_EQ(sight_distance(elements), 2.5);
    EXPECT_DOUBLE_EQ(sight_distance(Elements()), 0.0);
}

}  // namespace
}  // namespace radiosity
