/// @file cached_transport.cpp
/// @brief The uniform bake's transport from a BakeCache, and back (cached_transport.h).
#include "bake/cached_transport.h"

#include "common/word_hash.h"
#include "geometry/surface_textures.h"

#include <chrono>
#include <cstring>
#include <string>

namespace radiosity::detail {
namespace {

using detail::WordHash;

/// `count` values of 1 or 4 bytes, a word each, after their count (0 for none given).
template <typename T>
void hash_array(WordHash& h, const T* values, std::size_t count) {
    static_assert(sizeof(T) == 4 || sizeof(T) == 1);
    h.size(values == nullptr ? 0 : count + 1);
    if (values == nullptr) return;
    for (std::size_t i = 0; i < count; ++i) {
        uint32_t w = 0;
        std::memcpy(&w, &values[i], sizeof(T));
        h.word(w);
    }
}

void hash_settings(const BakeSettings& settings, WordHash& h) {
    h.number(settings.element_size);
    h.size(settings.limits.max_elements);
    h.number(settings.limits.max_aspect);
    h.number(settings.limits.element_size);
    h.word(uint32_t(settings.limits.cut_intersections) | uint32_t(settings.limits.cut_contacts) << 1);
    h.word(uint32_t(settings.resolution));
    h.word(uint32_t(settings.hemicube_rotations));
    h.word(uint32_t(settings.near_field.enabled));
    h.number(settings.near_field.distance);
    h.word(uint32_t(settings.near_field.sub_points));
    h.size(settings.matrix_budget_bytes);
    h.word(uint32_t(settings.solve.method == Method::Progressive));
    h.word(uint32_t(settings.merge_elements));
}

std::size_t elements_bytes(const Elements& e) {
    return e.vertices.size() * sizeof(Vec3) +
           e.size() *
               (sizeof(e.corners[0]) + 2 * sizeof(Vec3) + sizeof(float) + sizeof(int32_t) + 3 * sizeof(Rgb) + 3) +
           e.corner_vertex.size() * sizeof(int32_t);
}

/// The direct light kept: at the gather's points and on the solve's elements.
std::size_t kept_direct_bytes(const UniformTransport& t) {
    return (t.kept_direct ? t.kept_direct->bytes() : 0) + (t.kept_first_shot ? t.kept_first_shot->bytes() : 0);
}

std::size_t transport_bytes(const UniformTransport& t) {
    return elements_bytes(t.build.elements) + elements_bytes(t.clusters.elements) +
           (t.form_factors ? t.form_factors->bytes() : 0) + (t.gather_hits ? t.gather_hits->bytes() : 0) +
           kept_direct_bytes(t);
}

/// The memory budget less the elements and F: what the gather's hits and kept direct light may take.
std::size_t hits_budget(const UniformTransport& t, const BakeSettings& settings) {
    const std::size_t held = elements_bytes(t.build.elements) + elements_bytes(t.clusters.elements) +
                             (t.form_factors ? t.form_factors->bytes() : 0);
    return held < settings.matrix_budget_bytes ? settings.matrix_budget_bytes - held : 0;
}

/// Each element's reflectance and emission from its polygon's, as build_elements gives them (and
/// the textures' means over it), and the merged solve elements' reflectance from their members'.
void refresh_materials(const SceneInput& in, UniformTransport& t, const ProgressFn& progress) {
    validate_materials(in);
    Elements& elements = t.build.elements;
    for (std::size_t e = 0; e < elements.size(); ++e) {
        const std::size_t f = std::size_t(elements.polygon[e]);
        elements.reflectance[e] = Rgb(in.reflectance[3 * f], in.reflectance[3 * f + 1], in.reflectance[3 * f + 2]);
        elements.emission[e] = Rgb(in.emission[3 * f], in.emission[3 * f + 1], in.emission[3 * f + 2]);
    }
    if (in.textures) texture_elements(in, elements, progress);
    t.emitted = elements.emission;
    // Merged solve elements are of one material each (geometry/clusters.h): their members' reflectance.
    if (t.clusters.merged()) t.clusters.elements.reflectance = per_solve_element(t.clusters, elements.reflectance);
}

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

uint64_t geometry_key(const SceneInput& input, const BakeSettings& settings) {
    WordHash h;
    hash_array(h, input.positions, 3 * input.vertex_count);
    hash_array(h, input.face_offsets, input.face_count + 1);
    const std::size_t corners = input.face_offsets != nullptr ? std::size_t(input.face_offsets[input.face_count]) : 0;
    hash_array(h, input.corner_vertices, corners);
    hash_array(h, input.material, input.face_count);
    hash_array(h, input.front_only, input.face_count);
    for (std::size_t f = 0; f < input.face_count; ++f)  // emitting polygons have back sides
        h.word(uint32_t(input.emission[3 * f] > 0.0f || input.emission[3 * f + 1] > 0.0f ||
                        input.emission[3 * f + 2] > 0.0f));
    hash_settings(settings, h);
    return h.value();
}

CachedTransport acquire_transport(const SceneInput& input, const BakeSettings& settings, BakeCache& cache,
                                  const ProgressFn& progress) {
    CachedTransport cached;
    cached.key = geometry_key(input, settings);
    cached.transport = cache.take(cached.key, cached.use.not_reused);
    if (cached.transport != nullptr) {
        const auto start = std::chrono::steady_clock::now();
        refresh_materials(input, *cached.transport, progress);
        // The clusters beside a point lamp follow its distance, which the key does not hold.
        Clusters clusters = uniform_clusters(cached.transport->build, input, settings);
        cached.use.merged_again = clusters.of_element != cached.transport->clusters.of_element;
        cached.transport->seconds_elements = seconds_since(start);
        cached.transport->seconds_form_factors = 0.0;
        if (cached.use.merged_again) merge_again(*cached.transport, std::move(clusters), settings, progress);
        cached.use.reused = true;
    } else {
        cached.transport = std::make_unique<UniformTransport>(uniform_transport(input, settings, progress));
    }
    make_room_for_hits(*cached.transport, settings);
    keep_direct_light(*cached.transport);
    return cached;
}

void make_room_for_hits(UniformTransport& transport, const BakeSettings& settings) {
    if (!transport.gather_hits) transport.gather_hits = std::make_unique<GatherHits>();
    transport.gather_hits->set_budget(hits_budget(transport, settings));
}

void keep_direct_light(UniformTransport& transport) {
    if (!transport.kept_direct) transport.kept_direct = std::make_unique<KeptDirectLight>();
    const std::size_t budget = transport.gather_hits->budget();
    const std::size_t hits = transport.gather_hits->bytes();
    transport.kept_direct->set_budget(hits < budget ? budget - hits : 0);
    transport.kept_direct->begin_bake();
    if (!transport.kept_first_shot) transport.kept_first_shot = std::make_unique<KeptFirstShot>();
    transport.kept_first_shot->begin_bake(transport.solve_elements().size());
}

void release_transport(CachedTransport& cached, const BakeSettings& settings, BakeCache& cache) {
    CacheUse& use = cached.use;
    UniformTransport& transport = *cached.transport;
    if (transport.kept_direct) {
        // Within the budget with the hits, recorded beside them; else the direct light goes (it is traced again).
        transport.kept_direct->prune();
        transport.kept_first_shot->prune();
        if (transport.gather_hits->bytes() + kept_direct_bytes(transport) > transport.gather_hits->budget()) {
            transport.kept_direct->clear();
            transport.kept_first_shot->clear();
        }
    }
    if (cached.transport->gather_hits->full()) {
        use.not_kept = "the elements, form factors and the final gather's rays need more than the memory budget (" +
                       std::to_string(settings.matrix_budget_bytes >> 20) + " MB)";
        cache.clear();
        return;
    }
    use.kept = true;
    use.bytes = transport_bytes(*cached.transport);
    use.direct_bytes = kept_direct_bytes(transport);
    cache.keep(cached.key, std::move(cached.transport), use.bytes);
}

BakeResult bake_uniform_cached(const SceneInput& input, const BakeSettings& settings, BakeCache& cache,
                               const ProgressFn& progress) {
    CachedTransport cached = acquire_transport(input, settings, cache, progress);
    UniformTransport& transport = *cached.transport;
    BakeResult result;
    result.seconds_elements = transport.seconds_elements;
    result.seconds_form_factors = transport.seconds_form_factors;
    light_of_sources(input, settings, transport, transport.emitted, result, progress);
    result.build = transport.build;  // the cache keeps its own
    release_transport(cached, settings, cache);
    result.cache = std::move(cached.use);
    return result;
}

}  // namespace radiosity::detail
