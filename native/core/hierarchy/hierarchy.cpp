/// @file hierarchy.cpp
/// @brief The hierarchical bake: patches and clusters, rounds of solve and refinement, the
/// conforming leaf mesh and its corner colours (hierarchy.h).
#include "hierarchy/hierarchy.h"

#include "common/report_progress.h"
#include "geometry/surface_textures.h"
#include "hierarchy/gather.h"
#include "hierarchy/lamp_detail.h"
#include "hierarchy/links.h"
#include "hierarchy/output.h"
#include "hierarchy/solve.h"
#include "transport/world_light.h"
#include "visibility/open_backs.h"

#include <tbb/parallel_for.h>

#include <chrono>
#include <cmath>
#include <optional>
#ifdef __GLIBC__
#include <malloc.h>
#endif

namespace radiosity {
namespace {

/// Frees the link lists of the nodes for which `drop(node)` holds. Freed lists stay in the
/// allocator's heap, counted in the process's memory, so the heap is handed back to the system:
/// otherwise the output stage's arrays come on top of it (at 10^6 triangles that was the bake's
/// peak: 4.0 GB, where the links phase peaks at 3.6).
template <class Drop>
void free_links(hr::Tree& tree, Drop drop) {
    tbb::parallel_for(std::size_t(0), tree.nodes.size(), [&](std::size_t n) {
        if (drop(n)) std::vector<hr::Link>().swap(tree.nodes[n].links);
    });
#ifdef __GLIBC__
    malloc_trim(0);
#endif
}

/// Per channel a / rho, 0 where rho is 0: light per unit reflectance.
Rgb per_reflectance(const Rgb& a, const Rgb& rho) {
    Rgb out(0.0);
    for (int c = 0; c < 3; ++c)
        if (rho[c] > 0.0) out[c] = a[c] / rho[c];
    return out;
}

/// The light arriving at the output's corners (irradiance / pi): the colours' light without the
/// elements' reflectance and emission. `rest`: radiance interpolated between the corners,
/// `emitted` its own emission, `corner_light` reflected light known at each corner.
CornerColors light_arriving(const Elements& out, const int32_t* material, float hard_edge_angle,
                            const std::vector<Rgb>& rest, const std::vector<Rgb>& emitted,
                            const std::vector<Rgb>& corner_light) {
    std::vector<Rgb> rest_light(out.size()), corner(corner_light.size());
    for (std::size_t e = 0; e < out.size(); ++e) {
        rest_light[e] = per_reflectance(rest[e] - emitted[e], out.reflectance[e]);
        for (int k = 0; k < 4; ++k) corner[4 * e + k] = per_reflectance(corner_light[4 * e + k], out.reflectance[e]);
    }
    return interpolate_corners(out, rest_light, material, hard_edge_angle, &corner);
}

bool finite(const Rgb& c) { return std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b); }

/// Throws NumericalError for the output stage if any element's radiance or corner colour is not
/// finite, naming the input polygon of the first such element.
void check_output(const HierarchyResult& result) {
    const Elements& out = result.output;
    for (std::size_t e = 0; e < out.size(); ++e) {
        bool ok = finite(result.output_radiance[e]);
        for (int k = 0; k < 4 && ok; ++k) ok = finite(result.colors.element_corner[4 * e + k]);
        if (!ok) throw NumericalError("output", out.polygon[e]);
    }
    for (const Rgb& c : result.colors.input_corner)
        if (!finite(c)) throw NumericalError("output", -1);
}

/// Throws NumericalError for the output stage if any element's radiance is not finite.
void check_radiance(const HierarchyResult& result) {
    for (std::size_t e = 0; e < result.output.size(); ++e)
        if (!finite(result.output_radiance[e])) throw NumericalError("output", result.output.polygon[e]);
}

/// The corners' colours from the hierarchy itself: the lamps' light (and the world's) as it is at
/// each output corner, the links' light as their geometry and the corner's rays shape it there; the
/// rest (light pushed down from clusters, and patches below the minimum size) interpolated from the
/// leaves' means (hierarchy/lamp_detail.h, hierarchy/gather.h). Frees the links.
void corner_output(hr::Tree& tree, const hr::Visibility& visibility, const HierarchySettings& settings,
                   const SceneInput& input, const hr::LeafMesh& mesh, const std::vector<Rgb>& world_light,
                   HierarchyResult& result, const ProgressFn& progress) {
    const Elements& out = result.output;
    std::vector<Rgb> corner_light = hr::lamp_light_at_corners(out, settings.lights, visibility, progress);
    std::vector<Rgb> rest(out.size());
    for (std::size_t e = 0; e < rest.size(); ++e) rest[e] = result.output_radiance[e] - mesh.lamp_part[e];
    if (!world_light.empty()) {
        const std::vector<Rgb> world_at_corners =
            detail::world_light_at_corners(out, settings.world, visibility, tree.scene_size, progress);
        for (std::size_t k = 0; k < corner_light.size(); ++k) corner_light[k] += world_at_corners[k];
        for (std::size_t e = 0; e < rest.size(); ++e) {
            const int32_t patch = tree.nodes[std::size_t(mesh.leaf[e])].patch;
            if (patch >= 0) rest[e] -= out.reflectance[e] * world_light[std::size_t(patch)];
        }
    }
    hr::gather_at_corners(tree, visibility, out, mesh.leaf, rest, corner_light, progress);
    // The rest of the links, before the corner colours' welding and sets.
    free_links(tree, [](std::size_t) { return true; });
    result.colors = interpolate_corners(out, rest, input.material, settings.hard_edge_angle, &corner_light);
    result.light_colors =
        light_arriving(out, input.material, settings.hard_edge_angle, rest, result.output_emitted, corner_light);
    // Textured faces show their texel at each corner, lit by the light arriving there.
    if (input.textures) detail::texture_corners(input, out, result.light_colors, result.colors);
}

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

void check(const HierarchySettings& s) {
    if (!(s.refine_tolerance > 0.0) || !std::isfinite(s.refine_tolerance))
        throw InputError("refine_tolerance must be positive");
    if (!(s.min_element_size > 0.0f) || !std::isfinite(s.min_element_size))
        throw InputError(
            "element_size (the hierarchy's min_element_size: its finest elements) must be a positive number of "
            "metres");
    if (!(s.tolerance > 0.0)) throw InputError("tolerance must be positive");
    if (s.max_iterations < 1 || s.max_rounds < 1) throw InputError("max_iterations and max_rounds must be at least 1");
    if (s.lamp_detail_levels < 0 || s.lamp_detail_levels > 8) throw InputError("lamp_detail_levels must be 0 to 8");
}

}  // namespace

BuildResult hierarchy_patches(const SceneInput& input, const HierarchySettings& settings) {
    check(settings);
    BuildResult patches = build_elements(input, 0.0f, settings.limits);
    const std::vector<uint8_t> open = open_backs(patches.elements, input.face_count);
    if (any_open(open)) {
        SceneInput two_sided = input;
        two_sided.open_back = open.data();
        patches = build_elements(two_sided, 0.0f, settings.limits);
    }
    // The hierarchy's visibility is its own (visibility/ray_tracer): lamps' quads block light there.
    patches.elements.lamp.clear();
    return patches;
}

/// The hierarchy of one bake: patches, tree and links; refined by RefinedHierarchy's constructor.
struct RefinedHierarchy::State {
    State(const SceneInput& input_in, const HierarchySettings& settings_in)
        : input(input_in), settings(settings_in), lights(settings_in.lights) {}

    const SceneInput& input;
    const HierarchySettings& settings;
    HierarchyResult result;
    /// Per patch, the World's light arriving (irradiance / pi, its mean over the patch): its first
    /// reflection is emitted light to the solve; the output shows it as it is at each corner instead.
    std::vector<Rgb> world_light;
    std::optional<detail::FaceTextures> textures;
    Lights lights;  ///< the tree's lamps (light() turns some off)
    std::optional<hr::Tree> tree;
    std::optional<hr::Visibility> visibility;
    std::optional<hr::Refiner> refiner;
    std::vector<Rgb> own_emission;  ///< per node, its emission without the World's first reflection (light())
};

namespace {

/// Patches, the World's light on them, the tree and its visibility.
void build_tree(RefinedHierarchy::State& s, const ProgressFn& progress) {
    // The set-up takes seconds on large scenes: report (and allow cancel) after each stage.
    auto stage = [&](std::size_t done) { detail::report_progress(progress, "elements", done, 3); };
    const auto start = Clock::now();
    HierarchyResult& result = s.result;
    result.build = hierarchy_patches(s.input, s.settings);
    if (!s.settings.world.empty()) {
        Elements& e = result.build.elements;
        s.world_light = world_irradiance(e, s.settings.world, progress);
        for (std::size_t p = 0; p < e.size(); ++p) {
            s.world_light[p] /= M_PI;
            e.emission[p] += e.reflectance[p] * s.world_light[p];
        }
    }
    if (s.input.textures) s.textures.emplace(s.input);
    stage(1);
    hr::Tree& tree =
        s.tree.emplace(result.build, s.lights, s.settings.min_element_size, s.settings.limits.max_elements);
    tree.textures = s.textures ? &*s.textures : nullptr;
    tree.world_light = s.world_light;
    stage(2);
    std::vector<std::array<int32_t, 4>> patch_corners(tree.patch_count);
    for (std::size_t p = 0; p < tree.patch_count; ++p) patch_corners[p] = tree.nodes[p].corners;
    s.visibility.emplace(std::vector<Vec3>(tree.vertices.begin(), tree.vertices.end()), patch_corners, tree.scene_size);
    stage(3);
    result.seconds_elements = seconds_since(start);
}

/// Rounds: each solves with the links it has, then refines those whose error the brighter sources
/// now make too large; a round that refines nothing ends them.
void refine(RefinedHierarchy::State& s, const ProgressFn& progress) {
    hr::Tree& tree = *s.tree;
    HierarchyResult& result = s.result;
    hr::Refiner& refiner = s.refiner.emplace(tree, *s.visibility, s.settings.max_bytes);
    hr::pull(tree);
    auto start = Clock::now();
    refiner.link_initial(progress);
    result.seconds_links += seconds_since(start);
    int round = 0;
    for (;;) {
        start = Clock::now();
        const hr::SweepResult sweep =
            hr::solve_links(tree, s.settings.tolerance, s.settings.max_iterations, result.residual_history, progress);
        result.seconds_solve += seconds_since(start);
        result.stats.iterations += sweep.sweeps;
        result.residual = sweep.residual;
        result.converged = sweep.converged;
        if (!sweep.finite)
            throw NumericalError("solve",
                                 sweep.bad_node >= 0 ? hr::input_polygon(tree, tree.nodes[sweep.bad_node]) : -1);
        ++round;
        if (round >= s.settings.max_rounds || refiner.memory_cap_reached()) break;  // capped: nothing may split
        const double scale = hr::reference_radiance(tree);
        if (!(scale > 0.0)) break;  // nothing lit: nothing to refine for
        start = Clock::now();
        const std::size_t refined = refiner.refine(s.settings.refine_tolerance * scale, progress);
        result.seconds_links += seconds_since(start);
        if (refined == 0) break;
    }
    result.stats.rounds = round;
}

/// The leaves as the output mesh, its radiance and each element's own emission (without the first
/// reflections of lamps and World it holds; `world_on`: whether the World shines).
hr::LeafMesh output_mesh(RefinedHierarchy::State& s, const std::vector<Rgb>& lamp_light, bool world_on,
                         HierarchyResult& result, const ProgressFn& progress) {
    hr::LeafMesh mesh = hr::leaf_mesh(*s.tree, s.result.build, lamp_light, progress);
    result.output = std::move(mesh.elements);
    result.output_radiance = std::move(mesh.radiance);
    const Elements& out = result.output;
    result.output_emitted.resize(out.size());
    for (std::size_t e = 0; e < out.size(); ++e) {
        result.output_emitted[e] = out.emission[e] - mesh.lamp_part[e];
        const int32_t patch = s.tree->nodes[std::size_t(mesh.leaf[e])].patch;
        if (world_on && !s.world_light.empty() && patch >= 0)
            result.output_emitted[e] -= out.reflectance[e] * s.world_light[patch];
    }
    return mesh;
}

void fill_stats(const RefinedHierarchy::State& s, const hr::LeafMesh& mesh, HierarchyStats& stats) {
    stats.patches = s.result.build.elements.size();
    stats.clusters = s.tree->cluster_count;
    stats.leaves = mesh.leaves;
    stats.nodes = s.tree->nodes.size();
    stats.links = s.refiner->links();
    stats.rays = s.refiner->rays();
    stats.leaf_cap_reached = s.tree->cap_reached();
    stats.memory_cap_reached = s.refiner->memory_cap_reached();
    stats.bytes = s.refiner->bytes();
}

/// Every element node's emission as `on` lights it: its polygon's own emission where that is on,
/// the World's first reflection where the World is; radiance starts there.
void set_sources(RefinedHierarchy::State& s, const SourceMask& on) {
    hr::Tree& tree = *s.tree;
    const Elements& patches = s.result.build.elements;
    if (s.own_emission.empty()) {
        s.own_emission.resize(tree.nodes.size(), Rgb(0.0));
        for (std::size_t i = 0; i < tree.nodes.size(); ++i) {
            const hr::Node& n = tree.nodes[i];
            if (!n.is_element()) continue;
            s.own_emission[i] = n.emission;
            if (!s.world_light.empty()) s.own_emission[i] -= n.reflectance * s.world_light[std::size_t(n.patch)];
        }
    }
    for (std::size_t i = 0; i < tree.nodes.size(); ++i) {
        hr::Node& n = tree.nodes[i];
        if (!n.is_element()) continue;
        const std::size_t polygon = std::size_t(patches.polygon[std::size_t(n.patch)]);
        n.emission = on.polygon[polygon] ? s.own_emission[i] : Rgb(0.0);
        if (on.world && !s.world_light.empty()) n.emission += n.reflectance * s.world_light[std::size_t(n.patch)];
        n.radiance = n.emission;
    }
    for (std::size_t l = 0; l < s.lights.points.size(); ++l)
        s.lights.points[l].intensity = on.point[l] ? s.settings.lights.points[l].intensity : Rgb(0.0);
    for (std::size_t l = 0; l < s.lights.suns.size(); ++l)
        s.lights.suns[l].irradiance = on.sun[l] ? s.settings.lights.suns[l].irradiance : Rgb(0.0);
}

}  // namespace

RefinedHierarchy::RefinedHierarchy(const SceneInput& input, const HierarchySettings& settings,
                                   const ProgressFn& progress)
    : state_(std::make_unique<State>(input, settings)) {
    build_tree(*state_, progress);
    refine(*state_, progress);
}

RefinedHierarchy::~RefinedHierarchy() = default;

const HierarchyResult& RefinedHierarchy::refinement() const { return state_->result; }

HierarchyResult RefinedHierarchy::output(const ProgressFn& progress) && {
    State& s = *state_;
    HierarchyResult& result = s.result;
    hr::Tree& tree = *s.tree;
    const auto start = Clock::now();
    std::vector<Rgb> lamp_light = hr::lamp_light(tree);
    const double scale = hr::reference_radiance(tree);
    // Most of the memory, before lamp detail grows the nodes and the output mesh is made.
    free_links(tree, [&](std::size_t n) { return !hr::links_gathered(tree, int32_t(n)); });
    if (!s.settings.gathered_output) {
        const float lamp_finest = std::ldexp(s.settings.min_element_size, -s.settings.lamp_detail_levels);
        result.stats.lamp_splits = hr::split_for_lamp_light(tree, *s.visibility, s.settings.refine_tolerance * scale,
                                                            lamp_finest, lamp_light, progress);
    }
    const hr::LeafMesh mesh = output_mesh(s, lamp_light, true, result, progress);
    if (s.settings.gathered_output) {
        free_links(tree, [](std::size_t) { return true; });
        check_radiance(result);
    } else {
        corner_output(tree, *s.visibility, s.settings, s.input, mesh, s.world_light, result, progress);
        check_output(result);
    }
    result.seconds_interpolate = seconds_since(start);
    fill_stats(s, mesh, result.stats);
    return std::move(result);
}

HierarchyResult RefinedHierarchy::light(const SourceMask& on, const ProgressFn& progress) {
    State& s = *state_;
    if (!s.settings.gathered_output)
        throw InputError("a hierarchy lit again by some of its sources needs its output gathered (final gather)");
    hr::Tree& tree = *s.tree;
    set_sources(s, on);
    HierarchyResult result;
    auto start = Clock::now();
    hr::pull(tree);
    const hr::SweepResult sweep =
        hr::solve_links(tree, s.settings.tolerance, s.settings.max_iterations, result.residual_history, progress);
    result.seconds_solve = seconds_since(start);
    result.stats.iterations = sweep.sweeps;
    result.residual = sweep.residual;
    result.converged = sweep.converged;
    if (!sweep.finite)
        throw NumericalError("solve", sweep.bad_node >= 0 ? hr::input_polygon(tree, tree.nodes[sweep.bad_node]) : -1);
    start = Clock::now();
    const hr::LeafMesh mesh = output_mesh(s, hr::lamp_light(tree), on.world, result, progress);
    check_radiance(result);
    result.seconds_interpolate = seconds_since(start);
    result.stats.rounds = s.result.stats.rounds;
    fill_stats(s, mesh, result.stats);
    return result;
}

HierarchyResult bake_hierarchical(const SceneInput& input, const HierarchySettings& settings,
                                  const ProgressFn& progress) {
    RefinedHierarchy refined(input, settings, progress);
    return std::move(refined).output(progress);
}

}  // namespace radiosity
