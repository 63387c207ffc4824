/// @file test_flat_places.cpp
/// @brief The element vertices that stand for one point of a flat surface (flat_places.h): a
/// tessellated floor's faces share a place's light; a seam, a turning vertex, a cut line or
/// overlapping faces keep each vertex its own.
#include "output/flat_places.h"

#include "geometry/weld.h"
#include "testing/test_util.h"

#include <gtest/gtest.h>

#include <set>

namespace radiosity::detail {
namespace {

struct Places {
    Elements elements;
    std::vector<int32_t> place;
    std::size_t count = 0;
};

Places places_of(const test::SceneArrays& scene) {
    Places p{build_elements(scene.input(), 0.0f).elements, {}, 0};
    p.place = weld_points(p.elements.vertices, weld_tolerance(p.elements.vertices), p.count);
    return p;
}

std::size_t distinct(const std::vector<int32_t>& same) { return std::set<int32_t>(same.begin(), same.end()).size(); }

TEST(FlatPlaces, TessellatedFloorSharesEachPlace) {
    test::SceneArrays floor;
    floor.add_grid(Vec3(0.0f), Vec3(1, 0, 0), Vec3(0, 1, 0), 4, Rgb(0.5));
    const Places p = places_of(floor);
    ASSERT_EQ(p.elements.vertices.size(), 64u);  // each face its own 4
    ASSERT_EQ(p.count, 25u);
    const std::vector<uint8_t> none(p.elements.vertices.size(), 0);
    const std::vector<int32_t> same = flat_place_vertices(p.elements, p.place, p.count, none, none);
    EXPECT_EQ(distinct(same), 25u);
    for (std::size_t v = 0; v < same.size(); ++v) {
        EXPECT_EQ(p.place[std::size_t(same[v])], p.place[v]);
        EXPECT_LE(same[v], int32_t(v));
    }
    // A seam or a turning vertex at the centre (place of vertex 2 of face 5): its four keep their own.
    const std::size_t centre = std::size_t(p.place[std::size_t(p.elements.corners[5][2])]);
    std::vector<uint8_t> seam = none;
    for (std::size_t v = 0; v < seam.size(); ++v) seam[v] = std::size_t(p.place[v]) == centre;
    for (const bool as_seam : {true, false}) {
        const std::vector<int32_t> kept = as_seam ? flat_place_vertices(p.elements, p.place, p.count, seam, none)
                                                  : flat_place_vertices(p.elements, p.place, p.count, none, seam);
        EXPECT_EQ(distinct(kept), 25u + 3u);
        for (std::size_t v = 0; v < kept.size(); ++v)
            if (seam[v]) EXPECT_EQ(kept[v], int32_t(v));
    }
}

TEST(FlatPlaces, OverlappingFacesKeepTheirOwn) {
    // The same 2 x 2 grid twice (faces lying on each other): the centre's faces turn through two
    // full turns there, so its eight vertices keep their own light; the rest are shared.
    test::SceneArrays floor;
    floor.add_grid(Vec3(0.0f), Vec3(1, 0, 0), Vec3(0, 1, 0), 2, Rgb(0.5));
    floor.add_grid(Vec3(0.0f), Vec3(1, 0, 0), Vec3(0, 1, 0), 2, Rgb(0.5));
    const Places p = places_of(floor);
    const std::vector<uint8_t> none(p.elements.vertices.size(), 0);
    const std::vector<int32_t> same = flat_place_vertices(p.elements, p.place, p.count, none, none);
    EXPECT_EQ(distinct(same), 8u + 8u);  // the 8 border places shared, the centre's 8 vertices their own
}

TEST(FlatPlaces, CutLinesKeepTheirOwn) {
    // A block standing on a floor of 4 x 4 faces, off their grid: the floor is cut along its
    // footprint, and no vertex on that line shares its light.
    test::SceneArrays scene;
    scene.add_grid(Vec3(0.0f), Vec3(1, 0, 0), Vec3(0, 1, 0), 4, Rgb(0.5));
    const float lo = 0.3f, hi = 0.6f, top = 0.2f;
    scene.add_quad({lo, lo, top}, {hi, lo, top}, {hi, hi, top}, {lo, hi, top}, Rgb(0.5));
    scene.add_quad({lo, lo, 0}, {hi, lo, 0}, {hi, lo, top}, {lo, lo, top}, Rgb(0.5));
    scene.add_quad({hi, lo, 0}, {hi, hi, 0}, {hi, hi, top}, {hi, lo, top}, Rgb(0.5));
    scene.add_quad({hi, hi, 0}, {lo, hi, 0}, {lo, hi, top}, {hi, hi, top}, Rgb(0.5));
    scene.add_quad({lo, hi, 0}, {lo, lo, 0}, {lo, lo, top}, {lo, hi, top}, Rgb(0.5));
    const Elements elements = build_elements(scene.input(), 0.0f, ElementLimits().with_contacts()).elements;
    std::size_t count = 0;
    const std::vector<int32_t> place = weld_points(elements.vertices, weld_tolerance(elements.vertices), count);
    const std::vector<uint8_t> none(elements.vertices.size(), 0);
    const std::vector<int32_t> same = flat_place_vertices(elements, place, count, none, none);
    std::size_t on_line = 0;
    for (std::size_t e = 0; e < elements.size(); ++e)
        for (int k = 0; k < elements.corner_count(e); ++k)
            if ((elements.cut_edges[e] >> k) & 1u) {
                const std::size_t v = std::size_t(elements.corners[e][k]);
                EXPECT_EQ(same[v], int32_t(v));
                ++on_line;
            }
    EXPECT_GT(on_line, 0u);
}

}  // namespace
}  // namespace radiosity::detail
