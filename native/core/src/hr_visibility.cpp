/// @file hr_visibility.cpp
/// @brief The patches as one Embree quad geometry (triangles as quads with a repeated corner).
#include "hr_visibility.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <stdexcept>

namespace radiosity::hr {

Visibility::Visibility(const std::vector<Vec3>& vertices, const std::vector<std::array<int32_t, 4>>& corners,
                       float scene_size)
    : gap_(1e-6f * scene_size), scene_size_(scene_size) {
    device_ = rtcNewDevice(nullptr);
    if (!device_) throw std::runtime_error("Embree: no device");
    scene_ = rtcNewScene(device_);
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_MEDIUM);
    rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);  // watertight: rays along a shared edge must not slip through
    RTCGeometry quads = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_QUAD);
    auto* position = static_cast<float*>(rtcSetNewGeometryBuffer(quads, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                 3 * sizeof(float), vertices.size()));
    for (std::size_t v = 0; v < vertices.size(); ++v)
        for (int a = 0; a < 3; ++a) position[3 * v + a] = vertices[v][a];
    auto* index = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(quads, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4,
                                                                 4 * sizeof(uint32_t), corners.size()));
    for (std::size_t p = 0; p < corners.size(); ++p)
        for (int k = 0; k < 4; ++k) index[4 * p + k] = static_cast<uint32_t>(corners[p][k] >= 0 ? corners[p][k] : corners[p][2]);
    rtcCommitGeometry(quads);
    rtcAttachGeometry(scene_, quads);
    rtcReleaseGeometry(quads);
    rtcCommitScene(scene_);
}

Visibility::~Visibility() {
    rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
}

bool Visibility::occluded(const Vec3& origin, const Vec3& direction, float t_near, float t_far) const {
    RTCRay ray{};  // flags, time and id 0
    ray.org_x = origin.x;
    ray.org_y = origin.y;
    ray.org_z = origin.z;
    ray.dir_x = direction.x;
    ray.dir_y = direction.y;
    ray.dir_z = direction.z;
    ray.tnear = t_near;
    ray.tfar = t_far;
    ray.mask = 0xFFFFFFFFu;
#if RADIOSITY_EMBREE_MAJOR == 4
    // Embree 4: the context became optional arguments; the defaults (incoherent rays, no filter,
    // every feature) are Embree 3's rtcInitIntersectContext defaults.
    RTCOccludedArguments arguments;
    rtcInitOccludedArguments(&arguments);
    rtcOccluded1(scene_, &ray, &arguments);
#else
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcOccluded1(scene_, &context, &ray);
#endif
    return ray.tfar < 0.0f;  // Embree marks a hit by tfar = -inf
}

bool Visibility::clear(const Vec3& from, const Vec3& to) const { return clear(from, to, 0.0f, 1.0f); }

bool Visibility::clear(const Vec3& from, const Vec3& to, float begin, float end) const {
    const Vec3 d = to - from;
    const float length = glm::length(d);
    if (!(length > 0.0f)) return true;
    const float end_gap = std::max(1e-4f, gap_ / length);  // in units of the segment
    begin = std::max(begin, end_gap);
    end = std::min(end, 1.0f - end_gap);
    if (!(begin < end)) return true;
    return !occluded(from, d, begin, end);
}

bool Visibility::clear_towards(const Vec3& from, const Vec3& direction) const {
    return !occluded(from, direction, std::max(gap_, 1e-6f), 2.0f * scene_size_ + 1.0f);
}

}  // namespace radiosity::hr
