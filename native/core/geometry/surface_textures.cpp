/// @file surface_textures.cpp
/// @brief Element means and corner texels of textured faces (surface_textures.h).
#include "geometry/surface_textures.h"

#include "common/parallel_rows.h"
#include "geometry/polygon_geometry.h"
#include "geometry/texture_integral.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>

namespace radiosity::detail {

using UV = glm::dvec2;

/// UV at points of one polygon: the corner UVs interpolated over its triangles (a triangle as is,
/// a quad split 0-2 as Blender splits it, anything else ear-clipped), in the triangle that holds
/// the point (or is nearest to holding it, for points a hair outside).
class PolygonUv {
public:
    PolygonUv(const SceneInput& in, std::size_t f) {
        const int32_t first = in.face_offsets[f], count = in.face_offsets[f + 1] - first;
        std::vector<DVec3> p;
        std::vector<UV> uv;
        for (int32_t k = 0; k < count; ++k) {
            const float* q = in.positions + 3 * std::size_t(in.corner_vertices[first + k]);
            p.emplace_back(q[0], q[1], q[2]);
            const float* t = in.textures->corner_uv + 2 * std::size_t(first + k);
            uv.emplace_back(t[0], t[1]);
        }
        std::vector<std::array<int, 3>> triangles;
        if (count == 3)
            triangles = {{0, 1, 2}};
        else if (count == 4)
            triangles = {{0, 1, 2}, {0, 2, 3}};
        else
            triangles = triangulate(p, glm::normalize(newell(p)));
        for (const auto& t : triangles) {
            Triangle tri{p[t[0]], p[t[1]] - p[t[0]], p[t[2]] - p[t[0]], uv[t[0]], uv[t[1]], uv[t[2]], {}};
            const double a = glm::dot(tri.e1, tri.e1), b = glm::dot(tri.e1, tri.e2), c = glm::dot(tri.e2, tri.e2);
            const double det = a * c - b * b;
            if (!(det > 0.0)) continue;
            tri.inverse = {c / det, -b / det, a / det};
            triangles_.push_back(tri);
        }
    }

    UV at(const DVec3& x) const {
        UV best(0.0);
        double best_score = -std::numeric_limits<double>::infinity();
        for (const Triangle& t : triangles_) {
            const DVec3 d = x - t.origin;
            const double r1 = glm::dot(t.e1, d), r2 = glm::dot(t.e2, d);
            const double b1 = t.inverse[0] * r1 + t.inverse[1] * r2, b2 = t.inverse[1] * r1 + t.inverse[2] * r2;
            const double b0 = 1.0 - b1 - b2;
            const double score = std::min({b0, b1, b2});
            if (score > best_score) {
                best_score = score;
                best = b0 * t.uv0 + b1 * t.uv1 + b2 * t.uv2;
            }
        }
        return best;
    }

private:
    struct Triangle {
        DVec3 origin, e1, e2;
        UV uv0, uv1, uv2;
        std::array<double, 3> inverse;  ///< the symmetric inverse of the edges' Gram matrix
    };
    std::vector<Triangle> triangles_;
};

/// An image and its box-filtered halvings, down to one texel.
class TextureLevels {
public:
    explicit TextureLevels(const Texture& base) : levels_{base}, mean_(texel_mean(base)) {
        for (;;) {
            const Texture& from = levels_.back();
            if (from.width == 1 && from.height == 1) return;
            const int w = std::max(1, from.width / 2), h = std::max(1, from.height / 2);
            auto texels = std::make_unique<std::vector<float>>(3 * std::size_t(w) * std::size_t(h));
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    // The source block of texel (x, y): all of it, also for odd sizes.
                    const int x0 = x * from.width / w, x1 = (x + 1) * from.width / w;
                    const int y0 = y * from.height / h, y1 = (y + 1) * from.height / h;
                    Rgb sum(0.0);
                    for (int sy = y0; sy < y1; ++sy)
                        for (int sx = x0; sx < x1; ++sx) sum += texel_at(from, sx, sy);
                    sum /= double((x1 - x0) * (y1 - y0));
                    float* q = texels->data() + 3 * (std::size_t(y) * std::size_t(w) + std::size_t(x));
                    for (int c = 0; c < 3; ++c) q[c] = float(sum[c]);
                }
            Texture next = from;
            next.rgb = texels->data();
            next.width = w;
            next.height = h;
            next.filter = TextureFilter::Linear;
            next.srgb = false;
            owned_.push_back(std::move(texels));
            levels_.push_back(next);
        }
    }

    const Rgb& mean() const { return mean_; }
    int count() const { return int(levels_.size()); }
    const Texture& level(int k) const { return levels_[std::size_t(std::min(k, count() - 1))]; }

private:
    std::vector<Texture> levels_;
    std::vector<std::unique_ptr<std::vector<float>>> owned_;
    Rgb mean_;
};

namespace {

/// One texture role (reflectance or emission) of the faces.
struct Role {
    const int32_t* texture;
    const float* scale;
    const float* value;  ///< the faces' mean colour (SceneInput::reflectance or emission)
    double cap;          ///< kMaxTexturedReflectance, or no cap for emission

    int32_t of(std::size_t f) const { return texture ? texture[f] : -1; }

    /// The colour of face f where the texture reads `sample` (its mean `mean`).
    Rgb colour(std::size_t f, const Rgb& sample, const Rgb& mean) const {
        Rgb out;
        for (int c = 0; c < 3; ++c)
            out[c] = std::clamp(double(value[3 * f + c]) + double(scale[3 * f + c]) * (sample[c] - mean[c]), 0.0, cap);
        return out;
    }
};

std::array<Role, 2> roles(const SceneInput& in) {
    const SurfaceTextures& t = *in.textures;
    return {Role{t.reflectance_texture, t.reflectance_scale, in.reflectance, kMaxTexturedReflectance},
            Role{t.emission_texture, t.emission_scale, in.emission, std::numeric_limits<double>::infinity()}};
}

bool any_texture(const std::array<Role, 2>& r, std::size_t f) { return r[0].of(f) >= 0 || r[1].of(f) >= 0; }

/// Texels across a footprint at the level an element reads: more than this reads a halved copy.
constexpr double kMaxTexelsAcross = 64.0;

/// The level at which `uv` spans at most kMaxTexelsAcross texels of `base` in each direction.
int level_for(const std::vector<UV>& uv, const Texture& base) {
    UV low(std::numeric_limits<double>::infinity()), high(-std::numeric_limits<double>::infinity());
    for (const UV& q : uv) {
        low = glm::min(low, q);
        high = glm::max(high, q);
    }
    double across = std::max((high.x - low.x) * base.width, (high.y - low.y) * base.height);
    int level = 0;
    while (across > kMaxTexelsAcross && level < 40) {
        across *= 0.5;
        ++level;
    }
    return level;
}

}  // namespace

FaceTextures::FaceTextures(const SceneInput& in) : input_(in), uv_(in.face_count) {
    for (const Texture& t : in.textures->textures) levels_.emplace_back(t);
    const std::array<Role, 2> role = roles(in);
    for (std::size_t f = 0; f < in.face_count; ++f)
        if (any_texture(role, f)) uv_[f] = std::make_unique<PolygonUv>(in, f);
}

FaceTextures::~FaceTextures() = default;

template <typename Read>
SurfaceColour FaceTextures::colours(std::size_t f, const Read& read) const {
    const std::array<Role, 2> role = roles(input_);
    SurfaceColour out;
    for (std::size_t which = 0; which < role.size(); ++which) {
        const Role& r = role[which];
        Rgb& value = which == 0 ? out.reflectance : out.emission;
        if (r.of(f) < 0) {
            value = Rgb(r.value[3 * f], r.value[3 * f + 1], r.value[3 * f + 2]);
            continue;
        }
        const std::size_t t = std::size_t(r.of(f));
        value = r.colour(f, read(t), levels_[t].mean());
    }
    return out;
}

SurfaceColour FaceTextures::mean(std::size_t f, const Vec3* points, int count) const {
    std::vector<UV> footprint;
    for (int k = 0; k < count; ++k) footprint.push_back(uv_[f]->at(DVec3(points[k])));
    return colours(f, [&](std::size_t t) {
        const TextureLevels& image = levels_[t];
        return footprint_mean(image.level(level_for(footprint, image.level(0))), footprint);
    });
}

SurfaceColour FaceTextures::at(std::size_t f, const Vec3& x) const { return at_uv(f, uv_[f]->at(DVec3(x))); }

SurfaceColour FaceTextures::at_uv(std::size_t f, const UV& uv) const {
    return colours(f, [&](std::size_t t) { return texel(input_.textures->textures[t], float(uv.x), float(uv.y)); });
}

void texture_elements(const SceneInput& in, Elements& elements, const ProgressFn& progress) {
    const FaceTextures textures(in);
    std::vector<std::size_t> todo;  // textured front elements
    for (std::size_t e = 0; e < elements.size(); ++e)
        if (!elements.is_back(e) && textures.textured(std::size_t(elements.polygon[e]))) todo.push_back(e);
    if (todo.empty()) return;

    parallel_rows("textures", todo.size(), 64, 0, progress, [&](std::size_t i) {
        const std::size_t e = todo[i];
        std::array<Vec3, 4> corners;
        for (int k = 0; k < elements.corner_count(e); ++k) corners[k] = elements.vertices[elements.corners[e][k]];
        const SurfaceColour mean =
            textures.mean(std::size_t(elements.polygon[e]), corners.data(), elements.corner_count(e));
        elements.reflectance[e] = mean.reflectance;
        elements.emission[e] = mean.emission;
        return true;
    });

    // Back sides follow their fronts, in the fronts' order (add_back_sides).
    std::vector<std::size_t> fronts, backs;
    for (std::size_t e = 0; e < elements.size(); ++e)
        if (elements.has_twin(e)) (elements.is_back(e) ? backs : fronts).push_back(e);
    for (std::size_t k = 0; k < std::min(fronts.size(), backs.size()); ++k) {
        elements.reflectance[backs[k]] = elements.reflectance[fronts[k]];
        elements.emission[backs[k]] = elements.emission[fronts[k]];
    }
}

void texture_corners(const SceneInput& in, const Elements& elements, const CornerColors& light, CornerColors& colors) {
    const FaceTextures textures(in);
    auto lit = [](const SurfaceColour& c, const Rgb& arriving) { return c.emission + c.reflectance * arriving; };
    for (std::size_t f = 0; f < in.face_count; ++f) {
        if (!textures.textured(f)) continue;
        for (int32_t c = in.face_offsets[f]; c < in.face_offsets[f + 1]; ++c) {
            if (elements.corner_vertex[std::size_t(c)] < 0) continue;  // a skipped polygon's corner stays black
            const float* uv = in.textures->corner_uv + 2 * std::size_t(c);
            colors.input_corner[std::size_t(c)] =
                lit(textures.at_uv(f, UV(uv[0], uv[1])), light.input_corner[std::size_t(c)]);
        }
    }
    for (std::size_t e = 0; e < elements.size(); ++e) {
        const std::size_t f = std::size_t(elements.polygon[e]);
        if (elements.is_back(e) || !textures.textured(f)) continue;
        for (int k = 0; k < elements.corner_count(e); ++k)
            colors.element_corner[4 * e + k] =
                lit(textures.at(f, elements.vertices[elements.corners[e][k]]), light.element_corner[4 * e + k]);
    }
}

}  // namespace radiosity::detail
