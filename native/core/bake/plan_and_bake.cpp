/// @file plan_and_bake.cpp
/// @brief plan() and bake(): the pipeline the settings choose, and its result in one shape.
#include "bake/bake_cache.h"
#include "bake/cached_transport.h"
#include "bake/media_bake.h"
#include "bake/output_pass.h"
#include "bake/pipelines.h"
#include "visibility/open_backs.h"
#include "visibility/resolution.h"
#include "visibility/sight_distance.h"
#include "visibility/sizes_by_sight.h"

#include <utility>

namespace radiosity {

namespace {

bool with_media(const BakeSettings& settings) { return !settings.media.media.empty(); }

void check(const BakeSettings& settings) {
    if (settings.hierarchical.enabled && with_media(settings))
        throw InputError("the hierarchical method does not bake media (fog, smoke) yet: use a uniform method");
}

BakeResult as_bake_result(ZonalBakeResult&& zonal) {
    BakeResult result = std::move(zonal.surfaces);
    result.media = static_cast<MediaResult&&>(std::move(zonal));
    return result;
}

}  // namespace

namespace detail {

BakeResult as_bake_result(HierarchyResult&& hierarchy) {
    BakeResult result;
    result.build = BuildResult{std::move(hierarchy.output), std::move(hierarchy.build.skipped), {}};
    result.solve.radiance = std::move(hierarchy.output_radiance);
    result.solve.iterations = hierarchy.stats.iterations;
    result.solve.residual = hierarchy.residual;
    result.solve.residual_history = std::move(hierarchy.residual_history);
    result.solve.converged = hierarchy.converged;
    result.solve.seconds = hierarchy.seconds_solve;
    result.colors = std::move(hierarchy.colors);
    result.light_colors = std::move(hierarchy.light_colors);
    result.matrix_bytes = hierarchy.stats.bytes;
    result.seconds_elements = hierarchy.seconds_elements;
    result.seconds_form_factors = hierarchy.seconds_links;  // lamps are link sources: no lamp phase
    result.seconds_solve = hierarchy.seconds_solve;
    result.seconds_interpolate = hierarchy.seconds_interpolate;
    result.hierarchy = hierarchy.stats;
    result.solve_elements = result.build.elements.size();
    return result;
}

BuildResult uniform_elements(const SceneInput& input, const BakeSettings& settings, const ProgressFn& progress) {
    BuildResult build = build_elements(input, settings.element_size, settings.limits, progress);
    ElementLimits limits = settings.limits;
    if (settings.element_size > 0.0f)
        limits.polygon_edge = sizes_by_sight(build.elements, input.face_count, settings.element_size);
    const std::vector<uint8_t> open = open_backs(build.elements, input.face_count);
    if (!any_size(limits.polygon_edge) && !any_open(open)) return build;
    SceneInput two_sided = input;
    two_sided.open_back = open.data();
    return build_elements(two_sided, settings.element_size, limits);  // the first build, as long, told the progress
}

Clusters uniform_clusters(const BuildResult& build, const SceneInput& input, const BakeSettings& settings) {
    std::vector<Vec3> lamps;
    for (const PointLight& lamp : settings.lights.points) lamps.push_back(lamp.position);
    return cluster_elements(build.elements, input, settings.merge_elements ? settings.element_size : 0.0f, lamps,
                            build.polygon_edge);
}

BuildResult media_elements(const SceneInput& input, const BakeSettings& settings) {
    BuildResult build = build_elements(input, settings.element_size);
    build.elements.lamp.clear();
    return build;
}

HierarchySettings hierarchy_settings(const BakeSettings& settings) {
    HierarchySettings h;
    h.min_element_size = settings.element_size;
    h.refine_tolerance = settings.hierarchical.refine_tolerance;
    h.max_bytes = settings.hierarchical.max_bytes;
    h.tolerance = settings.solve.tolerance;
    h.max_iterations = settings.solve.max_iterations;
    h.hard_edge_angle = settings.hard_edge_angle;
    h.limits = settings.limits;
    h.lights = settings.lights;
    h.world = settings.world;
    h.gathered_output = settings.final_gather.enabled;  // the output pass gathers the leaves' corners
    return h;
}

}  // namespace detail

namespace {

/// The distances the hemi-cube's resolution is judged from (bake.h's BakePlan).
void distances(BakePlan& plan) {
    plan.sight_distance = sight_distance(plan.build.elements);
    plan.resolution_distance = resolution_distance(plan.sight_distance, half_diagonal(plan.build.elements));
}

}  // namespace

BakePlan plan(const SceneInput& input, const BakeSettings& settings) {
    check(settings);
    BakePlan plan;
    if (settings.hierarchical.enabled) {
        plan.build = hierarchy_patches(input, detail::hierarchy_settings(settings));
        plan.solve_element_area = plan.build.elements.area;
        plan.solve_element_polygon = plan.build.elements.polygon;
        plan.solve_elements = plan.solve_element_area.size();
        distances(plan);
        return plan;
    }
    plan.build =
        with_media(settings) ? detail::media_elements(input, settings) : detail::uniform_elements(input, settings);
    distances(plan);
    if (with_media(settings)) {  // the media bake always stores its matrix (or refuses to bake beyond the budget)
        plan.solve_element_area = plan.build.elements.area;
        plan.solve_element_polygon = plan.build.elements.polygon;
        plan.solve_elements = plan.solve_element_area.size();
        plan.matrix_bytes_bound = matrix_bytes_bound(plan.solve_elements, settings.resolution);
        plan.matrix_bytes_planned = plan.matrix_bytes_bound;
        plan.matrix_stored = true;
        return plan;
    }
    const Clusters clusters = detail::uniform_clusters(plan.build, input, settings);
    const Elements& solved = clusters.merged() ? clusters.elements : plan.build.elements;
    plan.solve_element_area = solved.area;
    plan.solve_element_polygon = solved.polygon;
    plan.solve_elements = solved.size();
    plan.matrix_bytes_bound = matrix_bytes_bound(plan.solve_elements, settings.resolution);
    plan.matrix_bytes_planned = detail::planned_matrix_bytes(solved, settings);
    plan.matrix_stored = detail::fits_matrix_budget(plan.matrix_bytes_planned, settings);
    return plan;
}

namespace {

/// The hierarchical bake, and the output pass when it gathers.
BakeResult bake_hierarchy(const SceneInput& input, const BakeSettings& settings, const ProgressFn& progress) {
    HierarchyResult hierarchy = bake_hierarchical(input, detail::hierarchy_settings(settings), progress);
    const std::vector<Rgb> emitted = std::move(hierarchy.output_emitted);
    BakeResult result = detail::as_bake_result(std::move(hierarchy));
    if (settings.final_gather.enabled)
        detail::output_pass(input, settings, result.build.elements, emitted, result, progress);
    return result;
}

/// A bake whose method keeps nothing in the cache: it empties the cache and says why.
BakeResult not_cached(BakeResult&& result, BakeCache* cache, const char* why) {
    if (cache == nullptr) return std::move(result);
    cache->clear();
    result.cache = CacheUse{false, false, 0, why, why};
    return std::move(result);
}

}  // namespace

BakeResult bake(const SceneInput& input, const BakeSettings& settings, const ProgressFn& progress, BakeCache* cache) {
    check(settings);
    if (settings.hierarchical.enabled)
        return not_cached(bake_hierarchy(input, settings, progress), cache, detail::kHierarchyNotCached);
    if (with_media(settings)) {
        const MediaSettings& m = settings.media;
        BakeResult result = as_bake_result(bake_with_media(input, m.media, settings, m.zone_resolution, progress,
                                                           m.grid_subdivision, m.max_block_level));
        result.solve_elements = result.build.elements.size();
        return not_cached(std::move(result), cache, detail::kMediaNotCached);
    }
    if (cache != nullptr) return detail::bake_uniform_cached(input, settings, *cache, progress);
    return detail::bake_uniform(input, settings, progress);
}

}  // namespace radiosity
