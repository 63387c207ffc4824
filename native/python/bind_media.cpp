/// @file bind_media.cpp
/// @brief The media `_core.bake` takes (voxel grids as dicts) and `_core.principled_volume` (the
/// coefficients Cycles' Principled Volume gives, per voxel).
#include "arrays.h"
#include "bindings.h"

#include "media/volume.h"

#include <pybind11/stl.h>

#include <cmath>

namespace radiosity::python {

namespace {

/// One (nz, ny, nx, 3) grid of a medium into `out`, x fastest; ValueError naming medium and key.
void read_rgb_grid(const py::dict& medium, const char* key, const std::string& name, std::array<int32_t, 3>& dims,
                   std::vector<Rgb>& out) {
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
    for (py::ssize_t d = 0; same_shape && d < density.ndim(); ++d)
        same_shape = density.shape(d) == emission_strength.shape(d);
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

std::vector<Medium> parse_media(const py::list& media) {
    std::vector<Medium> parsed;
    for (std::size_t i = 0; i < media.size(); ++i) parsed.push_back(parse_medium(media[i], i));
    return parsed;
}

void bind_media(py::module_& m) {
    using namespace pybind11::literals;
    m.def("principled_volume", &principled_volume_arrays,
          "Cycles' Principled Volume per voxel (blackbody excluded): {scattering, absorption, emission}, "
          "each shape + (3,), from density and emission_strength grids of one shape.",
          "color"_a, "density"_a, "absorption_color"_a, "emission_strength"_a, "emission_color"_a);
}

}  // namespace radiosity::python
