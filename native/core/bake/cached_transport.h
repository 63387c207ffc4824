/// @file cached_transport.h
/// @brief The uniform bake's transport taken from a BakeCache or built, and given back after the
/// bake (internal; bake_cache.h).
#pragma once

#include "bake/bake_cache.h"
#include "bake/pipelines.h"

#include <memory>

namespace radiosity::detail {

inline constexpr const char* kHierarchyNotCached =
    "the hierarchical method refines its links from the light, so it keeps no cache";
inline constexpr const char* kMediaNotCached = "bakes with media keep no cache";

/// What the bake's elements, F and the gather's recorded hits hang on: a hash of the input's
/// geometry and of the settings that choose the elements and F (bake_cache.h).
uint64_t geometry_key(const SceneInput& input, const BakeSettings& settings);

/// The transport a cached bake lights, and what it says of the cache.
struct CachedTransport {
    std::unique_ptr<UniformTransport> transport;
    uint64_t key = 0;
    CacheUse use;
};

/// The cache's transport when its key matches (the elements' reflectance and emission taken again
/// from `input`, the form factors and hits as they are), else a new one (progress as
/// uniform_transport's). Either way with room for the gather's hits within the memory budget.
CachedTransport acquire_transport(const SceneInput& input, const BakeSettings& settings, BakeCache& cache,
                                  const ProgressFn& progress);

/// Gives `transport` recorded hits (if it has none) with room for them within the memory budget
/// that its elements and F leave.
void make_room_for_hits(UniformTransport& transport, const BakeSettings& settings);

/// Gives `transport` a kept direct light and first shot (if it has none) for a new bake, with room
/// for them within what the memory budget leaves beside the hits (kept_direct_light.h,
/// kept_first_shot.h).
void keep_direct_light(UniformTransport& transport);

/// Gives the transport to the cache when it fits the memory budget (and every ray set the gather
/// traced was recorded), else empties the cache; fills `cached.use`'s kept, bytes and not_kept.
void release_transport(CachedTransport& cached, const BakeSettings& settings, BakeCache& cache);

/// The uniform bake over the cache's transport (bake.h's bake() with a cache).
BakeResult bake_uniform_cached(const SceneInput& input, const BakeSettings& settings, BakeCache& cache,
                               const ProgressFn& progress);

}  // namespace radiosity::detail
