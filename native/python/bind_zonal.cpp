/// @file bind_zonal.cpp
/// @brief `_core.bake_with_media` (bake() plus participating media on voxel grids) and
/// `_core.principled_volume` (the coefficients Cycles' Principled Volume gives, per voxel).
#include "arrays.h"
#include "bake_keywords.h"
#include "bindings.h"
#include "scene_arrays.h"

#include "media/volume.h"
#include "bake/media_bake.h"

#include <pybind11/stl.h>

#include <cmath>

namespace radiosity::python {

namespace {

/// One (nz, ny, nx, 3) grid of a medium into `out`, x fastest; ValueError naming medium and key.
void read_rgb_grid(const py::dict& medium, const char* key, const std::string& name,
                   std::array<int32_t, 3>& dims, std::vector<Rgb>& out) {
    if (!medium.contains(key)) throw InputError(name + " has no '" + key + "'");
    const auto values = medium[key].cast<Array<float>>();
    const bool first = dims[0] < 0;
    const bool ok = values.ndim() == 4 && values.shape(3) == 3 &&
                    (first || (values.shape(2) == dims[0] && values.shape(1) == dims[1] && values.shape(0) == dims[2]));
    if (!ok) {
        std::string got;
        for (py::ssize_t d = 0; d < values.ndim(); ++d) got += (d ? ", " : "") + std::to_string(values.shape(d));
        throw InputError(name + ": '" + key + "' must have shape (nz, ny, nx, 3)" +
                              (first ? "" : " like the medium's other grids") + ", got (" + got + ")");
    }
    dims = {int32_t(values.shape(2)), int32_t(values.shape(1)), int32_t(values.shape(0))};
    const float* v = values.data();
    out.resize(std::size_t(values.size() / 3));
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = Rgb(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
}

Medium parse_medium(const py::handle& entry, std::size_t index) {
    const std::string name = "medium " + std::to_string(index);
    if (!py::isinstance<py::dict>(entry)) throw InputError(name + " must be a dict");
    const auto medium = entry.cast<py::dict>();
    for (const char* key : {"origin", "voxel_size"})
        if (!medium.contains(key)) throw InputError(name + " has no '" + key + "'");
    const auto origin = medium["origin"].cast<std::vector<double>>();
    if (origin.size() != 3) throw InputError(name + ": origin must be three numbers");
    Medium m;
    m.origin = Vec3(origin[0], origin[1], origin[2]);
    m.voxel_size = medium["voxel_size"].cast<float>();
    m.dims = {-1, -1, -1};
    read_rgb_grid(medium, "extinction", name, m.dims, m.extinction);
    read_rgb_grid(medium, "albedo", name, m.dims, m.albedo);
    read_rgb_grid(medium, "emission", name, m.dims, m.emission);
    return m;
}

/// A per-voxel grid as (nz, ny, nx, 3) float32.
py::array_t<float> grid_array(const std::vector<Rgb>& values, const std::array<int32_t, 3>& dims) {
    py::array_t<float> out({py::ssize_t(dims[2]), py::ssize_t(dims[1]), py::ssize_t(dims[0]), py::ssize_t(3)});
    float* o = out.mutable_data();
    for (std::size_t i = 0; i < values.size(); ++i)
        for (int c = 0; c < 3; ++c) o[3 * i + c] = static_cast<float>(values[i][c]);
    return out;
}

py::dict bake_with_media_arrays(const Array<float>& positions, const Array<int32_t>& face_offsets,
                                const Array<int32_t>& corner_vertices, const Array<float>& reflectance,
                                const Array<float>& emission, const std::optional<Array<int32_t>>& material,
                                float element_size, int resolution, const std::string& method, double tolerance,
                                int max_iterations, float hard_edge_angle, bool ambient, const py::list& lights,
                                std::size_t matrix_budget_bytes, const py::object& progress,
                                const py::list& media_list, int zone_resolution, int grid_subdivision,
                                bool merge_uniform_zones, double over_relaxation, const std::optional<Array<uint8_t>>& front_only) {
    const SceneInput input =
        scene_input(positions, face_offsets, corner_vertices, reflectance, emission, material, front_only);
    BakeSettings settings = bake_settings(element_size, resolution, method, tolerance, max_iterations,
                                          hard_edge_angle, ambient, lights, matrix_budget_bytes);
    settings.solve.over_relaxation = over_relaxation;  // the core checks its range (ValueError)
    if (zone_resolution < 8 || zone_resolution % 2 != 0)
        throw InputError("zone_resolution must be an even number >= 8");
    if (grid_subdivision < 1) throw InputError("grid_subdivision must be at least 1");
    std::vector<Medium> media;
    for (std::size_t i = 0; i < media_list.size(); ++i) media.push_back(parse_medium(media_list[i], i));

    ProgressReporter reporter(progress);
    ZonalBakeResult result;
    try {
        py::gil_scoped_release release;
        result = bake_with_media(input, media, settings, zone_resolution, reporter.function(), grid_subdivision,
                                 merge_uniform_zones ? kDefaultMaxBlockLevel : 0);
    } catch (const Cancelled&) {
        reporter.rethrow_if_failed();
        throw;
    }

    py::dict out;
    add_bake_result(result.surfaces, out);
    const Zones& zones = result.zones;
    std::vector<Rgb> weight(zones.size());
    for (std::size_t k = 0; k < zones.size(); ++k) weight[k] = zones.weight(k);
    std::size_t voxels = 0;  // the zones there would be without merging: voxels with K_t > 0
    for (int32_t b : zones.block) voxels += std::size_t(b) * b * b;
    out["zones"] = zones.size();
    out["zones_before_merge"] = voxels;
    out["zone_radiance"] = to_numpy(result.zone_radiance);
    // What the solve used per zone, so the add-on can account for the media's power too.
    out["zone_medium"] = to_numpy(zones.medium);
    out["zone_weight"] = to_numpy(weight);
    out["zone_emitted"] = to_numpy(zones.emitted);
    out["zone_albedo"] = to_numpy(zones.albedo);
    out["zone_incident"] = to_numpy(result.zone_incident);
    py::list grids;
    for (const MediumGrids& grid : result.grids) {
        py::dict g;
        g["origin"] = py::make_tuple(grid.origin.x, grid.origin.y, grid.origin.z);
        g["voxel_size"] = grid.voxel_size;
        g["density"] = grid_array(grid.density, grid.dims);
        g["emission"] = grid_array(grid.emission, grid.dims);
        grids.append(g);
    }
    out["grids"] = grids;
    out["seconds"]["zones"] = result.seconds_zones;
    return out;
}

Rgb rgb_of(const std::vector<double>& v, const char* name) {
    if (v.size() != 3) throw InputError(std::string(name) + " must be three numbers");
    return Rgb(v[0], v[1], v[2]);
}

/// principled_volume() per voxel: density and emission_strength are grids of one shape (a grid
/// attribute times the socket's value); colours are the sockets' values.
py::dict principled_volume_arrays(const std::vector<double>& color, const Array<double>& density,
                                  const std::vector<double>& absorption_color, const Array<double>& emission_strength,
                                  const std::vector<double>& emission_color) {
    const Rgb c = rgb_of(color, "color"), a = rgb_of(absorption_color, "absorption_color"),
              e = rgb_of(emission_color, "emission_color");
    bool same_shape = density.ndim() == emission_strength.ndim();
    for (py::ssize_t d = 0; same_shape && d < density.ndim(); ++d) same_shape = density.shape(d) == emission_strength.shape(d);
    if (!same_shape) throw InputError("density and emission_strength must have the same shape");
    std::vector<py::ssize_t> shape(density.shape(), density.shape() + density.ndim());
    shape.push_back(3);
    py::array_t<float> scattering(shape), absorption(shape), emission(shape);
    float *s = scattering.mutable_data(), *ab = absorption.mutable_data(), *em = emission.mutable_data();
    const double *d = density.data(), *strength = emission_strength.data();
    for (py::ssize_t i = 0; i < density.size(); ++i) {
        const VolumeCoefficients v = principled_volume(c, d[i], a, strength[i], e);
        for (int ch = 0; ch < 3; ++ch) {
            s[3 * i + ch] = float(v.scattering[ch]);
            ab[3 * i + ch] = float(v.absorption[ch]);
            em[3 * i + ch] = float(v.emission[ch]);
        }
    }
    py::dict out;
    out["scattering"] = scattering;
    out["absorption"] = absorption;
    out["emission"] = emission;
    return out;
}

}  // namespace

void bind_zonal(py::module_& m) {
    using namespace pybind11::literals;
    m.def("bake_with_media", &bake_with_media_arrays,
          "bake() with participating media: media = [{origin, voxel_size, extinction, albedo, emission "
          "(nz, ny, nx, 3)}]. merge_uniform_zones: uniform blocks of voxels become one zone each (octree, "
          "build_zones); over_relaxation as bake() (Gauss-Seidel; 0 = the core's omega). "
          "Returns bake()'s dict plus zones (count after merging), zones_before_merge (voxels with K_t > 0), "
          "zone_radiance, zone_medium, "
          "zone_weight (4 K_t V), zone_emitted, zone_albedo, zone_incident, and per medium grids "
          "[{origin, voxel_size, density: K_t, emission: K_t J}] at grid_subdivision cells per voxel edge, J "
          "interpolated between zones keeping each zone's power (zonal_grids.h).",
          "positions"_a, "face_offsets"_a, "corner_vertices"_a, "reflectance"_a, "emission"_a,
          "material"_a = py::none(), py::kw_only(), "element_size"_a = 0.0f, "resolution"_a = 128,
          "method"_a = "gauss_seidel", "tolerance"_a = 1e-4, "max_iterations"_a = 1000,
          "hard_edge_angle"_a = 0.5235988f, "ambient"_a = false, "lights"_a = py::list(),
          "matrix_budget_bytes"_a = BakeSettings().matrix_budget_bytes, "progress"_a = py::none(),
          "media"_a = py::list(), "zone_resolution"_a = 32, "grid_subdivision"_a = 3, "merge_uniform_zones"_a = true,
          "over_relaxation"_a = 1.0, "front_only"_a = py::none());
    m.def("principled_volume", &principled_volume_arrays,
          "Cycles' Principled Volume per voxel (blackbody excluded): {scattering, absorption, emission}, "
          "each shape + (3,), from density and emission_strength grids of one shape.",
          "color"_a, "density"_a, "absorption_color"_a, "emission_strength"_a, "emission_color"_a);
}

}  // namespace radiosity::python
