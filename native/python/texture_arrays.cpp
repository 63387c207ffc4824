/// @file texture_arrays.cpp
/// @brief Parsing of the `textures` keyword (texture_arrays.h).
#include "texture_arrays.h"

#include <string>

namespace radiosity::python {

namespace {

TextureFilter parse_filter(const std::string& name) {
    if (name == "closest") return TextureFilter::Closest;
    if (name == "linear") return TextureFilter::Linear;
    throw InputError("texture filter must be 'closest' or 'linear', got '" + name + "'");
}

TextureExtension parse_extension(const std::string& name) {
    if (name == "repeat") return TextureExtension::Repeat;
    if (name == "extend") return TextureExtension::Extend;
    if (name == "clip") return TextureExtension::Clip;
    if (name == "mirror") return TextureExtension::Mirror;
    throw InputError("texture extension must be 'repeat', 'extend', 'clip' or 'mirror', got '" + name + "'");
}

/// The per-face index and scale arrays of one role, when the dict has them.
void parse_role(const py::dict& in, const char* index_key, const char* scale_key, py::ssize_t faces,
                std::optional<Array<int32_t>>& index, std::optional<Array<float>>& scale) {
    if (!in.contains(index_key)) return;
    index = in[index_key].cast<Array<int32_t>>();
    require_shape(*index, index_key, faces, 0);
    if (!in.contains(scale_key))
        throw InputError(std::string("textures: '") + index_key + "' needs '" + scale_key + "'");
    scale = in[scale_key].cast<Array<float>>();
    require_shape(*scale, scale_key, faces, 3);
}

}  // namespace

std::optional<TextureArrays> parse_textures(const py::object& textures, py::ssize_t faces, py::ssize_t corners) {
    if (textures.is_none()) return std::nullopt;
    const py::dict in = textures.cast<py::dict>();
    TextureArrays out;
    if (!in.contains("corner_uv")) throw InputError("textures: 'corner_uv' is missing");
    out.corner_uv = in["corner_uv"].cast<Array<float>>();
    require_shape(out.corner_uv, "corner_uv", corners, 2);
    if (in.contains("images"))
        for (const py::handle image : in["images"].cast<py::list>()) {
            const py::dict entry = image.cast<py::dict>();
            Array<float> rgb = entry["rgb"].cast<Array<float>>();
            if (rgb.ndim() != 3 || rgb.shape(2) != 3 || rgb.shape(0) < 1 || rgb.shape(1) < 1)
                throw InputError("texture " + std::to_string(out.images.size()) +
                                 ": rgb must have shape (height, width, 3), bottom row first");
            Texture t;
            t.height = static_cast<int>(rgb.shape(0));
            t.width = static_cast<int>(rgb.shape(1));
            t.filter = parse_filter(entry.contains("filter") ? entry["filter"].cast<std::string>() : "linear");
            t.extension =
                parse_extension(entry.contains("extension") ? entry["extension"].cast<std::string>() : "repeat");
            t.srgb = entry.contains("srgb") && entry["srgb"].cast<bool>();
            out.images.push_back(std::move(rgb));
            out.view.textures.push_back(t);
        }
    parse_role(in, "reflectance_texture", "reflectance_scale", faces, out.reflectance_texture, out.reflectance_scale);
    parse_role(in, "emission_texture", "emission_scale", faces, out.emission_texture, out.emission_scale);
    // The views, once the arrays have their final places.
    for (std::size_t k = 0; k < out.images.size(); ++k) out.view.textures[k].rgb = out.images[k].data();
    out.view.corner_uv = out.corner_uv.data();
    if (out.reflectance_texture) {
        out.view.reflectance_texture = out.reflectance_texture->data();
        out.view.reflectance_scale = out.reflectance_scale->data();
    }
    if (out.emission_texture) {
        out.view.emission_texture = out.emission_texture->data();
        out.view.emission_scale = out.emission_scale->data();
    }
    return out;
}

}  // namespace radiosity::python
