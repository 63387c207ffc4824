/// @file test_open_backs.cpp
/// @brief Which faces' backs look into the scene: a bridge of one face over a floor does, a closed
/// room's walls, a closed box's faces and those of a box without a bottom on a floor do not.
#include "geometry/scene.h"
#include "testing/test_util.h"
#include "visibility/open_backs.h"

#include <gtest/gtest.h>

namespace radiosity {
namespace {

TEST(OpenBacks, ABridgeOfOneFaceOverAFloorLooksAtItFromBehind) {
    test::SceneArrays s;
    s.add_quad({0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, Rgb(0.5));  // floor, +z
    s.add_quad({0, 1.5f, 1}, {4, 1.5f, 1}, {4, 2.5f, 1}, {0, 2.5f, 1},
               Rgb(0.5));                                              // bridge, +z: its back over the floor
    s.add_quad({0, 0, 2}, {0, 4, 2}, {4, 4, 2}, {4, 0, 2}, Rgb(0.5));  // ceiling, -z: its back over nothing
    const std::vector<uint8_t> open = open_backs(build_elements(s.input(), 0.5f).elements, 3);
    EXPECT_EQ(open, (std::vector<uint8_t>{0, 1, 0}));
    EXPECT_TRUE(any_open(open));
}

TEST(OpenBacks, AClosedRoomsWallsAndAClosedBoxInItHaveNone) {
    // The room's walls look out into nothing from behind, the box's faces at each other's backs.
    test::SceneArrays s = test::closed_box(Vec3(4, 4, 3), Rgb(0.5), Rgb(0.0));
    const Vec3 lo(1, 1, 0.5f), hi(2, 2, 1.5f);
    s.add_quad({lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}, Rgb(0.5));  // +z
    s.add_quad({lo.x, lo.y, lo.z}, {lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, lo.y, lo.z}, Rgb(0.5));  // -z
    s.add_quad({lo.x, lo.y, lo.z}, {lo.x, lo.y, hi.z}, {lo.x, hi.y, hi.z}, {lo.x, hi.y, lo.z}, Rgb(0.5));  // -x
    s.add_quad({hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}, {hi.x, lo.y, hi.z}, Rgb(0.5));  // +x
    s.add_quad({lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, lo.y, hi.z}, {lo.x, lo.y, hi.z}, Rgb(0.5));  // -y
    s.add_quad({lo.x, hi.y, lo.z}, {lo.x, hi.y, hi.z}, {hi.x, hi.y, hi.z}, {hi.x, hi.y, lo.z}, Rgb(0.5));  // +y
    const std::vector<uint8_t> open = open_backs(build_elements(s.input(), 0.25f).elements, s.input().face_count);
    EXPECT_FALSE(any_open(open));
}

TEST(OpenBacks, BlocksWithoutABottomStandingOnAFloorHaveNone) {
    // From behind, the blocks' faces see the floor under them, which sees nothing but their backs.
    const test::SceneArrays cornell = test::cornell_box();
    for (const float size : {0.05f, 0.1f}) {
        const Elements elements = build_elements(cornell.input(), size, ElementLimits().with_contacts()).elements;
        EXPECT_FALSE(any_open(open_backs(elements, cornell.input().face_count))) << size;
    }
}

}  // namespace
}  // namespace radiosity
