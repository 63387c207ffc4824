/// @file hierarchy_scenes.h
/// @brief Scenes of the hierarchy measurements (docs/hierarchy.md): a room with a sharp shadow,
/// and a room of tessellated objects of any triangle count.
#pragma once

#include "testing/test_util.h"
#include "transport/lights.h"

#include <cstddef>

namespace radiosity::charts {

/// Polygons plus the lamps that light them (lamps are not polygons).
struct LitScene {
    test::SceneArrays arrays;
    Lights lights;
    float triangle_edge = 0.0f;  ///< mean edge of the objects' triangles, metres (0: no objects)
};

/// A closed 4 x 3 x 2.5 m room (walls rho 0.6), a point lamp 0.3 m under the ceiling and a
/// table (0.04 m top 0.75 m up, four legs) under it: the top throws a sharp shadow on the floor.
LitScene shadow_room();

/// A closed 10 x 10 x 3 m room with a 6 x 6 grid of objects on its floor (UV spheres, boxes,
/// tori in turn, about 0.9 m across), lit by a 1 x 1 m ceiling quad (radiance 15) and a point
/// lamp. The objects are tessellated so that the scene has about `triangles` triangles.
LitScene object_room(std::size_t triangles);

}  // namespace radiosity::charts
