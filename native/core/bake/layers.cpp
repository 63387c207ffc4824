/// @file layers.cpp
/// @brief The light groups' layers over one shared transport, and their sum (layers.h).
#include "bake/layers.h"

#include "bake/cached_transport.h"
#include "bake/output_pass.h"
#include "bake/pipelines.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace radiosity {
namespace {

void check_layer(int32_t layer, int count, const char* what, std::size_t index) {
    if (layer < 0 || layer >= count)
        throw InputError(std::string("the layer of ") + what + " " + std::to_string(index) + " is " +
                         std::to_string(layer) + ", outside 0.." + std::to_string(count - 1));
}

void check(const SceneInput& input, const BakeSettings& settings, const LayerSources& sources) {
    if (!settings.media.media.empty()) throw InputError("light group layers are not baked with media yet");
    if (settings.hierarchical.enabled && !settings.final_gather.enabled)
        throw InputError(
            "hierarchical light group layers need the final gather: its output is the same leaves in "
            "every layer");
    if (sources.count < 1) throw InputError("a layered bake needs at least one layer");
    if (sources.polygon.size() != input.face_count || sources.point.size() != settings.lights.points.size() ||
        sources.sun.size() != settings.lights.suns.size())
        throw InputError("the layers must name one layer per polygon (" + std::to_string(input.face_count) +
                         "), per point or spot lamp (" + std::to_string(settings.lights.points.size()) +
                         ") and per sun (" + std::to_string(settings.lights.suns.size()) + ")");
    for (std::size_t f = 0; f < sources.polygon.size(); ++f)
        check_layer(sources.polygon[f], sources.count, "polygon", f);
    for (std::size_t l = 0; l < sources.point.size(); ++l) check_layer(sources.point[l], sources.count, "lamp", l);
    for (std::size_t l = 0; l < sources.sun.size(); ++l) check_layer(sources.sun[l], sources.count, "sun", l);
    check_layer(sources.world, sources.count, "the world", 0);
}

/// The scene as one layer's sources see it: the other layers' polygons emit nothing (their flat
/// emission and their emission textures).
class LayerInput {
public:
    LayerInput(const SceneInput& input, const LayerSources& sources, int32_t layer) : input_(input) {
        emission_.assign(input.emission, input.emission + 3 * input.face_count);
        for (std::size_t f = 0; f < input.face_count; ++f)
            if (sources.polygon[f] != layer) std::fill_n(emission_.begin() + 3 * f, 3, 0.0f);
        input_.emission = emission_.data();
        if (input.textures && input.textures->emission_texture) {
            emission_texture_.assign(input.textures->emission_texture,
                                     input.textures->emission_texture + input.face_count);
            for (std::size_t f = 0; f < input.face_count; ++f)
                if (sources.polygon[f] != layer) emission_texture_[f] = -1;
            textures_ = *input.textures;
            textures_.emission_texture = emission_texture_.data();
            input_.textures = &textures_;
        }
    }
    LayerInput(const LayerInput&) = delete;
    LayerInput& operator=(const LayerInput&) = delete;

    const SceneInput& input() const { return input_; }

private:
    SceneInput input_;
    std::vector<float> emission_;
    std::vector<int32_t> emission_texture_;
    SurfaceTextures textures_;
};

/// The settings with only the layer's lamps and, if it is the world's layer, the world.
BakeSettings layer_settings(const BakeSettings& settings, const LayerSources& sources, int32_t layer) {
    BakeSettings s = settings;
    s.lights.points.clear();
    s.lights.suns.clear();
    for (std::size_t l = 0; l < sources.point.size(); ++l)
        if (sources.point[l] == layer) s.lights.points.push_back(settings.lights.points[l]);
    for (std::size_t l = 0; l < sources.sun.size(); ++l)
        if (sources.sun[l] == layer) s.lights.suns.push_back(settings.lights.suns[l]);
    if (sources.world != layer) s.world = WorldLight();
    return s;
}

/// Each element's own emission where its polygon is in the layer, else zero.
std::vector<Rgb> layer_emitted(const detail::UniformTransport& transport, const LayerSources& sources, int32_t layer) {
    const Elements& elements = transport.build.elements;
    std::vector<Rgb> emitted(elements.size(), Rgb(0.0));
    for (std::size_t e = 0; e < elements.size(); ++e)
        if (sources.polygon[std::size_t(elements.polygon[e])] == layer) emitted[e] = transport.emitted[e];
    return emitted;
}

void add(std::vector<Rgb>& sum, const std::vector<Rgb>& part) {
    if (sum.empty()) sum.assign(part.size(), Rgb(0.0));
    for (std::size_t i = 0; i < part.size(); ++i) sum[i] += part[i];
}

void add(CornerColors& sum, const CornerColors& part) {
    add(sum.element_corner, part.element_corner);
    add(sum.input_corner, part.input_corner);
}

/// Standard deviations add (Minkowski): the variance of a sum of layers whose noise is correlated
/// (the same rays) is at most the square of the sum of their standard deviations.
void add_variance(std::vector<Rgb>& sum, const std::vector<Rgb>& part) {
    if (sum.empty()) sum.assign(part.size(), Rgb(0.0));
    for (std::size_t i = 0; i < part.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const double deviation = std::sqrt(sum[i][c]) + std::sqrt(part[i][c]);
            sum[i][c] = deviation * deviation;
        }
}

void add(GatherStatistics& sum, const GatherStatistics& part) {
    add(sum.solution_light, part.solution_light);
    add(sum.indirect, part.indirect);
    add_variance(sum.variance.element_corner, part.variance.element_corner);
    add_variance(sum.variance.input_corner, part.variance.input_corner);
    add_variance(sum.field_noise.element_corner, part.field_noise.element_corner);
    add_variance(sum.field_noise.input_corner, part.field_noise.input_corner);
    add(sum.element_field_error, part.element_field_error);
    add(sum.element_reflected, part.element_reflected);
}

/// The total's residual is at most the layers' largest: the residuals add, and so do the layers'
/// emitted power, which is never negative.
void add(SolveResult& sum, const SolveResult& part, bool first) {
    add(sum.radiance, part.radiance);
    sum.iterations = std::max(sum.iterations, part.iterations);
    sum.shots += part.shots;
    sum.residual = std::max(sum.residual, part.residual);
    sum.converged = (first || sum.converged) && part.converged;
    sum.seconds += part.seconds;
}

void add(GatherPhaseCost& sum, const GatherPhaseCost& part) {
    sum.seconds += part.seconds;
    sum.rays += part.rays;
}

/// Every layer's gather: the phases' seconds and rays add; which points were gathered, interpolated
/// or buried depends on the geometry alone, the same in every layer.
void add(GatherCost& sum, const GatherCost& part) {
    for (auto phase : {&GatherCost::other, &GatherCost::field, &GatherCost::wedges, &GatherCost::probes,
                       &GatherCost::points, &GatherCost::seams})
        add(sum.*phase, part.*phase);
    sum.gathered = part.gathered;
    sum.interpolated = part.interpolated;
    sum.buried = part.buried;
}

void add_layer(BakeResult& total, const BakeResult& layer, bool first) {
    add(total.solve, layer.solve, first);
    add(total.colors, layer.colors);
    add(total.light_colors, layer.light_colors);
    total.solve_elements = layer.solve_elements;
    total.matrix_stored = layer.matrix_stored;
    total.matrix_nonzeros = layer.matrix_nonzeros;
    total.matrix_bytes = layer.matrix_bytes;
    total.seconds_lights += layer.seconds_lights;
    total.seconds_world += layer.seconds_world;
    total.seconds_solve += layer.seconds_solve;
    total.seconds_interpolate += layer.seconds_interpolate;
    total.seconds_gather += layer.seconds_gather;
    total.seconds_direct_emitters += layer.seconds_direct_emitters;
    total.direct_emitters = std::max(total.direct_emitters, layer.direct_emitters);
    // Whether a corner is gathered or buried depends on the geometry alone: the same in every layer.
    total.gathered_points = layer.gathered_points;
    total.interpolated_points = layer.interpolated_points;
    add(total.gather_cost, layer.gather_cost);
    if (layer.hierarchy) total.hierarchy = layer.hierarchy;
    total.buried_points = layer.buried_points;
    if (layer.gather_statistics)
        add(total.gather_statistics ? *total.gather_statistics : total.gather_statistics.emplace(),
            *layer.gather_statistics);
}

/// Which sources shine in layer `layer`.
SourceMask layer_mask(const LayerSources& sources, int32_t layer) {
    SourceMask on;
    for (const int32_t l : sources.polygon) on.polygon.push_back(l == layer);
    for (const int32_t l : sources.point) on.point.push_back(l == layer);
    for (const int32_t l : sources.sun) on.sun.push_back(l == layer);
    on.world = sources.world == layer;
    return on;
}

/// The layers over one refined hierarchy: its links and leaves refined for all sources, each
/// layer's links solved from its own and its leaves' corners gathered with its own.
LayeredBake hierarchical_layers(const SceneInput& input, const BakeSettings& settings, const LayerSources& sources,
                                const ProgressFn& progress) {
    const HierarchySettings h = detail::hierarchy_settings(settings);
    RefinedHierarchy refined(input, h, progress);
    // The same leaves in every layer: the first layer's gather records its hits, within what the
    // nodes and links leave of the budget.
    const std::size_t held = refined.refinement().stats.bytes;
    GatherHits hits(held < settings.matrix_budget_bytes ? settings.matrix_budget_bytes - held : 0);
    LayeredBake layered;
    std::vector<Rgb> emission;
    for (int32_t k = 0; k < sources.count; ++k) {
        HierarchyResult lit = refined.light(layer_mask(sources, k), progress);
        const std::vector<Rgb> emitted = std::move(lit.output_emitted);
        BakeResult& layer = layered.layers.emplace_back(detail::as_bake_result(std::move(lit)));
        const LayerInput layer_input(input, sources, k);
        detail::output_pass(layer_input.input(), layer_settings(settings, sources, k), layer.build.elements, emitted,
                            layer, progress, {&hits});
        add_layer(layered.total, layer, k == 0);
        layered.layer_emission.push_back(layer.build.elements.emission);
        add(emission, layer.build.elements.emission);
        layer.gather_statistics.reset();
        if (k == 0) layered.total.build.elements = std::move(layer.build.elements);
        layer.build = BuildResult();
    }
    const HierarchyResult& refinement = refined.refinement();
    layered.total.build.skipped = refinement.build.skipped;
    layered.total.build.elements.emission = std::move(emission);
    layered.total.seconds_elements = refinement.seconds_elements;
    layered.total.seconds_form_factors = refinement.seconds_links;
    layered.total.seconds_solve += refinement.seconds_solve;
    return layered;
}

}  // namespace

std::size_t layer_bytes_bound(std::size_t layers, std::size_t elements, std::size_t corners) {
    // Colours and light at the input and the 4 element corners, radiance and emission per element.
    return layers * (2 * corners + 2 * 4 * elements + 2 * elements) * sizeof(Rgb);
}

namespace {

/// The transport the layers share: the cache's (cached_transport.h) or one of their own, with room
/// for the gather's hits, which every layer after the first reads.
detail::CachedTransport layers_transport(const SceneInput& input, const BakeSettings& settings, BakeCache* cache,
                                         const ProgressFn& progress) {
    if (cache != nullptr) return detail::acquire_transport(input, settings, *cache, progress);
    detail::CachedTransport own;
    own.transport = std::make_unique<detail::UniformTransport>(detail::uniform_transport(input, settings, progress));
    detail::make_room_for_hits(*own.transport, settings);
    return own;
}

}  // namespace

LayeredBake bake_layers(const SceneInput& input, const BakeSettings& settings, const LayerSources& sources,
                        const ProgressFn& progress, BakeCache* cache) {
    check(input, settings, sources);
    if (settings.hierarchical.enabled) {
        LayeredBake layered = hierarchical_layers(input, settings, sources, progress);
        if (cache != nullptr) {
            cache->clear();
            layered.total.cache = CacheUse{false, false, 0, detail::kHierarchyNotCached, detail::kHierarchyNotCached};
        }
        return layered;
    }
    detail::CachedTransport cached = layers_transport(input, settings, cache, progress);
    detail::UniformTransport& transport = *cached.transport;
    LayeredBake layered;
    layered.total.seconds_elements = transport.seconds_elements;
    layered.total.seconds_form_factors = transport.seconds_form_factors;
    std::vector<Rgb> emission;
    for (int32_t k = 0; k < sources.count; ++k) {
        const LayerInput layer_input(input, sources, k);
        BakeResult& layer = layered.layers.emplace_back();
        detail::light_of_sources(layer_input.input(), layer_settings(settings, sources, k), transport,
                                 layer_emitted(transport, sources, k), layer, progress);
        add_layer(layered.total, layer, k == 0);
        layered.layer_emission.push_back(transport.build.elements.emission);
        add(emission, transport.build.elements.emission);
        layer.gather_statistics.reset();  // the total's error estimate holds them
    }
    layered.total.build = transport.build;
    layered.total.build.elements.emission = std::move(emission);
    if (cache != nullptr) {
        detail::release_transport(cached, settings, *cache);
        layered.total.cache = std::move(cached.use);
    }
    return layered;
}

}  // namespace radiosity
