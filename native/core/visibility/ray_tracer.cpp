/// @file ray_tracer.cpp
/// @brief The patches as one Embree quad geometry (triangles as quads with a repeated corner).
///
/// Embree is opened privately (shared_library.h: dlopen with RTLD_LOCAL) and called through the
/// addresses dlsym gives, never linked: in Blender 4 and later, which load Embree 4 themselves, a linked module's rtc*
/// calls would bind to the Embree loaded first, whatever version it is (an Embree 3 call on Embree 4 misses every ray:
/// hierarchical bakes lose their shadows without an error). dlsym on our own handle returns our Embree's functions;
/// Embree exports nothing but its rtc* API and does not call it itself, so nothing inside it binds to the other Embree
/// either.
#include "visibility/ray_tracer.h"

#include "visibility/shared_library.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace radiosity::hr {

namespace {

/// The Embree functions used here (decltype is unevaluated: no reference to the symbols).
struct Embree {
    decltype(&::rtcNewDevice) newDevice;
    decltype(&::rtcReleaseDevice) releaseDevice;
    decltype(&::rtcNewScene) newScene;
    decltype(&::rtcReleaseScene) releaseScene;
    decltype(&::rtcSetSceneBuildQuality) setSceneBuildQuality;
    decltype(&::rtcSetSceneFlags) setSceneFlags;
    decltype(&::rtcCommitScene) commitScene;
    decltype(&::rtcNewGeometry) newGeometry;
    decltype(&::rtcSetNewGeometryBuffer) setNewGeometryBuffer;
    decltype(&::rtcCommitGeometry) commitGeometry;
    decltype(&::rtcAttachGeometry) attachGeometry;
    decltype(&::rtcReleaseGeometry) releaseGeometry;
    decltype(&::rtcOccluded1) occluded1;
    decltype(&::rtcIntersect1) intersect1;
};

Embree load_embree() {
    void* library = nullptr;
    std::string errors;
    // A package ships its own Embree beside the module (tools/packaging); opened by path, it is
    // that copy even when the host already loaded a library of the same soname.
    for (const std::string& name : {shared_library::own_folder() + RADIOSITY_EMBREE_SONAME,
                                    std::string(RADIOSITY_EMBREE_SONAME), std::string(RADIOSITY_EMBREE_PATH)}) {
        if ((library = shared_library::open(name, errors))) break;
    }
    if (!library) throw std::runtime_error("Embree: cannot load " RADIOSITY_EMBREE_SONAME ": " + errors);
    auto get = [library](auto& function, const char* name) {
        void* address = shared_library::find(library, name);
        if (!address) throw std::runtime_error(std::string("Embree: ") + RADIOSITY_EMBREE_SONAME + " has no " + name);
        function = reinterpret_cast<std::remove_reference_t<decltype(function)>>(address);
    };
    Embree e{};
    get(e.newDevice, "rtcNewDevice");
    get(e.releaseDevice, "rtcReleaseDevice");
    get(e.newScene, "rtcNewScene");
    get(e.releaseScene, "rtcReleaseScene");
    get(e.setSceneBuildQuality, "rtcSetSceneBuildQuality");
    get(e.setSceneFlags, "rtcSetSceneFlags");
    get(e.commitScene, "rtcCommitScene");
    get(e.newGeometry, "rtcNewGeometry");
    get(e.setNewGeometryBuffer, "rtcSetNewGeometryBuffer");
    get(e.commitGeometry, "rtcCommitGeometry");
    get(e.attachGeometry, "rtcAttachGeometry");
    get(e.releaseGeometry, "rtcReleaseGeometry");
    get(e.occluded1, "rtcOccluded1");
    get(e.intersect1, "rtcIntersect1");
    return e;
}

/// Loaded on first use, once (a failed load throws and is tried again next time).
const Embree& embree() {
    static const Embree api = load_embree();
    return api;
}

#if RADIOSITY_EMBREE_MAJOR == 4
using QueryContext = RTCRayQueryContext;
constexpr RTCSceneFlags kFilterInQueries = RTC_SCENE_FLAG_FILTER_FUNCTION_IN_ARGUMENTS;
#else
using QueryContext = RTCIntersectContext;
constexpr RTCSceneFlags kFilterInQueries = RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION;
#endif

/// Whether a face of geometric normal `face` (not unit; zero for a degenerate one) is parallel to a
/// point's surface of unit normal `normal`.
bool parallel(const Vec3& face, const Vec3& normal) {
    const float area = glm::length(face);  // twice the triangle's
    return area > 0.0f && std::abs(glm::dot(face, normal)) >= kParallelCosine * area;
}

/// A query from a point on a surface: Embree's context first (the filter gets its address), then
/// the point's unit normal and how far off its plane a parallel face is its own.
struct SurfaceQuery {
    QueryContext context;
    Vec3 normal;
    float tolerance;
};

/// Embree's filter for a SurfaceQuery: a hit on a face parallel to the point's own, within
/// `tolerance` of its plane, is its own face met by round-off and does not count (Embree passes the hit's
/// distance as the ray's tfar).
void skip_own_face(const RTCFilterFunctionNArguments* args) {
    const auto* query = reinterpret_cast<const SurfaceQuery*>(args->context);
    const unsigned int n = args->N;
    for (unsigned int i = 0; i < n; ++i) {
        if (args->valid[i] == 0) continue;
        const Vec3 face(RTCHitN_Ng_x(args->hit, n, i), RTCHitN_Ng_y(args->hit, n, i), RTCHitN_Ng_z(args->hit, n, i));
        const Vec3 direction(RTCRayN_dir_x(args->ray, n, i), RTCRayN_dir_y(args->ray, n, i),
                             RTCRayN_dir_z(args->ray, n, i));
        const float height = RTCRayN_tfar(args->ray, n, i) * glm::dot(direction, query->normal);
        if (parallel(face, query->normal) && std::abs(height) < query->tolerance) args->valid[i] = 0;
    }
}

/// A ray from `origin` along `direction` between t_near and t_far (flags, time and id 0).
RTCRay make_ray(const Vec3& origin, const Vec3& direction, float t_near, float t_far) {
    RTCRay ray{};
    ray.org_x = origin.x;
    ray.org_y = origin.y;
    ray.org_z = origin.z;
    ray.dir_x = direction.x;
    ray.dir_y = direction.y;
    ray.dir_z = direction.z;
    ray.tnear = t_near;
    ray.tfar = t_far;
    ray.mask = 0xFFFFFFFFu;
    return ray;
}

}  // namespace

Visibility::Visibility(const std::vector<Vec3>& vertices, const std::vector<std::array<int32_t, 4>>& corners,
                       float scene_size)
    : gap_(1e-6f * scene_size), scene_size_(scene_size) {
    const Embree& e = embree();
    device_ = e.newDevice(nullptr);
    if (!device_) throw std::runtime_error("Embree: no device");
    scene_ = e.newScene(device_);
    e.setSceneBuildQuality(scene_, RTC_BUILD_QUALITY_MEDIUM);
    // Watertight: rays along a shared edge must not slip through; filters per query (skip_own_face).
    e.setSceneFlags(scene_, RTCSceneFlags(RTC_SCENE_FLAG_ROBUST | kFilterInQueries));
    RTCGeometry quads = e.newGeometry(device_, RTC_GEOMETRY_TYPE_QUAD);
    auto* position = static_cast<float*>(e.setNewGeometryBuffer(quads, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                3 * sizeof(float), vertices.size()));
    for (std::size_t v = 0; v < vertices.size(); ++v)
        for (int a = 0; a < 3; ++a) position[3 * v + a] = vertices[v][a];
    auto* index = static_cast<uint32_t*>(e.setNewGeometryBuffer(quads, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4,
                                                                4 * sizeof(uint32_t), corners.size()));
    for (std::size_t p = 0; p < corners.size(); ++p)
        for (int k = 0; k < 4; ++k)
            index[4 * p + k] = static_cast<uint32_t>(corners[p][k] >= 0 ? corners[p][k] : corners[p][2]);
    e.commitGeometry(quads);
    e.attachGeometry(scene_, quads);
    e.releaseGeometry(quads);
    e.commitScene(scene_);
}

Visibility::~Visibility() {
    embree().releaseScene(scene_);
    embree().releaseDevice(device_);
}

bool Visibility::occluded(const Vec3& origin, const Vec3& direction, float t_near, float t_far) const {
    rays_.fetch_add(1, std::memory_order_relaxed);
    RTCRay ray = make_ray(origin, direction, t_near, t_far);
#if RADIOSITY_EMBREE_MAJOR == 4
    // Embree 4: the context became optional arguments; the defaults (incoherent rays, no filter,
    // every feature) are Embree 3's rtcInitIntersectContext defaults.
    RTCOccludedArguments arguments;
    rtcInitOccludedArguments(&arguments);
    embree().occluded1(scene_, &ray, &arguments);
#else
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    embree().occluded1(scene_, &context, &ray);
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

bool Visibility::clear_from_surface(const Vec3& from, const Vec3& normal, const Vec3& to) const {
    const Vec3 origin = lifted(from, normal);
    const Vec3 d = to - origin;
    const float length = glm::length(d);
    if (!(length > 0.0f)) return true;
    const float end = 1.0f - std::max(1e-4f, gap_ / length);
    if (!(0.0f < end)) return true;
    return !occluded(origin, d, 0.0f, end);
}

bool Visibility::clear_towards(const Vec3& from, const Vec3& direction) const {
    return !occluded(from, direction, lift(), out_of_scene());
}

bool Visibility::escapes(const Vec3& origin, const Vec3& direction) const {
    return !occluded(origin, direction, 0.0f, out_of_scene());
}

bool Visibility::escapes_from_surface(const Vec3& from, const Vec3& normal, const Vec3& direction) const {
    return escapes(lifted(from, normal), direction);
}

Visibility::Hit Visibility::first_hit(const Vec3& from, const Vec3& direction, float t_near) const {
    rays_.fetch_add(1, std::memory_order_relaxed);
    return intersect(from, direction, t_near, out_of_scene(), nullptr);
}

float Visibility::own_face_tolerance(const Vec3& from) const {
    return gap_ + 1e-6f * std::max({std::abs(from.x), std::abs(from.y), std::abs(from.z)});
}

Visibility::Hit Visibility::first_hit_from_surface(const Vec3& from, const Vec3& normal, const Vec3& direction) const {
    rays_.fetch_add(1, std::memory_order_relaxed);
    return intersect(from, direction, 0.0f, out_of_scene(), nullptr, &normal);
}

Vec3 Visibility::lifted(const Vec3& from, const Vec3& normal) const {
    const float lift = this->lift();
    float t_near = 0.01f * lift;  // past the point's own plane, whose hits the float positions scatter
    for (int beside = 0; beside < 4; ++beside) {
        Vec3 crossing;
        const Hit above = intersect(from, normal, t_near, lift, &crossing);
        if (above.patch < 0) break;
        if (glm::length(crossing) > 0.0f && !parallel(crossing, normal)) return from + (0.5f * above.distance) * normal;
        t_near = std::nextafter(above.distance, lift);  // a plane beside the point's
    }
    return from + lift * normal;
}

Visibility::Hit Visibility::intersect(const Vec3& from, const Vec3& direction, float t_near, float t_far, Vec3* normal,
                                      const Vec3* own_face) const {
    RTCRayHit query{};
    query.ray = make_ray(from, direction, t_near, t_far);
    query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    query.hit.primID = RTC_INVALID_GEOMETRY_ID;
    SurfaceQuery surface{
        {}, own_face != nullptr ? *own_face : Vec3(0.0f), own_face != nullptr ? own_face_tolerance(from) : 0.0f};
#if RADIOSITY_EMBREE_MAJOR == 4
    RTCIntersectArguments arguments;  // the defaults, as for occluded()
    rtcInitIntersectArguments(&arguments);
    if (own_face != nullptr) {
        rtcInitRayQueryContext(&surface.context);
        arguments.context = &surface.context;
        arguments.filter = skip_own_face;
        arguments.flags = RTCRayQueryFlags(arguments.flags | RTC_RAY_QUERY_FLAG_INVOKE_ARGUMENT_FILTER);
    }
    embree().intersect1(scene_, &query, &arguments);
#else
    rtcInitIntersectContext(&surface.context);
    if (own_face != nullptr) surface.context.filter = skip_own_face;
    embree().intersect1(scene_, &surface.context, &query);
#endif
    Hit hit;
    if (query.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
        hit.patch = static_cast<int32_t>(query.hit.primID);
        hit.distance = query.ray.tfar;
        hit.u = query.hit.u;
        hit.v = query.hit.v;
        if (normal != nullptr) *normal = Vec3(query.hit.Ng_x, query.hit.Ng_y, query.hit.Ng_z);
    }
    return hit;
}

}  // namespace radiosity::hr
