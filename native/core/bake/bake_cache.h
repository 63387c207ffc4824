/// @file bake_cache.h
/// @brief What a bake learned about the geometry, kept for the next bake of the same geometry: a
/// re-bake after a lighting or material edit, or lighting variants of one level.
///
/// A uniform bake splits into what depends on the geometry alone and what depends on the sources
/// and reflectances (light is linear in its sources; Kajiya 1986). Geometry alone: the elements,
/// their form factors (the hemi-cubes see shapes, not colours), and which element each of the
/// final gather's indirect and probe rays first hits and where (gather_hits.h). The sources and
/// reflectances: the lamps' and World's first shot, the small emitters, the solve, and what the
/// gather's hits read and its shadow rays find. A bake given a cache whose geometry matches reads
/// the first three and computes the rest: the elements' reflectance and emission are taken again
/// from the input (a material's colour, an emission's strength), the solve runs on the stored F,
/// and the gather reads its recorded hits. Each source's direct light at each gathered point is kept
/// under a signature of the source (kept_direct_light.h): shadow rays are traced again only towards
/// the lamps, emitters and World that changed, with the sampling of a bake from scratch, so the
/// re-bake's colours equal a bake from scratch to the bit; so is each lamp's first shot onto the
/// elements (kept_first_shot.h).
///
/// What invalidates it (a hash, bake_cache.cpp geometry_key): the vertex positions, the polygons and
/// their corners, the material ids, which polygons emit and which emit from their front only (an
/// emitting polygon gets a back side), and the settings that choose the elements and whether F is
/// stored (element size, limits, resolution, rotations, near field, the memory budget, progressive
/// or not); and the solve's elements, merged beside a point lamp by its distance (cluster_elements):
/// a re-bake merges the faces again with its own lamps, and where that changes them it computes the
/// form factors again over the new ones (the output's elements, the gather's hits and its direct
/// light stay: they are the output's; kept first shots onto the old ones go).
/// The gather's rays are named by their own origin, seed and count, so a change of gather
/// rays needs no key: a set not recorded is traced and kept. The hierarchical method refines its
/// links from the light, and the media bake's zones see the media: neither keeps a cache.
///
/// Memory: the elements, F and the hits, within BakeSettings::matrix_budget_bytes (the memory
/// budget F is judged by); a bake whose cache would pass it bakes without keeping it and says so.
/// The direct light kept takes what the budget leaves beside them, or is let go (and traced again).
#pragma once

#include "bake/bake.h"

#include <cstdint>
#include <memory>
#include <string>

namespace radiosity {

namespace detail {
struct UniformTransport;
}

/// One bake's geometry for the next (see the top of this file). Not thread-safe: one bake at a time.
class BakeCache {
public:
    BakeCache();
    ~BakeCache();
    BakeCache(const BakeCache&) = delete;
    BakeCache& operator=(const BakeCache&) = delete;

    /// The bytes held (elements, F, the gather's hits and direct light); 0 when empty.
    std::size_t bytes() const { return bytes_; }
    bool empty() const { return transport_ == nullptr; }
    void clear();

    /// The transport kept for `key`, moved out (the cache is then empty), or null with `why_not`.
    std::unique_ptr<detail::UniformTransport> take(uint64_t key, std::string& why_not);
    /// Keeps `transport` of `bytes` for the next bake with `key`.
    void keep(uint64_t key, std::unique_ptr<detail::UniformTransport> transport, std::size_t bytes);

private:
    uint64_t key_ = 0;
    std::unique_ptr<detail::UniformTransport> transport_;
    std::size_t bytes_ = 0;
};

}  // namespace radiosity
