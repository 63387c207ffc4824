/// @file ray_tracer.h
/// @brief Is the segment between two points free of occluders? Rays traced by Embree against
/// the patches (internal). Both sides of every patch occlude, as in the hemi-cube.
#pragma once

#include "common/types.h"

#if RADIOSITY_EMBREE_MAJOR == 4
#include <embree4/rtcore.h>
#elif RADIOSITY_EMBREE_MAJOR == 3
#include <embree3/rtcore.h>
#else
#error "RADIOSITY_EMBREE_MAJOR must be 3 or 4 (set by native/core/CMakeLists.txt)"
#endif

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <vector>

namespace radiosity::hr {

class Visibility {
public:
    /// `corners` per patch (4 ids, [3] = -1 for triangles) into `vertices`.
    Visibility(const std::vector<Vec3>& vertices, const std::vector<std::array<int32_t, 4>>& corners, float scene_size);
    ~Visibility();
    Visibility(const Visibility&) = delete;
    Visibility& operator=(const Visibility&) = delete;

    /// True when nothing lies strictly between `from` and `to` (their own surfaces excluded by a
    /// gap of 1e-6 of the scene size, at least 1e-4 of the segment). Thread-safe.
    bool clear(const Vec3& from, const Vec3& to) const;
    /// The same for the part of the segment between fractions `begin` and `end` of its length.
    bool clear(const Vec3& from, const Vec3& to, float begin, float end) const;
    /// True when nothing lies between `from`, a point on a surface facing unit `normal`, and `to`, a
    /// point on a lamp. The ray leaves from lifted(from, normal) and ends as clear()'s: a face a
    /// fraction of a millimetre from the point (its neighbour at a corner) still hides the lamp, as
    /// in Cycles, where clear()'s gap of 1e-4 of the segment would pass it.
    bool clear_from_surface(const Vec3& from, const Vec3& normal, const Vec3& to) const;
    /// Where rays from `from`, a point on a surface facing unit `normal`, leave: 1e-6 of the scene
    /// size above it, or halfway to a surface that crosses that hair (a face running on under
    /// another at a shallow angle: a level's floor strip under the foot of a ramp), so that they
    /// meet the other's back, as Cycles' rays, which leave the point itself, do. Surfaces parallel
    /// to the point's (normals within 0.8 degrees: its own plane, a face lying on it) do not count.
    Vec3 lifted(const Vec3& from, const Vec3& normal) const;
    /// True when nothing lies along `direction` (unit) from `from` out of the scene.
    bool clear_towards(const Vec3& from, const Vec3& direction) const;
    /// The same from `origin`, a point already lifted off its surface (as the World's and the
    /// final gather's rays leave theirs): without clear_towards' gap at the start, so that a wall
    /// beside the point, nearer than the gap, still hides the sky behind it.
    bool escapes(const Vec3& origin, const Vec3& direction) const;
    /// The same from `from`, a point on a surface facing unit `normal`: the ray leaves from
    /// lifted(from, normal), as clear_from_surface's do.
    bool escapes_from_surface(const Vec3& from, const Vec3& normal, const Vec3& direction) const;

    /// The first patch along `direction` (unit) from `from`, beyond `t_near`: its index (-1 for
    /// none), distance and Embree's (u, v) on it: the point is corner 0 + u (1 - 0) + v (3 - 0)
    /// on a quad's first triangle, mirrored on its second (u, v in [0, 1] over the quad); on a
    /// triangle, corner 0 + u (1 - 0) + v (2 - 0). Thread-safe.
    struct Hit {
        int32_t patch = -1;
        float distance = 0.0f;
        float u = 0.0f, v = 0.0f;
    };
    Hit first_hit(const Vec3& from, const Vec3& direction, float t_near) const;
    /// first_hit from `from`, a point on a surface facing unit `normal`, itself, as Cycles' rays
    /// leave the point and skip its own face: faces parallel to its own (normals within 0.8
    /// degrees) met within own_face_tolerance() of its plane, which round-off makes about half the
    /// rays meet at once, do not count (Embree's filter skips them). A surface a hair from the point
    /// (the floor beside a wall's foot) is seen from there, not from a lift above, and a face whose
    /// plane passes through the point is met at once.
    Hit first_hit_from_surface(const Vec3& from, const Vec3& normal, const Vec3& direction) const;
    /// The gap left at a segment's ends (1e-6 of the scene size).
    float gap() const { return gap_; }
    /// The rays traced so far (clear, clear_towards, escapes, first_hit and first_hit_from_surface:
    /// one each; lifted()'s probe is not counted), from every thread.
    std::uint64_t rays_traced() const { return rays_.load(std::memory_order_relaxed); }

private:
    /// How far above a surface point its shadow rays leave at most (lifted()), and how far
    /// clear_towards' rays skip at their start: the gap, 1e-6 of the scene's size, so that a scene
    /// scaled by any factor bakes the same.
    float lift() const { return gap_; }
    /// How far off the plane of `from`, a surface point, first_hit_from_surface's rays skip faces
    /// parallel to it: the gap, and 1e-6 of its largest coordinate (about 17 times round-off's).
    float own_face_tolerance(const Vec3& from) const;
    /// A ray length that leaves the scene from any point in it.
    float out_of_scene() const { return 2.0f * scene_size_ + 1.0f; }
    /// first_hit up to `t_far`, and the hit face's geometric normal (not unit) in `normal` if given;
    /// with `own_face`, the unit normal of the surface `from` lies on, faces parallel to it within
    /// own_face_tolerance(from) of its plane do not count (Embree skips them as it traverses).
    Hit intersect(const Vec3& from, const Vec3& direction, float t_near, float t_far, Vec3* normal,
                  const Vec3* own_face = nullptr) const;
    bool occluded(const Vec3& origin, const Vec3& direction, float t_near, float t_far) const;

    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
    float gap_ = 0.0f, scene_size_ = 0.0f;
    mutable std::atomic<std::uint64_t> rays_{0};
};

}  // namespace radiosity::hr
