/// @file test_kept_first_shot.cpp
/// @brief The lamps' first shot kept lamp by lamp (kept_first_shot.h): a lamp's light on an element
/// is traced once and read by later bakes under the same signature, traced again under another,
/// and let go when a bake did not use it.
#include "bake/kept_first_shot.h"

#include <gtest/gtest.h>

namespace radiosity::detail {
namespace {

TEST(KeptFirstShot, ALampsLightIsTracedOnceAndLetGoWhenNotUsed) {
    KeptFirstShot kept;
    int traced = 0;
    auto light = [&](double value) {
        return [&traced, value] {
            ++traced;
            return Rgb(value);
        };
    };
    kept.begin_bake(3);
    EXPECT_EQ(kept.light(0, 11, light(1.5)), Rgb(1.5));
    EXPECT_EQ(kept.light(2, 11, light(2.5)), Rgb(2.5));
    EXPECT_EQ(kept.light(2, 12, light(3.5)), Rgb(3.5));
    EXPECT_EQ(traced, 3);
    kept.prune();
    const std::size_t three = kept.bytes();
    EXPECT_GT(three, 0u);

    // The next bake: lamp 11 unchanged is read, lamp 12 moved (a new signature 13) is traced.
    kept.begin_bake(3);
    EXPECT_EQ(kept.light(0, 11, light(9.0)), Rgb(1.5));
    EXPECT_EQ(kept.light(2, 11, light(9.0)), Rgb(2.5));
    EXPECT_EQ(kept.light(2, 13, light(4.5)), Rgb(4.5));
    EXPECT_EQ(traced, 4);
    kept.prune();
    EXPECT_EQ(kept.bytes(), three);  // lamp 12's old light let go

    // Other elements (another geometry): nothing is read.
    kept.begin_bake(2);
    EXPECT_EQ(kept.light(0, 11, light(5.5)), Rgb(5.5));
    EXPECT_EQ(traced, 5);
    kept.prune();
    EXPECT_LT(kept.bytes(), three);
    kept.clear();
    EXPECT_EQ(kept.bytes(), 0u);
}

}  // namespace
}  // namespace radiosity::detail
