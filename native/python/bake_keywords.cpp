/// @file bake_keywords.cpp
/// @brief The keyword settings of `_core.plan` and `_core.bake`, progress, and the result dict.
#include "bake_keywords.h"

#include "arrays.h"
#include "bindings.h"
#include "scene_arrays.h"

#include <pybind11/stl.h>

#include <set>
#include <string>

namespace radiosity::python {

namespace {

/// Reads keyword settings by name, each at most once, and names any left unread.
class KeywordReader {
public:
    explicit KeywordReader(const py::kwargs& keywords) : keywords_(keywords) {}

    /// Sets `target` from the keyword `name` when given; ValueError when it has the wrong type.
    template <class T>
    bool read(const char* name, T& target) {
        known_.insert(name);
        if (!keywords_.contains(name)) return false;
        try {
            target = keywords_[name].cast<T>();
        } catch (const py::cast_error&) {
            throw InputError(std::string(name) + " has the wrong type: " +
                             std::string(py::str(py::type::of(keywords_[name]).attr("__name__"))));
        }
        return true;
    }

    /// TypeError naming every keyword that is not a setting, and the settings there are.
    void reject_unknown() const {
        std::string unknown, known;
        for (const auto& item : keywords_) {
            const std::string name = py::str(item.first);
            if (!known_.count(name)) unknown += (unknown.empty() ? "" : ", ") + name;
        }
        if (unknown.empty()) return;
        for (const std::string& name : known_) known += (known.empty() ? "" : ", ") + name;
        throw py::type_error("unknown bake setting(s) " + unknown + "; the settings are " + known);
    }

private:
    const py::kwargs& keywords_;
    std::set<std::string> known_;
};

/// Sets the method: a uniform solver's, or the hierarchy's.
void read_method(KeywordReader& keywords, BakeSettings& settings) {
    std::string name = "gauss_seidel";
    keywords.read("method", name);
    if (name == "hierarchical") {
        settings.hierarchical.enabled = true;
    } else if (name == "gauss_seidel") {
        settings.solve.method = Method::GaussSeidel;
    } else if (name == "jacobi") {
        settings.solve.method = Method::Jacobi;
    } else if (name == "progressive") {
        settings.solve.method = Method::Progressive;
    } else {
        throw InputError("method must be 'gauss_seidel', 'jacobi', 'progressive' or 'hierarchical', got '" + name +
                         "'");
    }
}

void read_lamps_and_world(KeywordReader& keywords, BakeSettings& settings) {
    py::list lights;
    if (keywords.read("lights", lights)) settings.lights = parse_lights(lights);
    py::object world = py::none();
    int samples = WorldLight().samples, point_samples = WorldLight().point_samples;
    keywords.read("world", world);
    keywords.read("world_samples", samples);
    keywords.read("world_point_samples", point_samples);
    settings.world = parse_world(world, samples, point_samples);
}

void read_final_gather(KeywordReader& keywords, FinalGatherSettings& gather) {
    keywords.read("final_gather", gather.enabled);
    keywords.read("gather_rays", gather.rays);
    keywords.read("gather_shadow_rays", gather.shadow_rays);
    keywords.read("gather_field_rays", gather.field_rays);
    keywords.read("gather_cache_accuracy", gather.cache_accuracy);
    if (gather.rays < 1) throw InputError("gather_rays must be >= 1");
    if (gather.shadow_rays < 1) throw InputError("gather_shadow_rays must be >= 1");
    if (gather.field_rays < 0) throw InputError("gather_field_rays must be >= 0");
    if (!(gather.cache_accuracy >= 0.0)) throw InputError("gather_cache_accuracy must be >= 0");
}

void read_media(KeywordReader& keywords, MediaSettings& media) {
    py::list list;
    if (keywords.read("media", list)) media.media = parse_media(list);
    keywords.read("zone_resolution", media.zone_resolution);
    keywords.read("grid_subdivision", media.grid_subdivision);
    bool merge_uniform_zones = true;
    keywords.read("merge_uniform_zones", merge_uniform_zones);
    media.max_block_level = merge_uniform_zones ? kDefaultMaxBlockLevel : 0;
    if (media.zone_resolution < 8 || media.zone_resolution % 2 != 0)
        throw InputError("zone_resolution must be an even number >= 8");
    if (media.grid_subdivision < 1) throw InputError("grid_subdivision must be at least 1");
}

}  // namespace

py::array_t<float> element_corner_array(const std::vector<Rgb>& element_corner) {
    const auto count = static_cast<py::ssize_t>(element_corner.size() / 4);
    py::array_t<float> out({count, py::ssize_t{4}, py::ssize_t{3}});
    float* o = out.mutable_data();
    for (std::size_t k = 0; k < element_corner.size(); ++k)
        for (int c = 0; c < 3; ++c) o[3 * k + c] = static_cast<float>(element_corner[k][c]);
    return out;
}

namespace {

ProgressMonitor* monitor_of(const py::object& progress) {
    return py::isinstance<ProgressMonitor>(progress) ? progress.cast<ProgressMonitor*>() : nullptr;
}

py::dict hierarchy_counts(const HierarchyStats& stats) {
    py::dict out;
    out["patches"] = stats.patches;
    out["clusters"] = stats.clusters;
    out["leaves"] = stats.leaves;
    out["lamp_splits"] = stats.lamp_splits;
    out["nodes"] = stats.nodes;
    out["links"] = stats.links;
    out["rays"] = stats.rays;
    out["bytes"] = stats.bytes;
    out["rounds"] = stats.rounds;
    out["leaf_cap_reached"] = stats.leaf_cap_reached;
    out["memory_cap_reached"] = stats.memory_cap_reached;
    return out;
}

/// A per-voxel grid as (nz, ny, nx, 3) float32.
py::array_t<float> grid_array(const std::vector<Rgb>& values, const std::array<int32_t, 3>& dims) {
    py::array_t<float> out({py::ssize_t(dims[2]), py::ssize_t(dims[1]), py::ssize_t(dims[0]), py::ssize_t(3)});
    float* o = out.mutable_data();
    for (std::size_t i = 0; i < values.size(); ++i)
        for (int c = 0; c < 3; ++c) o[3 * i + c] = static_cast<float>(values[i][c]);
    return out;
}

/// Per input corner (GatherStatistics): the solution's light arriving, the indirect light read, the
/// colour's sampling variance from its own rays and from the field's noise; per element, the field's
/// error in the light it carries and the light the solve found there.
void add_gather_statistics(const GatherStatistics& statistics, py::dict& out) {
    out["solution_light"] = to_numpy(statistics.solution_light.input_corner);
    out["indirect"] = to_numpy(statistics.indirect.input_corner);
    out["variance"] = to_numpy(statistics.variance.input_corner);
    out["field_noise"] = to_numpy(statistics.field_noise.input_corner);
    out["element_field_error"] = to_numpy(statistics.element_field_error);
    out["element_reflected"] = to_numpy(statistics.element_reflected);
}

void add_media(const MediaResult& media, py::dict& out) {
    const Zones& zones = media.zones;
    std::vector<Rgb> weight(zones.size());
    for (std::size_t k = 0; k < zones.size(); ++k) weight[k] = zones.weight(k);
    std::size_t voxels = 0;  // the zones there would be without merging: voxels with K_t > 0
    for (int32_t b : zones.block) voxels += std::size_t(b) * b * b;
    out["zones"] = zones.size();
    out["zones_before_merge"] = voxels;
    out["zone_radiance"] = to_numpy(media.zone_radiance);
    // What the solve used per zone, so the add-on can account for the media's power too.
    out["zone_medium"] = to_numpy(zones.medium);
    out["zone_weight"] = to_numpy(weight);
    out["zone_emitted"] = to_numpy(zones.emitted);
    out["zone_albedo"] = to_numpy(zones.albedo);
    out["zone_incident"] = to_numpy(media.zone_incident);
    py::list grids;
    for (const MediumGrids& grid : media.grids) {
        py::dict g;
        g["origin"] = py::make_tuple(grid.origin.x, grid.origin.y, grid.origin.z);
        g["voxel_size"] = grid.voxel_size;
        g["density"] = grid_array(grid.density, grid.dims);
        g["emission"] = grid_array(grid.emission, grid.dims);
        grids.append(g);
    }
    out["grids"] = grids;
}

/// The final gather's phases (GatherCost), each {"seconds", "rays"}, in their order.
py::dict gather_phases(const GatherCost& cost) {
    py::dict phases;
    const std::pair<const char*, const GatherPhaseCost*> named[] = {{"field", &cost.field},   {"wedges", &cost.wedges},
                                                                    {"probes", &cost.probes}, {"points", &cost.points},
                                                                    {"seams", &cost.seams},   {"other", &cost.other}};
    for (const auto& [name, phase] : named) {
        py::dict one;
        one["seconds"] = phase->seconds;
        one["rays"] = phase->rays;
        phases[name] = one;
    }
    return phases;
}

}  // namespace

BakeSettings bake_settings(const py::kwargs& given) {
    KeywordReader keywords(given);
    BakeSettings settings;
    keywords.read("element_size", settings.element_size);
    keywords.read("resolution", settings.resolution);
    read_method(keywords, settings);
    keywords.read("tolerance", settings.solve.tolerance);
    keywords.read("max_iterations", settings.solve.max_iterations);
    keywords.read("ambient", settings.solve.ambient);
    keywords.read("over_relaxation", settings.solve.over_relaxation);  // the core checks its range
    keywords.read("hard_edge_angle", settings.hard_edge_angle);
    keywords.read("matrix_budget_bytes", settings.matrix_budget_bytes);
    keywords.read("near_field", settings.near_field.enabled);
    keywords.read("max_element_aspect", settings.limits.max_aspect);
    keywords.read("merge_elements", settings.merge_elements);
    settings.limits.element_size = settings.element_size;  // the hierarchy's patches bound slivers by it too
    keywords.read("max_elements", settings.limits.max_elements);
    keywords.read("hemicube_rotations", settings.hemicube_rotations);
    keywords.read("direct_emitter_area", settings.direct_emitter_area);
    keywords.read("refine_tolerance", settings.hierarchical.refine_tolerance);
    keywords.read("max_bytes", settings.hierarchical.max_bytes);
    read_lamps_and_world(keywords, settings);
    read_final_gather(keywords, settings.final_gather);
    read_media(keywords, settings.media);
    keywords.reject_unknown();
    if (settings.resolution < 8 || settings.resolution % 2 != 0)
        throw InputError("resolution must be an even number >= 8");
    if (!(settings.element_size >= 0.0f)) throw InputError("element_size must be >= 0");
    if (!(settings.solve.tolerance > 0.0)) throw InputError("tolerance must be > 0");
    if (settings.solve.max_iterations < 1) throw InputError("max_iterations must be >= 1");
    if (!(settings.direct_emitter_area >= 0.0f)) throw InputError("direct_emitter_area must be >= 0");
    return settings;
}

ProgressReporter::ProgressReporter(const py::object& progress)
    : monitor_(monitor_of(progress)),
      bridge_(monitor_ ? py::none() : progress),
      function_(monitor_ ? monitor_->function() : bridge_.function()) {}

py::dict bake_result(const BakeResult& result) {
    py::dict out;
    py::dict seconds;
    seconds["elements"] = result.seconds_elements;
    seconds["lights"] = result.seconds_lights;
    seconds["world"] = result.seconds_world;
    seconds["form_factors"] = result.seconds_form_factors;
    seconds["solve"] = result.seconds_solve;
    seconds["interpolate"] = result.seconds_interpolate;
    seconds["gather"] = result.seconds_gather;
    seconds["small_emitters"] = result.seconds_direct_emitters;

    const Elements& elements = result.build.elements;
    add_elements(result.build, out);
    out["corner_radiance"] = to_numpy(result.colors.input_corner);
    out["element_corner_radiance"] = element_corner_array(result.colors.element_corner);
    out["element_radiance"] = to_numpy(result.solve.radiance);
    // What the solve used per element, so the add-on can account for power: emission includes
    // the lamps' first reflection (rho E / pi), reflectance is the capped input.
    out["element_emission"] = to_numpy(elements.emission);
    out["element_reflectance"] = to_numpy(elements.reflectance);
    // The light arriving without the surface's colour (BakeResult::light_colors).
    out["corner_light"] = to_numpy(result.light_colors.input_corner);
    out["element_corner_light"] = element_corner_array(result.light_colors.element_corner);
    out["iterations"] = result.solve.iterations;
    out["shots"] = result.solve.shots;
    out["residual"] = result.solve.residual;
    out["residual_history"] = result.solve.residual_history;
    out["converged"] = result.solve.converged;
    out["solve_elements"] = result.solve_elements;
    out["matrix_stored"] = result.matrix_stored;
    out["matrix_nonzeros"] = result.matrix_nonzeros;
    out["matrix_bytes"] = result.matrix_bytes;
    if (result.direct_emitters > 0) out["direct_emitters"] = result.direct_emitters;
    if (result.gathered_points + result.buried_points > 0) {  // the final gather ran
        py::dict gather;
        gather["points"] = result.gathered_points;
        gather["interpolated"] = result.interpolated_points;
        gather["buried"] = result.buried_points;
        gather["phases"] = gather_phases(result.gather_cost);
        if (result.gather_statistics) add_gather_statistics(*result.gather_statistics, gather);
        out["final_gather"] = gather;
    }
    out["hierarchy"] = result.hierarchy ? py::object(hierarchy_counts(*result.hierarchy)) : py::object(py::none());
    if (result.media) {
        add_media(*result.media, out);
        seconds["zones"] = result.media->seconds_zones;
    }
    out["seconds"] = seconds;
    if (result.cache) {
        py::dict cache;
        cache["reused"] = result.cache->reused;
        cache["merged_again"] = result.cache->merged_again;
        cache["kept"] = result.cache->kept;
        cache["bytes"] = result.cache->bytes;
        cache["direct_bytes"] = result.cache->direct_bytes;
        cache["not_reused"] = result.cache->not_reused;
        cache["not_kept"] = result.cache->not_kept;
        out["cache"] = cache;
    }
    return out;
}

}  // namespace radiosity::python
