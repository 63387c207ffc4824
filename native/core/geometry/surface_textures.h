/// @file surface_textures.h
/// @brief Textured faces in the bake (internal; texture.h): each element's mean colour over its
/// UV footprint for the solve, the texel at each output corner for the colours written.
#pragma once

#include "geometry/scene.h"
#include "geometry/texture.h"

#include <glm/vec2.hpp>

#include <memory>
#include <vector>

namespace radiosity::detail {

class PolygonUv;
class TextureLevels;

/// A face's reflectance and emission at a point or over a part of it.
struct SurfaceColour {
    Rgb reflectance{0.0}, emission{0.0};
};

/// The colours of the textured faces of a scene (SceneInput::textures), at points and over parts
/// of a face. Everything is made when it is constructed: its queries may run on many threads.
class FaceTextures {
public:
    explicit FaceTextures(const SceneInput& input);
    ~FaceTextures();

    bool textured(std::size_t face) const { return uv_[face] != nullptr; }
    /// Face `face`'s colour averaged over its part with corners `points` (on the face): the exact
    /// mean of each texture over the part's UV footprint (texture_integral.h). A footprint more
    /// than 64 texels across reads a box-filtered copy of the image, halved until it is at most
    /// that (the solve's light needs no finer detail; the output corners read the image itself).
    SurfaceColour mean(std::size_t face, const Vec3* points, int count) const;
    /// The face's colour at its point `x` (the texel at x's UV).
    SurfaceColour at(std::size_t face, const Vec3& x) const;
    /// The face's colour at `uv` of its UV map.
    SurfaceColour at_uv(std::size_t face, const glm::dvec2& uv) const;

private:
    /// Face f's reflectance and emission: each its flat value, or where a texture gives it, its
    /// colour of `read(texture index)`.
    template <typename Read>
    SurfaceColour colours(std::size_t f, const Read& read) const;

    const SceneInput& input_;
    std::vector<std::unique_ptr<PolygonUv>> uv_;  ///< per face; null where no texture varies it
    std::vector<TextureLevels> levels_;           ///< per texture
};

/// Sets the reflectance and emission of the elements of textured faces to their mean over the
/// element (FaceTextures::mean). A back side takes its front's values. Progress phase "textures".
void texture_elements(const SceneInput& input, Elements& elements, const ProgressFn& progress);

/// The corner colours of textured faces with their colour at the corner itself: emission(uv) +
/// reflectance(uv) x the light arriving there (`light`, irradiance / pi at the same corners).
/// Input corners read their own UV; element corners the UV their polygon gives the vertex.
void texture_corners(const SceneInput& input, const Elements& elements, const CornerColors& light,
                     CornerColors& colors);

}  // namespace radiosity::detail
