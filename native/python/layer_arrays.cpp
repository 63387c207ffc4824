/// @file layer_arrays.cpp
/// @brief The `layers` keyword and the layered result (layer_arrays.h).
#include "layer_arrays.h"

#include "bake_keywords.h"

#include <string>

namespace radiosity::python {
namespace {

py::object entry(const py::dict& layers, const char* name) {
    if (!layers.contains(name)) throw InputError(std::string("layers needs '") + name + "'");
    return layers[name];
}

std::vector<int32_t> indices(const py::dict& layers, const char* name, std::size_t count) {
    const Array<int32_t> array = entry(layers, name).cast<Array<int32_t>>();
    require_shape(array, (std::string("layers['") + name + "']").c_str(), py::ssize_t(count), 0);
    return std::vector<int32_t>(array.data(), array.data() + array.shape(0));
}

}  // namespace

LayerSources parse_layers(const py::dict& layers, std::size_t face_count, const py::list& lights) {
    LayerSources sources;
    sources.count = entry(layers, "count").cast<int>();
    sources.world = entry(layers, "world").cast<int32_t>();
    sources.polygon = indices(layers, "polygon", face_count);
    const std::vector<int32_t> lamp = indices(layers, "lamp", lights.size());
    for (std::size_t l = 0; l < lamp.size(); ++l) {
        const py::dict light = lights[l].cast<py::dict>();
        const bool sun = light.contains("type") && light["type"].cast<std::string>() == "SUN";
        (sun ? sources.sun : sources.point).push_back(lamp[l]);
    }
    return sources;
}

py::dict layered_result(const LayeredBake& layered) {
    py::dict out = bake_result(layered.total);
    py::list layers;
    for (std::size_t k = 0; k < layered.layers.size(); ++k) {
        const BakeResult& layer = layered.layers[k];
        py::dict d;
        d["corner_radiance"] = to_numpy(layer.colors.input_corner);
        d["element_corner_radiance"] = element_corner_array(layer.colors.element_corner);
        d["corner_light"] = to_numpy(layer.light_colors.input_corner);
        d["element_corner_light"] = element_corner_array(layer.light_colors.element_corner);
        d["element_radiance"] = to_numpy(layer.solve.radiance);
        d["element_emission"] = to_numpy(layered.layer_emission[k]);
        d["iterations"] = layer.solve.iterations;
        d["residual"] = layer.solve.residual;
        d["converged"] = layer.solve.converged;
        py::dict seconds;
        seconds["solve"] = layer.seconds_solve;
        seconds["gather"] = layer.seconds_gather;
        d["seconds"] = seconds;
        layers.append(d);
    }
    out["layers"] = layers;
    return out;
}

}  // namespace radiosity::python
