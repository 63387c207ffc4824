/// @file layers.h
/// @brief One baked layer per light group: the light of each group's sources alone, every bounce
/// included, from one bake whose elements and form factors all layers share.
///
/// Light is linear in its sources (the rendering equation is linear in emission; Kajiya 1986), so a
/// scene's light is the sum of the light each group of sources gives alone, and an artist can mix
/// the groups afterwards with any strengths (what Cycles' Light Groups render as passes). The
/// transport (the elements and their form factors, pipelines.h's UniformTransport) depends on
/// geometry and materials only and is built once; each layer then has its own sources: the
/// emission of the polygons in its group, its lamps, the world if in its group; its own first
/// shot, solve and output pass. Every sampling choice made from the sources (which lamps get all
/// their shadow rays, which elements are small emitters, the emitters the final gather aims at)
/// is made from the layer's own sources, so a layer is bit for bit the bake of the same scene with
/// only that group's sources. The total is the sum of the layers.
///
/// The hierarchical bake refines its links and leaves once, for all sources (RefinedHierarchy);
/// each layer then solves the links from its own sources and gathers the same leaves' corners with
/// them, so its total is the hierarchical bake's light, and a layer the light its group gives over
/// links refined for the whole scene.
#pragma once

#include "bake/bake.h"

#include <vector>

namespace radiosity {

/// Which layer each source of a bake lights.
struct LayerSources {
    int count = 0;                 ///< layers, each in [0, count)
    std::vector<int32_t> polygon;  ///< per input polygon: the layer of its emission (read where it emits)
    std::vector<int32_t> point;    ///< per BakeSettings::lights.points
    std::vector<int32_t> sun;      ///< per BakeSettings::lights.suns
    int32_t world = 0;             ///< the layer of BakeSettings::world
};

/// The layers and their sum.
struct LayeredBake {
    /// The sum of the layers, as bake() would return it: elements, corners, solve (iterations,
    /// residual: the layers' largest; converged: all of them), seconds (the transport's once, the
    /// rest summed over the layers).
    BakeResult total;
    /// Per layer: corners, solve and seconds of its own sources (no elements: the total's).
    std::vector<BakeResult> layers;
    /// Per layer: its elements' emission as bake() reports it (own plus its lamps' and world's first reflection).
    std::vector<std::vector<Rgb>> layer_emission;
};

/// Upper bound of the bytes the layers add to a bake of `elements` elements and `corners` input
/// corners: per layer, the corner colours and light (input and element corners) and the elements'
/// radiance and emission, in double precision.
std::size_t layer_bytes_bound(std::size_t layers, std::size_t elements, std::size_t corners);

/// Bakes each layer of `sources` over one transport (see the top of this file). InputError for
/// media, the hierarchical method without the final gather, or layer indices out of range.
/// Progress phases as bake()'s, once for the transport and once per layer for the rest. The final
/// gather's indirect and probe rays are traced by the first layer and read by the others
/// (gather_hits.h), so the layers' extra cost is their direct light, first shot, solve and the
/// reading of the hits. With `cache`, the uniform layers reuse and keep what bake() with a cache
/// does (bake_cache.h; total.cache says which).
LayeredBake bake_layers(const SceneInput& input, const BakeSettings& settings, const LayerSources& sources,
                        const ProgressFn& progress = {}, BakeCache* cache = nullptr);

}  // namespace radiosity
