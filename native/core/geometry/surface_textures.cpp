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
namespace {

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

/// An image and its box-filtered halvings, made as far down as some element needs.
class TextureLevels {
public:
    explicit TextureLevels(const Texture& base) : levels_{base}, mean_(texel_mean(base)) {}

    const Rgb& mean() const { return mean_; }
    int count() const { return int(levels_.size()); }
    const Texture& level(int k) const { return levels_[std::size_t(std::min(k, count() - 1))]; }

    /// Makes the levels down to `k` (or down to one texel).
    void build_to(int k) {
        while (count() <= k) {
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

private:
    std::vector<Texture> levels_;
    std::vector<std::unique_ptr<std::vector<float>>> owned_;
    Rgb mean_;
};

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

bool textured(const std::array<Role, 2>& r, std::size_t f) { return r[0].of(f) >= 0 || r[1].of(f) >= 0; }

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

void texture_elements(const SceneInput& in, Elements& elements, const ProgressFn& progress) {
    const std::array<Role, 2> role = roles(in);
    std::vector<std::unique_ptr<PolygonUv>> uv_of(in.face_count);
    std::vector<std::size_t> todo;  // textured front elements
    for (std::size_t e = 0; e < elements.size(); ++e) {
        const std::size_t f = std::size_t(elements.polygon[e]);
        if (elements.is_back(e) || !textured(role, f)) continue;
        if (!uv_of[f]) uv_of[f] = std::make_unique<PolygonUv>(in, f);
        todo.push_back(e);
    }
    if (todo.empty()) return;

    // Each element's UV footprint, then the levels the textures need.
    std::vector<TextureLevels> levels;
    for (const Texture& t : in.textures->textures) levels.emplace_back(t);
    std::vector<std::vector<UV>> footprint(todo.size());
    for (std::size_t i = 0; i < todo.size(); ++i) {
        const std::size_t e = todo[i], f = std::size_t(elements.polygon[e]);
        for (int k = 0; k < elements.corner_count(e); ++k)
            footprint[i].push_back(uv_of[f]->at(DVec3(elements.vertices[elements.corners[e][k]])));
        for (const Role& r : role)
            if (r.of(f) >= 0) {
                TextureLevels& image = levels[std::size_t(r.of(f))];
                image.build_to(level_for(footprint[i], image.level(0)));
            }
    }

    parallel_rows("textures", todo.size(), 64, 0, progress, [&](std::size_t i) {
        const std::size_t e = todo[i], f = std::size_t(elements.polygon[e]);
        for (std::size_t which = 0; which < role.size(); ++which) {
            const Role& r = role[which];
            if (r.of(f) < 0) continue;
            const TextureLevels& image = levels[std::size_t(r.of(f))];
            const Texture& level = image.level(level_for(footprint[i], image.level(0)));
            (which == 0 ? elements.reflectance : elements.emission)[e] =
                r.colour(f, footprint_mean(level, footprint[i]), image.mean());
        }
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
    const std::array<Role, 2> role = roles(in);
    std::vector<Rgb> means;
    for (const Texture& t : in.textures->textures) means.push_back(texel_mean(t));
    // The colour of face f at `uv` times the light arriving there, plus its emission there.
    auto colour_at = [&](std::size_t f, const UV& uv, const Rgb& arriving) {
        std::array<Rgb, 2> value;
        for (std::size_t which = 0; which < role.size(); ++which) {
            const Role& r = role[which];
            const float* plain = which == 0 ? in.reflectance : in.emission;
            if (r.of(f) < 0) {
                value[which] = Rgb(plain[3 * f], plain[3 * f + 1], plain[3 * f + 2]);
                continue;
            }
            const std::size_t t = std::size_t(r.of(f));
            value[which] = r.colour(f, texel(in.textures->textures[t], float(uv.x), float(uv.y)), means[t]);
        }
        return value[1] + value[0] * arriving;
    };
    for (std::size_t f = 0; f < in.face_count; ++f) {
        if (!textured(role, f)) continue;
        for (int32_t c = in.face_offsets[f]; c < in.face_offsets[f + 1]; ++c) {
            if (elements.corner_vertex[std::size_t(c)] < 0) continue;  // a skipped polygon's corner stays black
            const float* uv = in.textures->corner_uv + 2 * std::size_t(c);
            colors.input_corner[std::size_t(c)] = colour_at(f, UV(uv[0], uv[1]), light.input_corner[std::size_t(c)]);
        }
    }
    std::vector<std::unique_ptr<PolygonUv>> uv_of(in.face_count);
    for (std::size_t e = 0; e < elements.size(); ++e) {
        const std::size_t f = std::size_t(elements.polygon[e]);
        if (elements.is_back(e) || !textured(role, f)) continue;
        if (!uv_of[f]) uv_of[f] = std::make_unique<PolygonUv>(in, f);
        for (int k = 0; k < elements.corner_count(e); ++k) {
            const UV uv = uv_of[f]->at(DVec3(elements.vertices[elements.corners[e][k]]));
            colors.element_corner[4 * e + k] = colour_at(f, uv, light.element_corner[4 * e + k]);
        }
    }
}

}  // namespace radiosity::detail
