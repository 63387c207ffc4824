/// @file shadow_ray.h
/// @brief Whether a point of an emitting element is unhidden from another point (internal; the
/// final gather and the small emitters' direct light).
#pragma once

#include "geometry/scene.h"
#include "visibility/ray_tracer.h"

#include <array>
#include <vector>

namespace radiosity::detail {

/// The elements' corners for a hr::Visibility, lamps' collapsed to a point: rays pass through lamps
/// (Elements::lamp), and element indices stay those of `elements`.
std::vector<std::array<int32_t, 4>> blocking_corners(const Elements& elements);

/// Whether nothing hides point `to` (on a surface of normal `to_normal`) from `from`. Hits in the
/// plane through `to` do not count: a ray that grazes that plane (from a corner to the wall beside
/// it) meets it a little early in float arithmetic, and nothing in that plane can hide a point of it.
bool unhidden(const hr::Visibility& visibility, const Elements& elements, const Vec3& from, const Vec3& to,
              const Vec3& to_normal, float scene_size);

/// unhidden from `origin`, where a surface point facing unit `normal` sends its rays
/// (hr::Visibility::lifted): the ray starts there, without unhidden's gap, so that a surface right
/// beside the point (the other face of an acute corner) hides what lies behind it. Hits in the
/// point's own plane do not count either.
bool unhidden_from_surface(const hr::Visibility& visibility, const Elements& elements, const Vec3& origin,
                           const Vec3& normal, const Vec3& to, const Vec3& to_normal, float scene_size);

}  // namespace radiosity::detail
