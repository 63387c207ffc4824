/// @file test_kept_direct_light.cpp
/// @brief The gather's direct light kept per source (kept_direct_light.h): a value is made once per
/// point and signature, read after, let go when a bake does not use it, and kept within the budget.
#include "output/kept_direct_light.h"

#include <gtest/gtest.h>

namespace radiosity {
namespace {

const Vec3 kX(0.5f, 0.25f, 0.0f), kNormal(0.0f, 0.0f, 1.0f);

/// The light of `signature` at kX through `kept`, counting the times it is made.
Rgb light_at(KeptDirectLight& kept, uint64_t signature, const Rgb& made, int& computed, uint32_t seed = 7) {
    KeptDirectLight::Point point(&kept, kX, kNormal, seed);
    const Rgb light = point.light(signature, [&] {
        ++computed;
        return made;
    });
    point.finish();
    return light;
}

TEST(KeptDirectLight, AValueIsMadeOnceAPointAndSignature) {
    KeptDirectLight kept(1 << 20);
    int computed = 0;
    EXPECT_EQ(light_at(kept, 1, Rgb(0.5), computed), Rgb(0.5));
    EXPECT_EQ(light_at(kept, 1, Rgb(9.0), computed), Rgb(0.5));  // read, not made again
    EXPECT_EQ(computed, 1);
    EXPECT_EQ(light_at(kept, 2, Rgb(0.25), computed), Rgb(0.25));   // another source
    EXPECT_EQ(light_at(kept, 1, Rgb(9.0), computed, 8), Rgb(9.0));  // another seed: another point
    EXPECT_EQ(computed, 3);
    EXPECT_GT(kept.bytes(), 0u);
}

TEST(KeptDirectLight, WhatABakeDidNotUseIsLetGo) {
    KeptDirectLight kept(1 << 20);
    int computed = 0;
    light_at(kept, 1, Rgb(0.5), computed);
    light_at(kept, 2, Rgb(0.5), computed);
    const std::size_t both = kept.bytes();
    kept.begin_bake();
    light_at(kept, 1, Rgb(0.5), computed);  // the lamp of signature 2 moved away
    kept.prune();
    EXPECT_LT(kept.bytes(), both);
    light_at(kept, 2, Rgb(0.5), computed);
    EXPECT_EQ(computed, 3);
    kept.begin_bake();
    kept.prune();
    EXPECT_EQ(kept.bytes(), 0u);
}

TEST(KeptDirectLight, NothingIsKeptBeyondTheBudget) {
    KeptDirectLight kept(16);
    int computed = 0;
    EXPECT_EQ(light_at(kept, 1, Rgb(0.5), computed), Rgb(0.5));
    EXPECT_EQ(light_at(kept, 1, Rgb(0.5), computed), Rgb(0.5));
    EXPECT_EQ(computed, 2);
    EXPECT_TRUE(kept.full());
    EXPECT_EQ(kept.bytes(), 0u);
}

TEST(KeptDirectLight, LampsDifferingInAnyParameterHaveOtherSignatures) {
    Lights lights;
    PointLight lamp;
    lamp.position = Vec3(1.0f, 2.0f, 3.0f);
    lamp.intensity = Rgb(1.0);
    lights.points = {lamp, lamp};
    lights.points[1].radius = 0.1f;
    SunLight sun;
    lights.suns = {sun};
    const SourceSignatures s = source_signatures(lights, WorldLight::uniform(Rgb(0.2)));
    ASSERT_EQ(s.lamps.size(), 3u);
    EXPECT_NE(s.lamps[0][0], s.lamps[0][1]);
    EXPECT_NE(s.lamps[0][1], s.lamps[1][1]);
    EXPECT_NE(s.lamps[1][1], s.lamps[2][1]);
    EXPECT_NE(s.world, source_signatures(lights, WorldLight::uniform(Rgb(0.3))).world);
    lights.points[0].intensity = Rgb(2.0);
    EXPECT_NE(source_signatures(lights, WorldLight()).lamps[0][1], s.lamps[0][1]);
}

}  // namespace
}  // namespace radiosity
